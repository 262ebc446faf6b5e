"""OpenSeesPy building and solving the same generated lattice crane (an optional
benchmark dependency: pip install 'cranefe[bench]'; Debian needs libblas3).

    python -m cranefe.studies._opensees MODEL.yaml COUNT
"""

import json
import sys
import time


def main(path, count):
    t0 = time.perf_counter()
    import numpy as np
    import openseespy.opensees as ops
    import yaml
    with open(path) as fh:
        d = yaml.load(fh, Loader=yaml.CSafeLoader)
    t1 = time.perf_counter()
    names = list(d["nodes"])
    index = {n: i + 1 for i, n in enumerate(names)}
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 3)
    for n in names:
        ops.node(index[n], *map(float, d["nodes"][n]))
    for g in d["ground"]:
        ops.fix(index[g], 1, 1, 1)
    tag = 0
    for mat, m in enumerate(d["members"].values(), start=1):
        ops.uniaxialMaterial("Elastic", mat, m["E"])
        for a, b in m["pairs"]:
            tag += 1           # lumped mass: rho here is mass per unit length
            ops.element("Truss", tag, index[a], index[b], m["A"], mat, "-rho",
                        m["rho"] * m["A"])
    for node, mass in d["masses"].items():
        ops.mass(index[node], mass, mass, mass)
    mat = len(d["members"]) + 1
    for r in d["ropes"].values():          # the rope as one truss of the same stiffness
        top, hook = r["path"][0], r["path"][1]["node"]
        f = r["path"][1]["falls"]
        span = np.linalg.norm(np.subtract(d["nodes"][hook], d["nodes"][top]))
        k = f * f * r["EA"] / (f * span)
        ops.uniaxialMaterial("Elastic", mat, 1.0)
        tag += 1
        ops.element("Truss", tag, index[top], index[hook], k * span, mat)
        ops.fix(index[hook], 1, 1, 0)      # the load moves along its rope
        mat += 1
    t2 = time.perf_counter()
    w2 = np.array(ops.eigen(count))
    t3 = time.perf_counter()
    f_hz = np.sqrt(np.sort(w2)) / (2 * np.pi)
    print(json.dumps({"frequency_hz": f_hz.tolist(),
                      "timings_s": {"read": t1 - t0, "build": t2 - t1, "solve": t3 - t2}}))


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]))
