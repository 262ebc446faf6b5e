"""Time integration of a scene (docs/transient.md).

Equations about the reference geometry (the static equilibrium, or the load resting on
the ground): M q'' + C q' + f(q) = dF(t) with the piecewise-linear internal force of
tension-only ropes  f(q) = K_rest q + R^T (max(0, S0 + c R q) - S0)  (rows R of the ropes
in generalised coordinates, static tensions S0) and, on a grounded load, a contact force
that only pushes.

- direct: Newmark's average acceleration (trapezoidal rule: unconditionally stable and,
  for a linear system, energy conserving); within a step the set of taut ropes and
  contacts is fixed and the step is linear; a step in which a rope goes slack or taut, or
  a load lifts off or lands, is cut at the event (bisection of the step length to 1e-10 of
  it) and continued with the new set, so the energy stays exact across events.
- modal: superposition of k modes (rigid ones included, so the drive keeps its rigid
  motion, as Heletiy's eq. 8 does) with the decoupled damping, the same time stepping.
"""

import time
from dataclasses import dataclass, field, replace

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..assemble import assemble
from ..errors import ModelError
from .scene import parse


@dataclass
class TransientResult:
    model_name: str
    effects: dict
    method: str
    dofs: int
    labels: tuple
    time_step: float
    steps: int
    times: np.ndarray              # (nt,) output times
    q: np.ndarray                  # (nt, n) displacements (generalised)
    rope_names: tuple
    rope_force: np.ndarray         # (nt, nr) N, the largest element force of each rope
    rope_force_static: np.ndarray  # (nr,) with the load hanging at rest
    rope_force_max: np.ndarray     # (nr,)
    dynamic_factor: np.ndarray     # (nr,) max / static
    drum_names: tuple
    drum_speed: np.ndarray         # (nt, nd) rad/s
    lift_off_time: float           # s, or nan
    energy_error: float            # |E - W - E0| / max(E), undamped runs
    events: list = field(default_factory=list)
    timings: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)


