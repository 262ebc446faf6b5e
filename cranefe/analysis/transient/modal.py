"""Modal superposition in principal coordinates (Heletiy 2016; docs/transient.md).

The structure with its prescribed drums held (the sub-system of the free coordinates f)
is condensed as in `cranefe.condense`: massless coordinates statically, quasi-cyclic ones
(free drums, free bodies) by eq. 7-8, ``A1 = A11 - A12 A22^-1 A21``, ``C1 = C11``,
``F1' = F1 - A12 A22^-1 F2``. With the eigenvectors Y of (C1, A1) and the recovery
``q = P y1``, ``P = Tq [I; -A22^-1 A21]``, the k retained principal coordinates obey

    eta_i'' + 2 zeta_i w_i eta_i' + w_i^2 eta_i = (P Y_i)^T F = Y_i^T F1'

(the elastic shapes P Y_i are M-orthogonal to the rigid motions, so projecting F on them
is eq. 8), with the decoupled damping ratios zeta_i of `cranefe.analysis.damping` (eq. 16). The
quasi-cyclic coordinates keep their rigid motion: with the mass-normalised rigid shapes
Phi_r, ``z'' = Phi_r^T F`` (eq. 5 of the seed solved for Y2''), and are recovered in
``q = Phi_r z + P Y eta``. A prescribed drum is a known angle theta(t): the free
coordinates see ``-K_fp theta - C_fp theta' - M_fp theta''``.

Static correction (mode acceleration): the modes left out answer quasi-statically, so
each load shape G adds ``(G_e - sum_kept Phi_i Phi_i^T / w_i^2) G g(t)`` with G_e the
flexibility of the elastic part; massless coordinates always get their direct static
response ``K_bb^-1 G_b`` (no mode carries it).
"""

from dataclasses import replace

import numpy as np
import scipy.sparse.linalg as spla

from ...condense import DENSE_MAX, choose_quasi_cyclic, massless_split
from .equations import Equations, MotorLoad, Signal


def _coupling_signals(p):
    """angle, speed and acceleration of a prescribed drum with speed Profile p."""
    angle = Signal(lambda t, left=False: p.integral(t), lambda t, left=False: p(t))
    speed = Signal(lambda t, left=False: p(t), lambda t, left=False: p.rate(t, left))
    accel = Signal(lambda t, left=False: p.rate(t, left))
    return angle, speed, accel


def _modes(problem, k):
    from ..modal import modes
    sub = problem.sub
    n = sub.K.shape[0]
    if n <= DENSE_MAX:
        return modes(problem.model, system=sub, solver="dense")
    count = min(k + 8, n - 1)
    while True:
        modal = modes(problem.model, system=sub, count=count)
        if (~modal.rigid).sum() >= k or count >= n - 1:
            return modal
        count = min(count + int(modal.rigid.sum()) + 8, n - 1)


