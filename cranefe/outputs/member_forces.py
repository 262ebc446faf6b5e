"""Section forces at the ends of beam members in the static state."""

import numpy as np

from ..assembly.beams import beam_dofs, beam_local_matrices

FORCE_NAMES = ("N", "Vy", "Vz", "T", "My", "Mz")


def beam_end_forces(model, layout, mm, u):
    """Section forces at both ends of every beam element, local axes, (nb, 2, 6):
    (N, Vy, Vz, T, My, Mz) on the face whose outward normal is +x at the second end and
    the same resultants at the first (the negated force the first node exerts). The force
    the nodes exert on an element is K_e u_e - f_e, f_e = M_e g the consistent (or lumped)
    load of its own weight, as assembled; with consistent loads the cubic element's end
    forces are those of the exact solution."""
    b = np.flatnonzero(mm.beam)
    k, m, axes = beam_local_matrices(model, layout, mm, b)
    R = np.zeros((len(b), 12, 12))
    for blk in range(4):
        R[:, 3 * blk:3 * blk + 3, 3 * blk:3 * blk + 3] = axes
    u_loc = np.einsum("kij,kj->ki", R, u[beam_dofs(layout, mm, b)])
    g_loc = np.einsum("kij,j->ki", R, np.concatenate([model.gravity, np.zeros(3)] * 2))
    F = np.einsum("kij,kj->ki", k, u_loc) - np.einsum("kij,kj->ki", m, g_loc)
    return np.stack([-F[:, :6], F[:, 6:]], axis=1), b


def member_end_forces(model, layout, mm, u):
    """JSON-ready section forces at the ends of each node-to-node piece of each beam
    member: [{"member", "from", "to", "start": {N..Mz}, "end": {N..Mz}}, ...]."""
    if mm is None or not mm.beam.any():
        return []
    S, b = beam_end_forces(model, layout, mm, u)
    row = {int(e): k for k, e in enumerate(b)}
    out = []
    for mi, mem in enumerate(model.members):
        if mem.type != "beam":
            continue
        els = np.flatnonzero(mm.member == mi)
        n = mem.elements
        for p in range(len(els) // n):
            first, last = els[p * n], els[(p + 1) * n - 1]
            out.append({"member": mem.name,
                        "from": model.node_names[mm.node[first, 0]],
                        "to": model.node_names[mm.node[last, 1]],
                        "start": dict(zip(FORCE_NAMES, map(float, S[row[first], 0]))),
                        "end": dict(zip(FORCE_NAMES, map(float, S[row[last], 1])))})
    return out