class _Problem:
    """Matrices and forces of one scene, in generalised coordinates."""

    def __init__(self, model, spec):
        self.model, self.spec = model, spec
        self.system = assemble(model)
        s = self.system
        self.n = s.K.shape[0]
        self.M, self.K = s.M.tocsr(), s.K.tocsr()
        springs = s.springs
        rope_rows = np.flatnonzero(springs.rope >= 0)
        self.rope_of_row = springs.rope[rope_rows]
        self.R = (springs.R[rope_rows] @ s.dofs.T).tocsr()
        self.c = springs.c[rope_rows].copy()
        self.S0 = self._initial_tension(spec)[rope_rows]
        self.K_rest = (self.K - self.R.T @ sp.diags(self.c) @ self.R).tocsr()
        # static tension of each rope with the load hanging (for the dynamic factor)
        from ..statics import solve_static
        hanging = solve_static(model, model.effects).element_force[rope_rows]
        nr = len(model.ropes)
        self.static_rope = np.array([hanging[self.rope_of_row == k].max()
                                     if np.any(self.rope_of_row == k) else np.nan
                                     for k in range(nr)])
        labels = s.dofs.labels
        self.drum_q = {d: labels.index(f"drum {dr.name}") for d, dr in enumerate(model.drums)
                       if f"drum {dr.name}" in labels}
        self.hold = self.R.T @ self.S0 if self.R.shape[0] else np.zeros(self.n)
        self.C = self._damping()
        self.prescribed, self.dF0 = {}, np.zeros(self.n)
        for load in spec.drums:
            i = self.drum_q[load.drum]
            dr = model.drums[load.drum]
            if load.kind == "speed":
                self.prescribed[i] = load.value
            elif load.kind == "motor":     # linear characteristic: a torque and a damper
                slope = dr.gear_ratio**2 * load.stall_torque / load.synchronous_speed
                self.C = (self.C + sp.csr_matrix(([slope], ([i], [i])),
                                                 shape=(self.n, self.n))).tocsr()
        self.contact = self._contacts() if spec.initial == "grounded" else np.zeros(0, int)
        self.factors = {}
        if spec.initial == "grounded":
            self.dF0 = self.system.f.copy()      # the loads' weight is not yet on the ropes
            others = np.setdiff1d(np.arange(self.n), self.contact)
            self.dF0[others] = 0.0

    def _initial_tension(self, spec):
        from ..statics import solve_static
        model = self.model
        if spec.initial == "grounded":         # the point masses rest on the ground
            model = replace(model, ground=np.union1d(model.ground, model.masses.nodes))
        return solve_static(model, self.model.effects).element_force

    def _damping(self):
        eff = self.model.effects
        if eff.damping == "none":
            return sp.csr_matrix((self.n, self.n))
        from ..damping import modal_damping, psi_stiffness
        from ..modal import modes
        modal = modes(self.model, system=self.system,
                      count=None if self.n <= 1500 else 20)
        if eff.damping == "exact":             # viscous at the fundamental frequency
            w1 = modal.omega[~modal.rigid][0]
            return (psi_stiffness(self.system) / (2 * np.pi * w1)).tocsr()
        # modal: B = M V diag(2 zeta w) V^T M, every mode damped as decoupled
        w, zeta = modal_damping(self.system, modal)[:2]
        V = modal.shapes[:, ~modal.rigid]
        MV = self.M @ V
        return sp.csr_matrix(MV @ np.diag(2 * zeta * w) @ MV.T)

    def _contacts(self):
        """Coordinates of grounded point masses along gravity (they rest on the ground)."""
        T = self.system.dofs.T
        layout = self.system.dofs.layout
        g = self.model.gravity / np.linalg.norm(self.model.gravity)
        out = []
        for node in self.model.masses.nodes:
            rows = layout.node([node])[0]
            block = T[rows].toarray()
            for j in np.flatnonzero(np.abs(block).sum(axis=0) > 0):
                col = block[:, j]
                if abs(abs(col @ g) - np.linalg.norm(col)) < 1e-9 * np.linalg.norm(col):
                    out.append(j if col @ g < 0 else -j - 1)   # sign: + is up
        if any(j < 0 for j in out):
            raise ModelError("a grounded load's coordinate points down; give it a rope "
                             "from above", self.model.file)
        return np.array(sorted(out), dtype=int)

    def force(self, t, v):
        """Applied forces beyond the reference state at time t."""
        F = self.dF0.copy()
        for load in self.spec.drums:
            i = self.drum_q[load.drum]
            if load.kind != "speed":
                dr = self.model.drums[load.drum]
                F[i] += (load.torque(t, 0.0 if load.kind == "motor" else v[i],
                                     dr.gear_ratio) - self.hold[i])
        return F

    def tension(self, q):
        return self.S0 + self.c * (self.R @ q)

    def internal(self, q, taut):
        return self.K_rest @ q + self.R.T @ (np.where(taut, self.tension(q), 0.0) - self.S0)

    def energy(self, q, v):
        """Kinetic energy plus the potential whose gradient is `internal`."""
        stretch = np.maximum(self.tension(q), 0.0) / self.c
        rope = 0.5 * self.c * stretch**2 - 0.5 * self.S0**2 / self.c - self.S0 * (self.R @ q)
        return 0.5 * v @ (self.M @ v) + 0.5 * q @ (self.K_rest @ q) + rope.sum()


def automatic_step(problem):
    """A twentieth of the shortest period, bounded by the row sums max_i sum_j |K_ij| / M_ii
    (Gershgorin's bound for the highest w^2 of the coordinates with inertia)."""
    m = problem.M.diagonal()
    rows = np.asarray(abs(problem.K).sum(axis=1)).ravel()
    w2 = np.max(rows[m > 0] / m[m > 0]) if np.any(m > 0) else 1.0
    return 2 * np.pi / np.sqrt(max(w2, 1e-12)) / 20