def modal_equations(problem, spec):
    """Equations in the retained principal coordinates (rigid ones first) and a map
    back to q; returns (Equations, info dict).

    Length: the modal reduction in the order of its derivation (modes, static
    correction, drives, damping); each step feeds the next.
    """
    p = problem
    model, sub, free = p.model, p.sub, p.free
    n = p.n
    phys = p.eq
    modal = _modes(p, spec.modes)
    rigid = modal.rigid
    el = np.flatnonzero(~rigid)
    kept = el[:spec.modes]
    sel = np.concatenate([np.flatnonzero(rigid), kept])
    Phi = modal.shapes[:, sel]
    w = modal.omega[sel]
    nr = int(rigid.sum())
    m = len(sel)
    warnings = []
    if not spec.static_correction and any(np.any(pr.values) for pr in
                                          p.eq.prescribed.values()):
        warnings.append("static_correction: false with a prescribed drum speed: the "
                        "structure's quasi-static following of the drum is left to the "
                        "retained modes, which carry it poorly")
    if len(kept) < spec.modes:
        warnings.append(f"modes: {spec.modes} asked, the model has {len(el)} elastic modes; "
                        "all are used")

    # damping in principal coordinates
    kind = model.effects.damping
    C = None
    if kind == "modal":
        from ..damping import modal_damping_ratios
        chosen = replace(modal, omega=w, shapes=Phi, rigid=rigid[sel],
                         node_shapes=modal.node_shapes[sel])
        zeta = modal_damping_ratios(sub, chosen)
        C = np.diag(2 * zeta * w)
    elif kind == "exact":
        Cf = phys.C[free][:, free]
        C = np.asarray(Phi.T @ (Cf @ Phi))

    # loads: constant, signals, prescribed drums seen by the free coordinates, motors
    shapes = [(phys.F0[free][:, None], None)]
    for G, sig in phys.loads:
        shapes.append((np.asarray(G)[free], sig))
    for i, prof in phys.prescribed.items():
        if np.all(prof.values == 0):
            continue                              # held: nothing moves
        e = np.zeros(n)
        e[i] = 1.0
        angle, speed, accel = _coupling_signals(prof)
        Kcol = -np.asarray(p.system.K[:, [i]].toarray()).ravel()[free]
        Mcol = -np.asarray(p.system.M[:, [i]].toarray()).ravel()[free]
        Ccol = -phys.damp(e)[free]              # zero unless damped (see simulate)
        shapes += [(Kcol[:, None], angle), (Mcol[:, None], accel)]
        if np.any(Ccol):
            shapes.append((Ccol[:, None], speed))
    motors = [MotorLoad(Phi.T @ mo.e[free], mo.motor, mo.gear, mo.name)
              for mo in phys.motors]
    loads = [(Phi.T @ G, sig) for G, sig in shapes[1:]]
    F0 = Phi.T @ shapes[0][0][:, 0]

    # quasi-static part of what the modes do not carry
    X = _corrections(sub, modal, Phi, w, nr, [G for G, _ in shapes] +
                     [mo.e[free][:, None] for mo in phys.motors],
                     full=spec.static_correction)
    X0 = X[0][:, 0]
    X_loads = X[1:len(shapes)]
    X_motors = X[len(shapes):]
    sigs = [sig for _, sig in shapes[1:]]
    pres = dict(phys.prescribed)

    def to_full(t, x, v, a):
        q, qv, qa = np.zeros(n), np.zeros(n), np.zeros(n)
        qf = Phi @ x + X0
        vf = Phi @ v
        for Xj, sig in zip(X_loads, sigs):
            qf += Xj @ sig.value(t)
            vf += Xj @ sig.d(t)
        for Xm, mo, mp in zip(X_motors, phys.motors, motors):
            qf += Xm[:, 0] * mo.gear * mo.motor.torque(mo.gear * float(mp.e @ v))[0]
        q[free], qv[free], qa[free] = qf, vf, Phi @ a
        for i, prof in pres.items():
            q[i], qv[i], qa[i] = prof.integral(t)[0], prof(t)[0], prof.rate(t)[0]
        return q, qv, qa

    eq = Equations(np.eye(m), np.diag(w**2), C, None, None, None, None, None, F0, loads,
                   motors, {}, None, None, to_full)
    return eq, {"modes": len(kept), "omega_max": float(w.max(initial=0.0)),
                "quasi_cyclic": modal.quasi_cyclic, "warnings": warnings}


def _corrections(sub, modal, Phi, w, nr, shapes, full=True):
    """Static correction X (n_f, width) of each load shape (module docstring)."""
    K, M = sub.K.tocsr(), sub.M.tocsr()
    nf = K.shape[0]
    a, b = massless_split(M)
    out = []
    if not full:
        lu = spla.splu(K[b][:, b].tocsc()) if len(b) else None
        for G in shapes:
            X = np.zeros((nf, G.shape[1]))
            if lu is not None:
                X[b] = lu.solve(np.ascontiguousarray(G[b]))
            out.append(X)
        return out
    rig = modal.shapes[:, modal.rigid]
    MR = np.asarray(M @ rig)
    # K x = G_e (self-equilibrated) with one coordinate per rigid motion held (chosen as
    # the quasi-cyclic ones of `cranefe.condense`), then made M-orthogonal to the rigid
    # motions: the elastic flexibility without forming K + (M R)(M R)^T densely
    held = choose_quasi_cyclic(rig, sub.dofs.kinds) if rig.shape[1] else np.zeros(0, int)
    keep = np.setdiff1d(np.arange(nf), held)
    lu = spla.splu(K[keep][:, keep].tocsc())
    el = Phi[:, nr:]
    inv_w2 = 1.0 / w[nr:] ** 2
    for G in shapes:
        Ge = G - MR @ (rig.T @ G) if rig.shape[1] else G
        flex = np.zeros((nf, G.shape[1]))
        flex[keep] = lu.solve(np.ascontiguousarray(Ge[keep]))
        if rig.shape[1]:
            flex -= rig @ (MR.T @ flex)
        out.append(flex - el @ (inv_w2[:, None] * (el.T @ G)))
    return out
