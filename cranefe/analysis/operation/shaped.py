"""Shaped drive profiles of operation scenes (issue 17; docs/shaping.md).

A profile move may carry ``shaper: {type: ZV|ZVD|ZVDD|EI, frequency: auto | Hz | [Hz,
...], damping: 0, modes: [1, 2], V: 0.05}``. The shaped move is the convolution of the
move with the shaper's impulse train (t_i, A_i, sum A_i = 1):

    s_shaped(t) = sum_i A_i s(t - t_i)

exact for the piecewise constant-jerk moves of ``profiles``: a sum of time-shifted,
scaled copies, itself piecewise constant-jerk (``profiles.combine``). It travels the
same distance at no more than the same speed and acceleration (a convex combination of
copies, for the shapers' positive amplitudes) and ends the shaper's duration later.

``frequency: auto`` takes the frequencies from the crane itself: the linearised
equations of the operation engine at the static state of the geometry where the move
starts (every drive at its position at that time, at rest) - the engine's tangent K and
mass M, which equal `cranefe modes`' at the reference state (tested in
test_operation.py) - and the modes whose kinetic energy is mostly horizontal (pendulum
modes: the hook, or hook-and-load double pendulum, which then gets a two-mode shaper,
the convolution of one shaper per mode) for slider and hinge drives; the lowest mostly
vertical mode (the hoisting bounce) for drum drives. ``modes: [k, ...]`` keeps the k-th
of those (1 = lowest). Degenerate pairs (the same pendulum swinging in x and in y) count
once.

Parsing lives here; scene.py's ``_motion`` admits the key and ``parse`` hands the
finished Operation to ``apply``.
"""

import dataclasses

import numpy as np

from ..shaping.shapers import convolve, make
from . import profiles

KINDS = ("ZV", "ZVD", "ZVDD", "EI")
KEYS = {"type", "frequency", "damping", "modes", "V"}
HORIZONTAL = 0.5          # a pendulum mode has more than half its kinetic energy horizontal
SAME = 1e-6               # relative gap below which two frequencies are one (degenerate)


@dataclasses.dataclass(frozen=True)
class ShaperSpec:
    """A shaper as the scene gives it (frequencies in rad/s, or None for auto)."""

    kind: str
    omegas: tuple = None
    zeta: float = 0.0
    modes: tuple = None
    V: float = 0.05
    entry: str = ""


def parse_shaper(r, spec, e):
    """The `shaper:` mapping of one profile move, checked."""
    r.keys(spec, e, KEYS, required=("type",))
    kind = spec["type"]
    if kind not in KINDS:
        r.fail(f"{e}.type", f"{kind!r} is not one of {', '.join(KINDS)}")
    f = spec.get("frequency", "auto")
    omegas = None
    if f != "auto":
        fs = f if isinstance(f, list) else [f]
        if not fs:
            r.fail(f"{e}.frequency", "an empty list; give auto, a frequency in Hz or a "
                   "list of them (one per mode)")
        omegas = tuple(2 * np.pi * r.number(x, f"{e}.frequency", positive=True)
                       for x in fs)
        if "modes" in spec:
            r.fail(f"{e}.modes", "modes selects among the crane's own modes: it goes "
                   "with frequency: auto")
    zeta = r.number(spec.get("damping", 0.0), f"{e}.damping", nonneg=True)
    if zeta >= 1:
        r.fail(f"{e}.damping", f"{zeta:g}: a damping ratio below 1 (an oscillating mode)")
    V = r.number(spec.get("V", 0.05), f"{e}.V", positive=True)
    if "V" in spec and kind != "EI":
        r.fail(f"{e}.V", "V (the tolerated residual) belongs to the EI shaper")
    if not V < 1:
        r.fail(f"{e}.V", f"{V:g}: the tolerated residual is a fraction below 1 (e.g. 0.05)")
    modes = None
    if "modes" in spec:
        raw = r.listing(spec["modes"], f"{e}.modes", min_len=1)
        modes = tuple(int(r.number(x, f"{e}.modes[{k}]", positive=True))
                      for k, x in enumerate(raw))
        if any(m != x for m, x in zip(modes, raw)):
            r.fail(f"{e}.modes", "mode numbers are whole numbers from 1 (the lowest)")
    return ShaperSpec(kind, omegas, zeta, modes, V, e)


def build_shaper(spec, omegas):
    """The impulse train of `spec` for the modes `omegas` (rad/s): one shaper, or the
    convolution of one per mode (cancels every mode; Singer & Seering 1990)."""
    opts = {"V": spec.V} if spec.kind == "EI" else {}
    parts = [make(spec.kind, w, spec.zeta, **opts) for w in omegas]
    if len(parts) == 1:
        return parts[0]
    return convolve(*parts, name="*".join(spec.kind for _ in parts))