def _newmark_step(P, h, t, q, v, a, taut, contact_on, fixed_q, fixed_v, fixed_a):
    """One average-acceleration step with a fixed active set; returns (q, v, a)."""
    n = P.n
    known = np.zeros(n, dtype=bool)
    known[list(P.prescribed)] = True
    known[P.contact[contact_on]] = True
    free = np.flatnonzero(~known)
    qn = np.zeros(n)
    qn[known] = fixed_q[known]
    # unknown q on free coordinates: M a + C v + f(q) = F, with
    # a = 4/h^2 (q - q0 - h v0) - a0 and v = v0 + h/2 (a0 + a); the motor's
    # speed-dependent torque is in C; the force uses t + h
    key = (h, taut.tobytes(), contact_on.tobytes())
    if key not in P.factors:                 # one factorisation per step and active set
        if len(P.factors) > 64:
            P.factors.clear()
        Kt = P.K_rest + P.R.T @ sp.diags(np.where(taut, P.c, 0.0)) @ P.R
        A = ((4 / h**2) * P.M + (2 / h) * P.C + Kt).tocsr()
        P.factors[key] = (spla.splu(A[free][:, free].tocsc()), A[free][:, known])
    lu, coupling = P.factors[key]
    F = P.force(t + h, v)
    rhs = F - P.internal(np.zeros(n), taut) \
        + P.M @ ((4 / h**2) * (q + h * v) + a) + P.C @ ((2 / h) * q + v)
    qk = qn.copy()
    qk[free] = lu.solve(rhs[free] - coupling @ qn[known])
    ak = (4 / h**2) * (qk - q - h * v) - a
    vk = v + h / 2 * (a + ak)
    ak[known] = fixed_a[known]
    vk[known] = fixed_v[known]
    return qk, vk, ak


