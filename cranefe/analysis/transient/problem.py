"""The equations of a transient scene in the model's generalised coordinates q.

About the reference state (static equilibrium, or the loads resting on the ground):

    M q'' + C q' + K_rest q + R^T (max(0, S0 + c R q) - S0) = dF(t)

R holds the rows of every rope (a massless rope: one row over its reeving; a rope with
mass: one per element) in generalised coordinates, c their stiffness, S0 their initial
forces (the static state, or the state with the loads grounded); K_rest is the rest of
the assembled stiffness (springs, members, and with sway the tension and load stiffness
of the reference static tensions). dF is what changes at t = 0: a driven drum's torque
minus the holding torque its brake carried (R^T S0 at the drum), node forces, and with
``initial: grounded`` the weight of the grounded loads, which the ground carries until
the ropes lift them. A drum torque is the generalised force ``T^T e_drum``; a prescribed
drum speed makes the drum angle a known function (partitioned out); drums that the scene
does not drive keep their brake on (angle held at zero).
"""

from dataclasses import replace

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ...system import assemble
from ...condense import massless_split
from ...errors import ModelError
from .equations import Equations, MotorLoad, Signal
from .scene import Profile

DENSE_DAMPING = 400     # up to this many coordinates the modal damping matrix is formed
DENSE_OMEGA = 400       # up to this many masses the highest frequency is found densely
SPARSE_DAMPING = 1500   # above this many free coordinates only the lowest modes are damped
SPARSE_DAMPED_MODES = 30  # modes damped on larger models (the others undamped)


def profile_signal(p):
    return Signal(lambda t, left=False: p(t), lambda t, left=False: p.rate(t, left))


def subsystem(system, keep):
    """The assembled system restricted to the coordinates `keep` (the others held)."""
    dofs = system.dofs
    keep = np.asarray(keep, dtype=int)
    sub_dofs = replace(dofs, T=dofs.T[:, keep].tocsr(),
                       labels=tuple(dofs.labels[i] for i in keep),
                       kinds=tuple(dofs.kinds[i] for i in keep))
    return replace(system, dofs=sub_dofs, K=system.K[keep][:, keep].tocsr(),
                   M=system.M[keep][:, keep].tocsr(), f=system.f[keep])


def highest_omega(system):
    """Highest natural frequency (rad/s) of an assembled system, massless coordinates
    condensed: dense for small systems, else Lanczos on the largest eigenvalue."""
    K, M = system.K, system.M
    a, b = massless_split(M)
    if not len(a):
        return 0.0
    Kaa = K[a][:, a]
    if len(a) <= DENSE_OMEGA:
        Ks = Kaa.toarray()
        if len(b):
            Ks -= K[a][:, b].toarray() @ np.linalg.solve(K[b][:, b].toarray(),
                                                         K[b][:, a].toarray())
        lam = sla.eigh(0.5 * (Ks + Ks.T), M[a][:, a].toarray(), eigvals_only=True,
                       subset_by_index=[len(a) - 1, len(a) - 1])
        return float(np.sqrt(max(lam[-1], 0.0)))
    Kab = K[a][:, b]
    lu = spla.splu(K[b][:, b].tocsc()) if len(b) else None

    def kstar(x):
        y = Kaa @ x
        return y - Kab @ lu.solve(Kab.T @ x) if lu is not None else y

    op = spla.LinearOperator((len(a), len(a)), matvec=kstar, dtype=float)
    v0 = np.random.default_rng(0).standard_normal(len(a))
    lam = spla.eigsh(op, k=1, M=M[a][:, a].tocsc(), which="LA", tol=1e-4, v0=v0,
                     return_eigenvectors=False)
    return float(np.sqrt(max(lam[-1], 0.0)))