def shape_motion(motion, shaper):
    """sum_i A_i motion(t - t_i): the move convolved with the impulse train (exact)."""
    copies = [profiles.Motion(motion.t + ti, A * motion.s, A * motion.v, A * motion.a,
                              A * motion.j, motion.kind)
              for ti, A in zip(shaper.times, shaper.amplitudes)]
    out = profiles.combine(copies)
    return dataclasses.replace(out, kind=motion.kind)


@dataclasses.dataclass(frozen=True)
class ShapedMotion(profiles.Motion):
    """A drive's motion with shaped moves: ``shapers`` = ((move index, Shaper, the
    frequencies it cancels in rad/s), ...)."""

    shapers: tuple = ()


# ------------------------------------------------------------------ the crane's modes

def crane_modes(model, op, t, newton_tol=1e-10):
    """(w, hor, vert, phi, mech): frequencies (rad/s), the shares of each mode's kinetic
    energy (of the point masses and the elastic structure, if any) in the point masses'
    horizontal and vertical motion, and the mode shapes, linearised at the static state
    of the geometry of time t (every drive at its position then, at rest; drums with a
    torque or motor drive held at their starting angle).

    The static state: Newton on F(q) = 0 with the engine's analytic tangent K = -dF/dq
    (mechanism.evaluate, damping off), from the reference position moved horizontally
    with the node each mass hangs from. Then K phi = w^2 M phi on the translational
    coordinates (the linear core's pendulum and axial stiffness: K = EA/L r r^T + S dr/dx).
    """
    import scipy.linalg as sl

    from ...errors import AnalysisError
    from .mechanism import Mechanism
    mech = Mechanism(model, op)
    X, V, A, th = mech.kinematics(t)
    th = th.copy()
    th[:, 1:] = 0.0
    kin = (X.copy(), np.zeros_like(V), np.zeros_like(A), th)
    nx, nf = mech.nx, len(mech.free)
    q = mech.q0.copy()
    if mech.flex is not None:
        # kinematics leaves the elastic nodes at 0: place them where their frames carry
        # them (bent as at t = 0)
        X = mech.place(t, q, np.zeros(mech.n), kin)[0]
    if nf and mech.sway:
        H = np.eye(3) - np.outer(mech.up, mech.up)
        P = model.coords[mech.free].copy()
        for k in range(nf):
            root = mech.root[k]
            if root >= 0:
                P[k] += H @ (X[root] - model.coords[root])
        q[:mech.nc] = mech.E.T @ P.ravel()      # the point masses (joints, structure after)
    taut = np.ones(len(mech.ropes), bool)
    zero = np.zeros(mech.n)
    scale = model.length_scale
    for _ in range(50):
        ev = mech.evaluate(t, q, zero, taut, kin, damping=False, powers=False)
        dq = np.linalg.solve(ev.K[:nx, :nx], ev.F[:nx])
        q[:nx] += dq
        if np.abs(dq).max() <= newton_tol * scale:
            break
    else:
        raise AnalysisError(f"the static state at t = {t:g} s (for the shaper's frequency "
                            "auto) did not converge; give the frequency in Hz")
    ev = mech.evaluate(t, q, zero, taut, kin, damping=False, powers=False)
    if np.any(ev.S < 0):
        raise AnalysisError(f"a rope is slack at the static state of t = {t:g} s; the "
                            "shaper's frequency auto needs hanging loads")
    K = 0.5 * (ev.K[:nx, :nx] + ev.K[:nx, :nx].T)
    M = mech.mass_matrix(ev)[:nx, :nx]          # with the joint coordinates' block
    w2, phi = sl.eigh(K, 0.5 * (M + M.T))
    u = (mech.E @ phi[:mech.nc]).reshape(nf, 3, nx)        # node displacements per mode
    m = mech.free_mass[:, None, None]
    up = np.einsum("i,kim->km", mech.up, u)                # (nf, nx) vertical part
    loads = np.einsum("kim,kim->m", m * u, u)              # 2 x the loads' kinetic energy
    vert = np.einsum("k,km->m", mech.free_mass, up**2)
    # the elastic structure's own kinetic energy (its coordinates follow the joints'): a
    # mode that mostly bends the structure is neither a pendulum nor a hoisting mode
    el = slice(mech.nc + mech.nJ, nx)
    structure = np.einsum("im,ij,jm->m", phi[el], M[el, el], phi[el])
    total = loads + structure
    return np.sqrt(np.maximum(w2, 0.0)), (loads - vert) / total, vert / total, phi, mech