def simulate(model, progress=None):
    """Run the transient scene of `model` (its `analysis` must be of type transient)."""
    if model.analysis.get("type") != "transient":
        raise ModelError("this is not a transient scene: give analysis: {type: transient, "
                         "...} (docs/transient.md)", model.scene_file or model.file,
                         "analysis.type")
    spec = parse(model)
    t0 = time.perf_counter()
    P = _Problem(model, spec)
    t1 = time.perf_counter()
    if spec.method == "modal":
        return _modal(model, spec, P, t0, t1)
    h = spec.time_step or automatic_step(P)
    n_steps = int(np.ceil(spec.duration / h - 1e-9))
    h = spec.duration / n_steps
    stride = max(1, int(round((spec.output_step or h) / h)))
    q, v = np.zeros(P.n), np.zeros(P.n)
    for i, speed in P.prescribed.items():
        v[i] = speed
    taut = P.tension(q) >= 0
    contact_on = np.ones(len(P.contact), dtype=bool)
    # initial acceleration from the equations with the initial active set
    a = _accelerations(P, 0.0, q, v, taut, contact_on)
    out_t, out_q, out_v = [0.0], [q.copy()], [v.copy()]
    events, lift_off = [], np.nan
    E0, work = P.energy(q, v), 0.0
    t, step = 0.0, 0
    while step < n_steps:
        hs = (step + 1) * h - t                 # to the next grid time
        q1, v1, a1 = _advance(P, hs, t, q, v, a, taut, contact_on)
        new_taut = P.tension(q1) >= 0
        new_contact = _contact_state(P, t + hs, q1, v1, a1, new_taut, contact_on)
        event = np.any(new_taut != taut) or np.any(new_contact != contact_on)
        if event and hs > 1e-9 * h:             # cut the step at the event
            hs = _locate(P, hs, t, q, v, a, taut, contact_on)
            q1, v1, a1 = _advance(P, hs, t, q, v, a, taut, contact_on)
            new_taut = P.tension(q1) >= 0
            new_contact = _contact_state(P, t + hs, q1, v1, a1, new_taut, contact_on)
        if not P.prescribed:
            work += 0.5 * (P.force(t, v) + P.force(t + hs, v1)) @ (q1 - q)
        if np.any(new_taut != taut):
            events.append((t + hs, "ropes " + ", ".join(
                f"{model.ropes[P.rope_of_row[k]].name} {'taut' if new_taut[k] else 'slack'}"
                for k in np.flatnonzero(new_taut != taut))))
        if np.any(new_contact != contact_on):
            lifted = np.any(contact_on & ~new_contact)
            if np.isnan(lift_off) and lifted:
                lift_off = t + hs
            events.append((t + hs, "lift-off" if lifted else "landing"))
            for k in np.flatnonzero(~contact_on & new_contact):
                v1[P.contact[k]] = 0.0           # a landing load stops (plastic impact)
        grid = abs(t + hs - (step + 1) * h) <= 1e-9 * h
        t = (step + 1) * h if grid else t + hs
        q, v, a, taut, contact_on = q1, v1, a1, new_taut, new_contact
        if grid:
            step += 1
            if step % stride == 0 or step == n_steps:
                out_t.append(t)
                out_q.append(q.copy())
                out_v.append(v.copy())
            if progress:
                progress(step, n_steps)
    Q = np.array(out_q)
    E = np.array([P.energy(qq, vv) for qq, vv in zip(Q, out_v)])
    result = _result(model, spec, P, "direct", h, n_steps, np.array(out_t), Q,
                     np.array(out_v), lift_off, events)
    if P.C.nnz == 0 and not P.prescribed and spec.initial == "static":
        result.energy_error = float(abs(E[-1] - work - E0) / max(abs(E).max(), 1e-300))
    result.timings = {"assemble": t1 - t0, "integrate": time.perf_counter() - t1}
    return result


def _advance(P, h, t, q, v, a, taut, contact_on):
    fq, fv, fa = np.zeros(P.n), np.zeros(P.n), np.zeros(P.n)
    for i, speed in P.prescribed.items():
        fq[i], fv[i] = q[i] + speed * h, speed
    # contacts held: q, v, a stay zero
    return _newmark_step(P, h, t, q, v, a, taut, contact_on, fq, fv, fa)


def _contact_state(P, t, q, v, a, taut, contact_on):
    """Contacts after a step: a held load lifts off when the ground would have to pull;
    a free one lands when it reaches the ground."""
    if not len(P.contact):
        return contact_on
    residual = P.M @ a + P.C @ v + P.internal(q, taut) - P.force(t, v)
    reaction = residual[P.contact]         # what the ground must supply (+ up)
    on = contact_on.copy()
    on[contact_on & (reaction < 0)] = False
    on[~contact_on & (q[P.contact] < 0)] = True
    return on


def _locate(P, hs, t, q, v, a, taut, contact_on):
    """The step length at which the active set first changes (bisection)."""
    lo, hi = 0.0, hs
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        q1, v1, a1 = _advance(P, mid, t, q, v, a, taut, contact_on)
        same = np.all((P.tension(q1) >= 0) == taut) and np.all(
            _contact_state(P, t + mid, q1, v1, a1, taut, contact_on) == contact_on)
        lo, hi = (mid, hi) if same else (lo, mid)
        if hi - lo < 1e-10 * hs:
            break
    return hi


def _accelerations(P, t, q, v, taut, contact_on):
    """Initial accelerations of the coordinates with inertia (massless ones follow the
    others statically: their acceleration never enters the step)."""
    known = np.zeros(P.n, dtype=bool)
    known[list(P.prescribed)] = True
    known[P.contact[contact_on]] = True
    free = np.flatnonzero(~known & (P.M.diagonal() > 0))
    rhs = P.force(t, v) - P.C @ v - P.internal(q, taut)
    a = np.zeros(P.n)
    if free.size:
        a[free] = spla.spsolve(P.M[free][:, free].tocsc(), rhs[free])
    return a


