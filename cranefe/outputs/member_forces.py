"""Section forces and extreme-fibre stresses at the ends of members: in the static state,
per mode and as envelopes of transient runs (docs/structure.md, "Member forces").

For every member element the forces are those the nodes exert on it in its local axes,
(N, Vy, Vz, T, My, Mz) at both ends (N tension +; at each end the resultants on the face
whose outward normal is +x, so a piece's two ends read as a beam diagram):

- beams: `K_e u_e - f_e`, f_e = M_e g the consistent (or lumped) load of the element's own
  weight where the state carries gravity (the static state and a run about it), none for
  a mode shape;
- trusses: N = EA/l e . (u_2 - u_1), the same at both ends.

The normal stress at the extreme fibres: sigma = N/A +- |My|/Wy +- |Mz|/Wz (the largest
and smallest), with the section's elastic moduli (`Wy`, `Wz` of the member, from its
`section`); exact for sections whose extreme fibres in y and z meet at a corner (I, H,
box, rectangle), on the safe side for round ones and angles. A truss: N/A.
"""

from dataclasses import dataclass, field

import numpy as np

from ..assembly.beams import beam_dofs, beam_local_matrices
from ..assembly.springs import member_geometry

FORCE_NAMES = ("N", "Vy", "Vz", "T", "My", "Mz")
STRESS_NAMES = ("sigma_max", "sigma_min")


def _rotations(axes):
    """blockdiag(axes x 4), (ne, 12, 12)."""
    R = np.zeros((len(axes), 12, 12))
    for blk in range(4):
        R[:, 3 * blk:3 * blk + 3, 3 * blk:3 * blk + 3] = axes
    return R


def element_end_forces(model, layout, mm, U, weight=True):
    """Section forces at both ends of every member element, (k, ne, 2, 6), for the
    primitive displacement vectors U (n_prim,) or (k, n_prim); `weight`: whether the
    states carry gravity (the elements' own weight loads subtracted)."""
    U = np.atleast_2d(np.asarray(U, dtype=float))
    out = np.zeros((len(U), len(mm.member), 2, 6))
    b = np.flatnonzero(mm.beam)
    if len(b):
        k, m, axes = beam_local_matrices(model, layout, mm, b)
        R = _rotations(axes)
        u_loc = np.einsum("eij,kej->kei", R, U[:, beam_dofs(layout, mm, b)])
        F = np.einsum("eij,kej->kei", k, u_loc)
        if weight:
            g_loc = np.einsum("eij,j->ei", R, np.concatenate([model.gravity, np.zeros(3)] * 2))
            F = F - np.einsum("eij,ej->ei", m, g_loc)[None]
        out[:, b, 0] = -F[:, :, :6]
        out[:, b, 1] = F[:, :, 6:]
    t = np.flatnonzero(~mm.beam)
    if len(t):
        e, l = member_geometry(model, layout, mm, t)
        EA = np.array([m.E * m.A for m in model.members])[mm.member[t]]
        du = U[:, 6 * mm.node[t, 1, None] + np.arange(3)] - \
            U[:, 6 * mm.node[t, 0, None] + np.arange(3)]
        axial = out[..., 0]                      # a view: (k, ne, 2)
        axial[:, t, :] = (EA / l * np.einsum("kei,ei->ke", du, e))[:, :, None]
    return out


def extreme_stresses(model, mm, F):
    """(..., ne, 2, 2): (sigma_max, sigma_min) at both ends of every member element for
    section forces F (..., ne, 2, 6); nan for a beam whose member has no `Wy` (or, in 3D,
    no `Wz`)."""
    per = {k: np.array([float(getattr(m, k)) for m in model.members])[mm.member]
           for k in ("A", "Wy", "Wz")}
    beam = mm.beam
    def term(M, W, missing):
        ok = (W > 0)[:, None]
        return np.where(ok, np.abs(M) / np.where(W > 0, W, 1.0)[:, None], missing)
    by = term(F[..., 4], per["Wy"], np.nan)
    bz = term(F[..., 5], per["Wz"], 0.0 if model.planar else np.nan)
    bend = np.where(beam[:, None], by + bz, 0.0)
    axial = F[..., 0] / per["A"][:, None]
    return np.stack([axial + bend, axial - bend], axis=-1)


