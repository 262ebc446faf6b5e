"""The floor: a bare script that reads a generated lattice crane file, assembles K and M
with scipy and calls eigsh. No checks, no generality beyond what the generated models
use (truss members with lumped mass, point masses, one massless rope hanging a load);
`cranefe study performance` compares cranefe's whole process with this one's, and
cranefe's assembly (from the read file to K and M) with `assemble` here.

    python -m cranefe.studies._floor MODEL.yaml COUNT
"""

import json
import sys
import time


def read(path):
    """The YAML document of `path`, read with PyYAML's C loader."""
    import yaml
    with open(path) as fh:
        return yaml.load(fh, Loader=yaml.CSafeLoader)


def assemble(d):
    """K and M (scipy CSC) on the free coordinates of the read document `d`."""
    import numpy as np
    import scipy.sparse as sp
    names = list(d["nodes"])
    index = {n: i for i, n in enumerate(names)}
    X = np.array([d["nodes"][n] for n in names], dtype=float)
    n = 3 * len(names)
    rows, cols, kv, mdiag = [], [], [], np.zeros(n)
    for m in d["members"].values():
        p = np.array([[index[a], index[b]] for a, b in m["pairs"]])
        dx = X[p[:, 1]] - X[p[:, 0]]
        L = np.linalg.norm(dx, axis=1)
        e = dx / L[:, None]
        k = m["E"] * m["A"] / L
        dofs = np.hstack([3 * p[:, :1] + np.arange(3), 3 * p[:, 1:] + np.arange(3)])
        B = np.hstack([-e, e])
        ke = k[:, None, None] * B[:, :, None] * B[:, None, :]
        rows.append(np.repeat(dofs, 6, axis=1).ravel())
        cols.append(np.tile(dofs, (1, 6)).ravel())
        kv.append(ke.ravel())
        np.add.at(mdiag, dofs.ravel(), np.repeat(m["rho"] * m["A"] * L / 2, 6))
    for node, mass in d["masses"].items():
        mdiag[3 * index[node]:3 * index[node] + 3] += mass
    free = np.ones(n, dtype=bool)
    for g in d["ground"]:
        free[3 * index[g]:3 * index[g] + 3] = False
    for r in d["ropes"].values():          # [top, {node: load, falls: f}]: vertical spring
        top, hook = r["path"][0], r["path"][1]["node"]
        f = r["path"][1]["falls"]
        L = f * np.linalg.norm(X[index[hook]] - X[index[top]])
        k = f * f * r["EA"] / L
        a, b = 3 * index[top] + 2, 3 * index[hook] + 2
        rows.append(np.array([a, a, b, b]))
        cols.append(np.array([a, b, a, b]))
        kv.append(np.array([k, -k, -k, k]))
        free[3 * index[hook]:3 * index[hook] + 2] = False   # the load moves along its rope
    K = sp.coo_matrix((np.concatenate(kv), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(n, n)).tocsc()[free][:, free]
    M = sp.diags(mdiag[free]).tocsc()
    return K, M


def main(path, count):
    t0 = time.perf_counter()
    import numpy as np
    import scipy.sparse.linalg as spla
    d = read(path)
    t1 = time.perf_counter()
    K, M = assemble(d)
    t2 = time.perf_counter()
    w2 = spla.eigsh(K, k=count, M=M, sigma=0, which="LM", return_eigenvectors=False)
    t3 = time.perf_counter()
    f_hz = np.sqrt(np.sort(w2)) / (2 * np.pi)
    print(json.dumps({"frequency_hz": f_hz.tolist(), "dofs": K.shape[0],
                      "timings_s": {"read": t1 - t0, "assemble": t2 - t1, "solve": t3 - t2}}))


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]))