class Problem:
    """The physical equations of a scene (see the module docstring)."""

    def __init__(self, model, spec, damping=True, reuse=None):
        """damping=False leaves the viscous matrix out (modal superposition damps its
        principal coordinates itself); reuse: a `cranefe.assembly.reuse.Reuse` (sweeps).

        Length: reads every part of the scene into the problem's arrays in one place, in
        the order docs/transient.md lists them.
        """
        from ...statics import solve_static
        self.model, self.spec = model, spec
        file = model.scene_file or model.file
        eff = model.effects
        if not eff.rope_elasticity:
            raise ModelError("a transient needs elastic ropes (their forces are what it "
                             "computes); remove rope_elasticity: false", file,
                             "effects.rope_elasticity")
        self.system = system = assemble(model, reuse=reuse)
        dofs = system.dofs
        self.n = n = dofs.n
        self.labels = dofs.labels
        self.warnings = []
        springs = system.springs
        rows = np.flatnonzero(springs.rope >= 0)
        self.R = (springs.R[rows] @ dofs.T).tocsr()
        self.c = springs.c[rows].astype(float)
        self.rope_of_row = springs.rope[rows]
        hanging = system.static if system.static is not None else \
            solve_static(model, eff, reuse)
        self.hanging = hanging.element_force[rows]
        K = system.K
        self.drum_q = {d: dofs.labels.index(f"drum {dr.name}")
                       for d, dr in enumerate(model.drums)
                       if f"drum {dr.name}" in dofs.labels}
        contacts, up = self._contacts()
        self.S0 = self._grounded_tensions(contacts) if spec.initial == "grounded" \
            else self.hanging.copy()
        K_rest = (K - self.R.T @ sp.diags(self.c) @ self.R).tocsr()
        self.hold = self.R.T @ self.S0             # generalised force of the tensions S0

        # drums: driven (speed, torque, motor) or held by their brake
        driven = {p.drum: p for p in spec.drums}
        self.drive_of = {}
        F0 = np.zeros(n)
        loads, motors, prescribed = [], [], {}
        for d, i in self.drum_q.items():
            p = driven.get(d)
            e = np.zeros(n)
            e[i] = 1.0
            if p is None:
                prescribed[i] = Profile.constant(0.0)
                self.drive_of[d] = ("held", None)
            elif p.kind == "speed":
                prescribed[i] = p.profile
                self.drive_of[d] = ("speed", p)
            elif p.kind == "torque":
                loads.append((e[:, None], profile_signal(p.profile)))
                F0[i] -= self.hold[i]
                self.drive_of[d] = ("torque", p)
            else:
                motors.append(MotorLoad(e, p.motor, model.drums[d].gear_ratio,
                                        model.drums[d].name))
                F0[i] -= self.hold[i]
                self.drive_of[d] = ("motor", p)
        layout = dofs.layout
        for f in spec.forces:
            block = dofs.T[layout.node([f.node])[0]].toarray()         # (3, n)
            G = block.T
            loads.append((G, profile_signal(f.profile)))
            P = block @ np.linalg.pinv(block) if block.any() else np.zeros((3, 3))
            lost = np.abs(f.profile.values - f.profile.values @ P.T).max()
            if lost > 1e-9 * np.abs(f.profile.values).max():
                self.warnings.append(
                    f"force on node '{f.name}': a part of it ({lost:.3g} N) acts where the "
                    "node has no coordinate (effects) and is carried rigidly")
        if len(contacts):
            F0[contacts] += system.f[contacts]        # the weight the ground carries
        self.contacts, self.up = contacts, up
        self.prescribed = prescribed

        # damping of the structure with the prescribed drums held
        keep = np.setdiff1d(np.arange(n), list(prescribed))
        self.free = keep
        self.sub = subsystem(system, keep) if len(prescribed) else system
        C, U, W = self._damping() if damping else (None, None, None)
        self.C = C
        self.eq = Equations(system.M, K_rest, C, U, W, self.R, self.c, self.S0, F0, loads,
                            motors, prescribed, contacts, up)
        self.force_scale = float(max(np.abs(self.S0).max(initial=0.0),
                                     np.abs(self.hanging).max(initial=0.0),
                                     np.abs(system.f).max(initial=0.0),
                                     np.abs(F0).max(initial=0.0), 1e-300))
        self.length_scale = model.length_scale

    def _grounded_tensions(self, contacts):
        """Rope forces with the loads resting on the ground and the ropes that reach
        them just taut (zero force): the static state under gravity with the drums held,
        the loads' coordinates held by the ground and the rope rows touching them left
        out. Statically admissible, so the reference geometry stays in equilibrium."""
        system = self.system
        K, f = system.K.tocsr(), system.f
        touching = np.asarray(abs(self.R[:, contacts]).sum(axis=1)).ravel() > 0 \
            if len(contacts) else np.zeros(len(self.c), dtype=bool)
        # left out: kept at 1e-9 of their stiffness, so that a rope loop hanging free
        # over a sheave (both ends at the grounded block: balanced) stays determinate
        Rg = self.R[touching]
        Ks = (K - Rg.T @ sp.diags((1 - 1e-9) * self.c[touching]) @ Rg).tocsr()
        held = np.union1d(list(self.drum_q.values()), contacts).astype(int)
        free = np.setdiff1d(np.arange(self.n), held)
        q = np.zeros(self.n)
        try:
            if len(free):
                q[free] = spla.splu(Ks[free][:, free].tocsc()).solve(f[free])
            S = self.c * (self.R @ q)
            ok = np.all(np.isfinite(q)) and np.allclose(
                Ks[free] @ q, f[free], rtol=0, atol=1e-8 * max(np.abs(f).max(), 1e-300)) \
                and np.abs(S[touching]).max(initial=0.0) * 1e-9 <= \
                1e-6 * max(np.abs(S[~touching]).max(initial=0.0), np.abs(f).max())
        except RuntimeError:
            ok = False
        if not ok:
            raise ModelError("with the loads on the ground the crane is not held (a "
                             "mechanism once the hoist ropes carry nothing); check the "
                             "model's supports", self.model.scene_file or self.model.file,
                             "analysis.initial")
        S[touching] = 0.0
        return S

    def _contacts(self):
        """Coordinates of the grounded loads along gravity; +1 where they point up."""
        model, spec = self.model, self.spec
        if spec.initial != "grounded":
            return np.zeros(0, dtype=int), np.zeros(0)
        dofs = self.system.dofs
        file = model.scene_file or model.file
        up_dir = -model.gravity / np.linalg.norm(model.gravity)
        out, up = [], []
        for node in spec.grounded:
            name = model.node_names[node]
            if dofs.carrier[node] != -2:
                raise ModelError(f"node '{name}' is carried by a body or fixed; a load "
                                 "resting on the ground must be a point mass at a node of "
                                 "its own", file, "analysis.grounded")
            block = dofs.T[dofs.layout.node([node])[0]].toarray()
            cols = np.flatnonzero(np.abs(block).sum(axis=0) > 0)
            vertical = [j for j in cols if abs(up_dir @ block[:, j]) >
                        1e-9 * np.linalg.norm(block[:, j])]
            if len(vertical) != 1 or abs(abs(up_dir @ block[:, vertical[0]]) -
                                         np.linalg.norm(block[:, vertical[0]])) > \
                    1e-9 * np.linalg.norm(block[:, vertical[0]]):
                raise ModelError(
                    f"load '{name}' rests on the ground, so it needs one vertical "
                    "coordinate: hang it on vertical ropes (with sway off its coordinates "
                    "are the directions its ropes and springs pull)", file,
                    "analysis.grounded")
            j = vertical[0]
            out.append(j)
            up.append(np.sign(up_dir @ block[:, j]))
        return np.array(out, dtype=int), np.array(up)

    def _damping(self):
        """(C, U, W): modal damping C = M V diag(2 zeta w) V^T M of the structure with
        the prescribed drums held (formed, or kept low-rank as U diag(W) U^T on large
        models); `exact`: the viscous b = psi c / (2 pi w_e) of every element at the
        frequency of the mode that most strains it (`damping.element_frequencies`)."""
        kind = self.model.effects.damping
        if kind == "none":
            return None, None, None
        from ..damping import (damping_matrix, element_frequencies,
                               modal_damping_ratios)
        from ..modal import modes
        sub = self.sub
        big = sub.K.shape[0] > SPARSE_DAMPING
        modal = modes(self.model, system=sub, count=SPARSE_DAMPED_MODES if big else None)
        el = ~modal.rigid
        w = modal.omega[el]
        V = np.zeros((self.n, el.sum()))
        V[self.free] = modal.shapes[:, el]
        if kind == "exact":
            rows, beams = element_frequencies(self.system, V, w)
            return damping_matrix(self.system, rows, omega_beams=beams), None, None
        zeta = modal_damping_ratios(sub, modal)[el]
        U = np.asarray(self.system.M @ V)
        W = 2 * zeta * w
        if big:
            self.warnings.append(f"damping: the {el.sum()} lowest modes are damped, the "
                                 "others not")
        if self.n <= DENSE_DAMPING:
            return sp.csr_matrix(U @ (W[:, None] * U.T)), None, None
        return None, U, W

    # ------------------------------------------------------------ outputs
    def drum_torque(self, t, q, v, a, taut):
        """(nd,) whole torque at each drum: applied, or what holds a prescribed speed."""
        out = []
        r = None
        for d, i in self.drum_q.items():
            kind, p = self.drive_of[d]
            if kind == "torque":
                out.append(float(p.profile(t)[0]))
            elif kind == "motor":
                g = self.model.drums[d].gear_ratio
                out.append(g * p.motor.torque(g * v[i])[0])
            else:
                if r is None:
                    r = self.eq.residual(t, q, v, a, taut)
                out.append(self.hold[i] + r[i])
        return np.array(out)

    def highest_omega(self):
        return highest_omega(self.sub)