def pieces(model, mm):
    """The node-to-node pieces of the members: [(member name, type, from, to, first
    element, last element)], in the order of the members."""
    out = []
    for mi, mem in enumerate(model.members):
        els = np.flatnonzero(mm.member == mi)
        n = mem.elements if mem.type == "beam" else 1
        for p in range(len(els) // n):
            first, last = int(els[p * n]), int(els[(p + 1) * n - 1])
            out.append((mem.name, mem.type, model.node_names[mm.node[first, 0]],
                        model.node_names[mm.node[last, 1]], first, last))
    return out


def element_members(model, mm):
    """The member name of every element (ne,)."""
    return tuple(model.members[int(k)].name for k in mm.member)


def _num(v):
    return None if not np.isfinite(v) else float(v)


def _end(F, S):
    d = dict(zip(FORCE_NAMES, map(float, F)))
    d.update(zip(STRESS_NAMES, map(_num, S)))
    return d


@dataclass
class MemberForces:
    """Section forces (k, ne, 2, 6) and extreme-fibre stresses (k, ne, 2, 2) of k states
    (the static state, modes, or output times) at both ends of every member element
    (ne, the order of `dofs.members`), with their pieces for reports. `kind`: static |
    modes | envelope (then k = 2: the minimum and the maximum over the run's output
    times, component by component); `scale`: how modes are scaled; `element_member`:
    the member of each element (ne,)."""

    kind: str
    forces: np.ndarray
    stress: np.ndarray
    pieces: list
    scale: dict = field(default_factory=dict)
    element_member: tuple = ()

    def piece_list(self, state):
        """JSON list of the pieces' start and end forces of state `state`."""
        return [{"member": m, "type": t, "from": a, "to": b,
                 "start": _end(self.forces[state, i, 0], self.stress[state, i, 0]),
                 "end": _end(self.forces[state, j, 1], self.stress[state, j, 1])}
                for m, t, a, b, i, j in self.pieces]

    def to_dict(self):
        """The `member_forces` document of `--json`."""
        if self.kind == "static":
            return self.piece_list(0)
        if self.kind == "modes":
            return {"scale": self.scale,
                    "modes": [{"index": k + 1, "pieces": self.piece_list(k)}
                              for k in range(len(self.forces))]}
        lo, hi = self.piece_list(0), self.piece_list(1)
        return {"over": "output times", "pieces": [
            {**{k: p[k] for k in ("member", "type", "from", "to")},
             **{end: {"min": p[end], "max": q[end]} for end in ("start", "end")}}
            for p, q in zip(lo, hi)]}

    def peak_stresses(self):
        """Per member the largest |sigma| over its elements, both ends, both fibres and
        every state: [{"member", "sigma_abs_max_Pa", "state", "element", "end"}] (state
        1-based: the mode, the output time, or min 1 / max 2 of an envelope); a member
        whose stresses are all nan (no Wy / Wz) has sigma_abs_max_Pa None."""
        S = np.abs(self.stress)                              # (k, ne, 2, 2)
        members = self.element_member or tuple(
            m for m, _, _, _, i, j in self.pieces for _ in range(j - i + 1))
        out = []
        for name in dict.fromkeys(members):
            els = np.flatnonzero(np.array(members) == name)
            sub = S[:, els]
            if not np.isfinite(sub).any():
                out.append({"member": name, "sigma_abs_max_Pa": None, "state": None,
                            "element": None, "end": None})
                continue
            k, e, end, _ = np.unravel_index(np.nanargmax(sub), sub.shape)
            out.append({"member": name, "sigma_abs_max_Pa": float(sub[k, e, end].max()),
                        "state": int(k) + 1, "element": int(els[e]),
                        "end": ("start", "end")[end]})
        return out

    def summary(self):
        """The short document `cranefe show` prints: kind, scale, states and the
        largest |sigma| of each member."""
        return {"kind": self.kind, "scale": self.scale, "states": len(self.forces),
                "elements": int(self.forces.shape[1]), "peak_stress": self.peak_stresses()}

    def table(self):
        """Text of `summary()`: one line per member."""
        state = {"modes": "mode", "envelope": "state (1 min, 2 max)",
                 "times": "output time"}.get(self.kind, "state")
        lines = [f"member forces ({self.kind}"
                 + (f", {self.scale['normalisation']}"
                    + (f" {self.scale['amplitude_m']:g} m" if "amplitude_m" in self.scale
                       else "") if self.scale else "")
                 + f"): {self.forces.shape[1]} elements, largest |sigma| per member",
                 f"  {'member':<16} {'|sigma| MPa':>12}  {state}, element, end"]
        for p in self.peak_stresses():
            if p["sigma_abs_max_Pa"] is None:
                lines.append(f"  {p['member']:<16} {'-':>12}  (no Wy / Wz)")
            else:
                lines.append(f"  {p['member']:<16} {p['sigma_abs_max_Pa'] / 1e6:>12.6g}  "
                             f"{p['state']}, {p['element']}, {p['end']}")
        return "\n".join(lines)

    def cell_values(self, state):
        """(ne, 8): per element the end value of larger magnitude of N .. Mz, and the
        larger sigma_max / smaller sigma_min of its two ends (ParaView cell data)."""
        F = self.forces[state]
        pick = np.where(np.abs(F[:, 0]) >= np.abs(F[:, 1]), F[:, 0], F[:, 1])
        S = self.stress[state]
        return np.column_stack([pick, np.fmax(S[:, 0, 0], S[:, 1, 0]),
                                np.fmin(S[:, 0, 1], S[:, 1, 1])])


def static_member_forces(model, layout, mm, u):
    """MemberForces of the static state u (n_prim,)."""
    F = element_end_forces(model, layout, mm, u, weight=True)
    return MemberForces("static", F, extreme_stresses(model, mm, F), pieces(model, mm),
                        element_member=element_members(model, mm))


def member_end_forces(model, layout, mm, u, trusses=False):
    """JSON-ready section forces at the ends of each node-to-node piece of each beam
    member (and with `trusses` each truss) in the static state u: [{"member", "type",
    "from", "to", "start": {N..Mz, sigma_max, sigma_min}, "end": {...}}, ...] ([]
    without them)."""
    if mm is None or not len(mm.member) or not (trusses or mm.beam.any()):
        return []
    mf = static_member_forces(model, layout, mm, u)
    if not trusses:
        mf.pieces = [p for p in mf.pieces if p[1] == "beam"]
    return mf.to_dict()


def modal_member_forces(model, dofs, shapes, node_shapes=None, amplitude=None):
    """MemberForces of mode shapes (n, m) in generalised coordinates: mass-normalised
    (q_k = 1 kg^0.5 m), or with `amplitude` (m) each mode scaled so that its largest node
    translation (`node_shapes` (m, nn, 3)) is that amplitude. No weight load: a mode is
    a deviation from the static state."""
    mm = dofs.members
    U = (dofs.T @ shapes).T
    if amplitude is not None:
        peak = np.linalg.norm(node_shapes, axis=2).max(axis=1)
        U = U * (amplitude / np.where(peak > 0, peak, 1.0))[:, None]
        scale = {"normalisation": "largest node translation", "amplitude_m": amplitude}
    else:
        scale = {"normalisation": "mass (shapes^T M shapes = I)"}
    F = element_end_forces(model, dofs.layout, mm, U, weight=False)
    return MemberForces("modes", F, extreme_stresses(model, mm, F), pieces(model, mm), scale,
                        element_members(model, mm))


def run_member_forces(model, dofs, static_u, q):
    """MemberForces of every output time of a run (k = nt): the states static_u + T q(t)
    for q (nt, n) about the static state, with the elements' weight."""
    mm = dofs.members
    U = static_u[None] + (dofs.T @ q.T).T
    F = element_end_forces(model, dofs.layout, mm, U, weight=True)
    return MemberForces("times", F, extreme_stresses(model, mm, F), pieces(model, mm),
                        element_member=element_members(model, mm))


def transient_envelope(model, dofs, static_u, q, chunk=256):
    """MemberForces envelope (min, max over the output times) of a run: the states
    static_u + T q(t) for q (nt, n) about the static state, with the elements' weight."""
    mm = dofs.members
    lo = hi = slo = shi = None
    for s in range(0, len(q), chunk):
        U = static_u[None] + (dofs.T @ q[s:s + chunk].T).T
        F = element_end_forces(model, dofs.layout, mm, U, weight=True)
        S = extreme_stresses(model, mm, F)
        f0, f1, s0, s1 = F.min(0), F.max(0), np.fmin.reduce(S, 0), np.fmax.reduce(S, 0)
        lo = f0 if lo is None else np.minimum(lo, f0)
        hi = f1 if hi is None else np.maximum(hi, f1)
        slo = s0 if slo is None else np.fmin(slo, s0)
        shi = s1 if shi is None else np.fmax(shi, s1)
    return MemberForces("envelope", np.stack([lo, hi]), np.stack([slo, shi]),
                        pieces(model, mm), element_member=element_members(model, mm))
