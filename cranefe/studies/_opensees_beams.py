"""OpenSeesPy solving the heavy beam tower crane of `cranefe study structure` (planar):
elastic beam-column elements with P-Delta transformation and consistent mass, a static
gravity step (self-weight as uniform element loads, point-mass weights as nodal loads),
then the eigenvalues of the tangent about that state. An optional peer (pip install
'cranefe[bench]'); run in its own process, without cranefe on its path:

    python -m cranefe.studies._opensees_beams MODEL.yaml COUNT

Reads the model file cranefe reads (plane: xz; z becomes OpenSees' Y) and prints JSON.
"""

import json
import sys


def main(path, count):
    import numpy as np
    import openseespy.opensees as ops
    import yaml
    with open(path) as fh:
        d = yaml.load(fh, Loader=yaml.CSafeLoader)
    g = 9.81
    xy = {n: (float(c[0]), float(c[2])) for n, c in d["nodes"].items()}
    tags = {}
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)

    def node(name, x, y):
        tags[name] = len(tags) + 1
        ops.node(tags[name], x, y)
        return tags[name]

    for n, (x, y) in xy.items():
        node(n, x, y)
    for n in d["ground"]:
        ops.fix(tags[n], 1, 1, 1)
    ops.geomTransf("PDelta", 1)
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    tag = 0
    for name, m in d["members"].items():
        chain = m["nodes"]
        k = int(m.get("elements", 1))
        w = m["rho"] * m["A"]                          # mass per length
        for a, b in zip(chain[:-1], chain[1:]):
            pa, pb = np.array(xy[a]), np.array(xy[b])
            ids = [tags[a]] + [node(f"{name}.{a}-{b}.{j}", *(pa + (pb - pa) * j / k))
                               for j in range(1, k)] + [tags[b]]
            e = (pb - pa) / np.linalg.norm(pb - pa)
            for i, j in zip(ids[:-1], ids[1:]):
                tag += 1
                ops.element("elasticBeamColumn", tag, i, j, m["A"], m["E"], m["Iy"], 1,
                            "-mass", w, "-cMass")
                # weight per length (0, -w g): local y = (-e_y, e_x), local x = e
                ops.eleLoad("-ele", tag, "-type", "-beamUniform", -w * g * e[0],
                            -w * g * e[1])
    for n, mass in d.get("masses", {}).items():
        ops.mass(tags[n], mass, mass, 0.0)
        ops.load(tags[n], 0.0, -mass * g, 0.0)
    ops.system("BandGeneral")
    ops.numberer("RCM")
    ops.constraints("Plain")
    ops.test("NormDispIncr", 1e-12, 50)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    if ops.analyze(1) != 0:
        raise SystemExit("OpenSees: the gravity step did not converge")
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()
    ops.system("BandGeneral")
    ops.numberer("RCM")
    ops.constraints("Plain")
    w2 = np.array(ops.eigen("-fullGenLapack", count))
    print(json.dumps({"frequency_hz": (np.sqrt(np.sort(w2)) / (2 * np.pi)).tolist(),
                      "elements": tag}))


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]))