def _modal(model, spec, P, t0, t1):
    from ..damping import modal_damping
    from ..modal import modes
    if P.prescribed:
        raise ModelError("method: modal takes drum torques; for a prescribed drum speed use "
                         "method: direct", model.scene_file or model.file, "analysis.method")
    modal = modes(model, count=min(spec.modes, P.n), system=P.system)
    Phi, w = modal.shapes, modal.omega
    zeta = np.zeros(len(w))
    if model.effects.damping != "none":
        zeta[~modal.rigid] = modal_damping(P.system, modal)[1]
    Cm = np.diag(2 * zeta * w) + Phi.T @ (P.C @ Phi) * (model.effects.damping == "none")
    Km = np.diag(w**2)
    h = spec.time_step or 2 * np.pi / max(w.max(), 1e-12) / 20
    n_steps = int(np.ceil(spec.duration / h - 1e-9))
    h = spec.duration / n_steps
    stride = max(1, int(round((spec.output_step or h) / h)))
    eta, deta = np.zeros(len(w)), np.zeros(len(w))
    acc = Phi.T @ P.force(0.0, np.zeros(P.n)) - Cm @ deta - Km @ eta
    A = (4 / h**2) * np.eye(len(w)) + (2 / h) * Cm + Km
    lu = np.linalg.inv(A)
    out_t, out_q, out_v = [0.0], [np.zeros(P.n)], [np.zeros(P.n)]
    for step in range(1, n_steps + 1):
        t = step * h
        F = Phi.T @ P.force(t, Phi @ deta)
        rhs = F + (4 / h**2) * (eta + h * deta) + acc + Cm @ ((2 / h) * eta + deta)
        eta1 = lu @ rhs
        acc1 = (4 / h**2) * (eta1 - eta - h * deta) - acc
        deta = deta + h / 2 * (acc + acc1)
        eta, acc = eta1, acc1
        if step % stride == 0 or step == n_steps:
            out_t.append(t)
            out_q.append(Phi @ eta)
            out_v.append(Phi @ deta)
    result = _result(model, spec, P, "modal", h, n_steps, np.array(out_t),
                     np.array(out_q), np.array(out_v), np.nan, [])
    if np.any(P.S0 + P.c * (P.R @ np.array(out_q).T).T < 0):
        result.warnings.append("a rope went slack, which modal superposition cannot "
                               "represent; use method: direct")
    result.timings = {"assemble": t1 - t0, "integrate": time.perf_counter() - t1}
    return result


def _result(model, spec, P, method, h, n_steps, times, Q, V, lift_off, events):
    S = P.S0[None, :] + P.c[None, :] * (P.R @ Q.T).T
    if method == "direct":
        S = np.maximum(S, 0.0)
    nr = len(model.ropes)
    rope_force = np.column_stack([S[:, P.rope_of_row == k].max(axis=1)
                                  if np.any(P.rope_of_row == k) else np.full(len(times), np.nan)
                                  for k in range(nr)]) if nr else np.zeros((len(times), 0))
    fmax = rope_force.max(axis=0) if nr else np.zeros(0)
    drums = sorted(P.drum_q)
    return TransientResult(
        model.scene or model.name, model.effects.as_dict(), method, P.n,
        P.system.dofs.labels, h, n_steps, times, Q, tuple(r.name for r in model.ropes),
        rope_force, P.static_rope, fmax, fmax / P.static_rope,
        tuple(model.drums[d].name for d in drums),
        V[:, [P.drum_q[d] for d in drums]] if drums else np.zeros((len(times), 0)),
        lift_off, np.nan, [f"{t:.6g} s: {e}" for t, e in events])