def auto_omegas(model, op, drive, t, modes=None, entry=""):
    """The frequencies (rad/s) a shaper with frequency: auto cancels for `drive` starting
    at t (module docstring): pendulum modes for joints, the hoisting mode for drums."""
    from ...errors import ModelError
    w, hor, vert, _, mech = crane_modes(model, op, t)
    file = model.scene_file or model.file
    if drive.target == "drum":
        cand = w[vert > 1 - HORIZONTAL][:1]
        what = "hoisting (vertical) mode"
    else:
        if not mech.sway:
            raise ModelError("frequency: auto shapes for the pendulum modes, and with "
                             "effects sway: false the loads do not swing; give the "
                             "frequency in Hz or turn sway on", file, entry)
        cand = w[hor > HORIZONTAL]
        what = "pendulum mode"
    uniq = []
    for x in cand:
        if not uniq or x > uniq[-1] * (1 + SAME):
            uniq.append(float(x))
    if not uniq:
        raise ModelError(f"the crane has no {what} for the shaper's frequency auto; give "
                         "the frequency in Hz", file, entry)
    if modes is None:
        return tuple(uniq)
    for m in modes:
        if m > len(uniq):
            hz = ", ".join(f"{x / (2 * np.pi):.4g}" for x in uniq)
            raise ModelError(f"mode {m}: the crane has {len(uniq)} {what}(s) at the "
                             f"start of this move ({hz} Hz); number them from 1",
                             file, f"{entry}.modes")
    return tuple(uniq[m - 1] for m in modes)


# ------------------------------------------------------------------ the scene pass

def _moves(raw):
    return raw if isinstance(raw, list) else [raw]


def has_shaper(raw_drives):
    """Whether any profile move of the scene's drives carries a shaper."""
    for spec in (raw_drives or {}).values():
        if isinstance(spec, dict) and "profile" in spec:
            if any(isinstance(p, dict) and "shaper" in p for p in _moves(spec["profile"])):
                return True
    return False


def apply(model, r, raw_drives, op, motion, check_travel):
    """The Operation `op` with every shaped move replaced by its convolution with its
    shaper. Moves are taken in the order they start, so that frequency: auto sees the
    geometry left by every move (shaped) before it. Returns `op` unchanged if no move is
    shaped.

    A shaped drive's motion is a ``ShapedMotion``: its ``shapers`` lists (move index,
    Shaper, frequencies) of each shaped move. `motion` and `check_travel` are scene.py's
    parser of one move and its check of a drive's travel (passed in: no import cycle).
    """
    if not has_shaper(raw_drives):
        return op
    drives = list(op.drives)
    moves, pending = {}, []
    for k, d in enumerate(drives):
        spec = raw_drives[d.name]
        if d.kind != "profile":
            continue
        ps = _moves(spec["profile"])
        e = f"{d.entry}.profile" + ("[{}]" if isinstance(spec["profile"], list) else "")
        radius = model.drums[d.index].radius if d.target == "drum" else None
        ms = [motion(r, p, e.format(i), d.target, radius)    # as scene._moves parses it
              for i, p in enumerate(ps)]
        moves[k] = ms
        for i, p in enumerate(ps):
            if "shaper" in p:
                if ms[i].kind == "table" and abs(ms[i].v[0]) > 0:
                    r.fail(e.format(i), "a speed table that starts moving at t = 0 cannot "
                           "be shaped (the shaper delays the move); start it from rest")
                sp = parse_shaper(r, p["shaper"], e.format(i) + ".shaper")
                pending.append((ms[i].t[0], k, i, sp))
    applied = {}
    for t0, k, i, sp in sorted(pending, key=lambda x: (x[0], x[1], x[2])):
        d = drives[k]
        current = dataclasses.replace(op, drives=tuple(drives))
        omegas = sp.omegas if sp.omegas is not None else \
            auto_omegas(model, current, d, float(t0), sp.modes, sp.entry)
        shaper = build_shaper(sp, omegas)
        moves[k][i] = shape_motion(moves[k][i], shaper)
        ms = moves[k]
        for j in range(1, len(ms)):
            if ms[j].t[0] < ms[j - 1].t[-1] - 1e-12:
                r.fail(f"{d.entry}.profile[{j}].start",
                       f"starts at {ms[j].t[0]:g} s, before the previous (shaped) move ends "
                       f"({ms[j - 1].t[-1]:.6g} s: the shaper adds its duration)")
        applied.setdefault(k, []).append((i, shaper, tuple(float(w) for w in omegas)))
        c = profiles.combine(ms)
        drives[k] = dataclasses.replace(d, motion=ShapedMotion(
            c.t, c.s, c.v, c.a, c.j, c.kind, tuple(sorted(applied[k], key=lambda x: x[0]))))
    for k in moves:
        check_travel(model, r, drives[k], op.duration)
    return dataclasses.replace(op, drives=tuple(drives))
