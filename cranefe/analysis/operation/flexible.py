"""Elastic structure riding on the mechanism (operation scenes with
`effects: {structure: flexible}`; docs/operations.md "Elastic structure").

A floating frame of reference per rigid set: the nodes of flexible members that no body
carries (the elastic nodes) have displacements u in the frame of the body their members
are anchored to (the ground, or a body moved by prescribed joints), so that

    x = R(t) (X + u) + p(t)                                    (R, p: the body's motion)

and with lumped masses m per node Newton's law m x'' = f, premultiplied by R^T, is

    m u'' = m R^T g + R^T f_ropes - dU/du - m (R^T R'' (X + u) + 2 R^T R' u' + R^T p'')

(the Euler and centrifugal terms R^T R'' = W' + W^2, W = R^T R' the body's angular
velocity as a skew matrix, and Coriolis 2 W u'; e.g. Shabana, Dynamics of Multibody
Systems, 3rd ed., sec. 5.5, eq. 5.93 with a lumped mass). Exact for any motion of the
frame; the strain energy U is that of small strains in the body frame:

    U(z) = 1/2 z^T K z + 1/2 sum_e N_e(z) z_e^T G_e z_e,     N_e = (EA/l)_e a_e . z_e

z = (u, theta) the translations and the rotations of the nodes where beams meet, K the
linear core's elastic stiffness of the members (`assembly.beams.beam_blocks`, trusses and
axial springs by `elements.spring_state`), G_e the geometric stiffness of element e under a
unit axial force (`assembly.beams.beam_geometric_local`; `(I - e e^T)/l` for trusses) and
a_e its elongation row. It is the second-order expansion of the Green strain of each
element (the axial strain with `1/2 int v'^2` of its bending shape): its Hessian at a
state with axial forces N is `K + sum N_e G_e + sum EA/l (a (G z)^T + G z a^T)`, so the
current axial forces stiffen (a spinning blade: Southwell) and the linearisation about
the static state is the linear core's `K + K_g(N_static)` to second order in the static
deflection. The rotations carry no mass and no load (lumped masses, forces at nodes), so
U is minimised over them for the given translations (exact condensation of massless
DOFs, made at the current axial forces since U is quadratic in theta for fixed u):
`theta = -H_rr^-1 H_rt u`, `dU/du` at that theta (envelope theorem), tangent
`H_tt - H_tr H_rr^-1 H_rt`.
"""

import math

import numpy as np

from ...assembly.beams import beam_blocks, beam_geometric_local
from ...assembly.materials import element_sections
from ...assembly.springs import member_geometry
from ...coordinates.layout import Layout
from ...coordinates.members import discretize
from ...elements import beam_axes, to_global
from ...elements.ropes import spring_state
from ...errors import AnalysisError, ModelError
from ...model.model import GROUND

ELASTIC = -3          # Mechanism.carrier of an elastic node


def active(model):
    """Does the scene ask for an elastic structure (and has it members)?"""
    return model.effects.structure == "flexible" and len(model.members) > 0


class ElasticStructure:
    """Elastic nodes, their frames, lumped masses and the members' element arrays.

    Made by `Mechanism` before its coordinates are laid out (`mark`, then `setup`)."""

    def __init__(self, mech, model):
        self.model = model
        self.file = model.file          # the entries refused below are the model's
        nn = len(model.node_names)
        mm = discretize(model, nn)
        self.mm = mm
        self.layout = Layout(nn + mm.n_interior, 0, 0)
        self.coords = np.vstack([model.coords, mm.coords]) if mm.n_interior else \
            np.asarray(model.coords, float)
        carrier = mech.carrier
        members = np.unique(mm.node.ravel())
        anchored = {int(i) for i in members if i < nn and carrier[i] != -2}
        self.en = np.array([int(i) for i in members if int(i) not in anchored], dtype=int)
        if not len(self.en):
            self.nu = 0
            return
        self.comps = np.array([0, 2]) if model.planar else np.arange(3)
        self.rcomps = np.array([4]) if model.planar else np.arange(3, 6)
        self.nt = len(self.comps)
        self.nu = len(self.en) * self.nt
        self.model_nodes = self.en[self.en < nn]      # elastic nodes of the model
        self._check_nodes(mech, model, anchored)

    def _check_nodes(self, mech, model, anchored):
        """What this round refuses (ModelError naming the entry): elastic nodes that are
        a joint's node, supported, or carry rotary inertia."""
        names = model.node_names
        el = set(self.en.tolist())
        for j in model.joints:
            if j.at in el:
                raise ModelError(
                    f"{j.label} is at node '{names[j.at]}' of the elastic structure: a body "
                    "carried by elastic members is not solved by operation scenes yet "
                    "(put the node on a body, or use structure: rigid)", self.file,
                    j.entry)
        for s in model.supports:
            if s.node in el:
                raise ModelError(f"node '{names[s.node]}' of the elastic structure has a "
                                 "support; supports of elastic nodes are not solved by "
                                 "operation scenes yet (put it on the ground)", self.file,
                                 s.entry)
        for i, J in zip(model.masses.nodes, model.masses.inertia):
            if int(i) in el and np.abs(J).max() > 0:
                raise ModelError(f"the point mass at node '{names[i]}' of the elastic "
                                 "structure has a rotary inertia; the elastic structure of "
                                 "an operation scene has lumped masses (translations only): "
                                 "give it none", self.file, f"masses.{names[i]}")

    # ------------------------------------------------------------------ setup
    def setup(self, mech, model):
        """Frames, masses, element arrays, the spans' columns (after `Mechanism._nodes`
        and `_joint_setup`: the carriers and the joint coordinates are known)."""
        mm, nn = self.mm, len(model.node_names)
        sec = element_sections(model, mm)
        self.sec = sec
        where = np.full(self.layout.n_nodes, -1)
        where[self.en] = np.arange(len(self.en))
        self.where = where
        self._frames(mech, model, where)
        # lumped masses: half of each element's rho A l at each end, and point masses
        consistent = sorted({model.members[k].name for k in mm.member[~sec.lumped]})
        if consistent:
            raise ModelError(
                f"member(s) {', '.join(consistent)} have a consistent mass matrix; the "
                "elastic structure of an operation scene has lumped masses this round: give "
                "them mass: lumped", self.file, f"members.{consistent[0]}.mass")
        e, l = member_geometry(model, self.layout, mm, np.arange(len(mm.member)))
        me = np.zeros(self.layout.n_nodes)
        np.add.at(me, mm.node.ravel(), np.repeat(sec.rho * sec.A * l / 2, 2))
        for i, m in zip(model.masses.nodes, model.masses.mass):
            me[i] += m
        self.me = me[self.en]
        light = np.flatnonzero(self.me <= 0)
        if len(light):
            i = self.en[light[0]]
            name = model.node_names[i] if i < nn else mm.names[i - nn]
            raise ModelError(f"node '{name}' of the elastic structure has no mass (rho = 0 "
                             "members and no point mass); operation scenes integrate every "
                             "elastic node: give its members a density", self.file,
                             self._member_entry(i))
        self.Mu = np.repeat(self.me, self.nt)
        self._elements(mech, model, e, l)

    def _member_entry(self, i):
        """'members.NAME' of the first member element at node i."""
        k = np.flatnonzero((self.mm.node == i).any(axis=1))[0]
        return f"members.{self.model.members[self.mm.member[k]].name}"

    def _frame_of(self, mech, b):
        """The body whose motion a body has (the nearest with a driven joint or in the
        linkage, else the ground)."""
        link = set(mech.linear.bodies) if mech.linear is not None else set()
        while b != GROUND and b not in link and mech.parent[b][1] not in mech.driven_joints:
            b = mech.parent[b][0]
        return b

    def _frames(self, mech, model, where):
        """Each connected piece of elastic members rides on one frame: the body all its
        anchors move with."""
        mm, nn = self.mm, len(model.node_names)
        parent = list(range(self.layout.n_nodes))

        def find(x):
            while parent[x] != x:
                parent[x] = parent[parent[x]]
                x = parent[x]
            return x
        for a, b in mm.node:
            if where[a] >= 0 and where[b] >= 0:
                parent[find(a)] = find(b)
        frame = {}
        for k, (a, b) in enumerate(mm.node):
            for x, y in ((a, b), (b, a)):
                if where[x] >= 0 and where[y] < 0:
                    c = mech.carrier[y]
                    f = GROUND if c == GROUND else self._frame_of(mech, int(c))
                    r = find(x)
                    member = model.members[mm.member[k]].name
                    if int(y) in mech.jnodes:
                        d = next(jc["drive"] for jc in mech.jc if int(y) in jc["nodes"])
                        raise ModelError(
                            f"member '{member}' is anchored at node '{model.node_names[y]}' "
                            f"on the bodies that drive '{d.name}' moves as a coordinate: "
                            "an elastic structure on a joint coordinate (torque, force, "
                            "motor or free joint) is not solved yet (prescribe the joint's "
                            "motion with a profile, or use structure: rigid)",
                            model.scene_file or model.file, d.entry)
                    if frame.setdefault(r, (f, member))[0] != f:
                        raise ModelError(
                            f"members '{frame[r][1]}' and '{member}' join nodes of bodies "
                            "that move relative to each other through elastic nodes; an "
                            "elastic structure rides on one body's frame in operation "
                            "scenes (not yet: members between moving bodies)", self.file,
                            f"members.{member}")
        node_frame = np.empty(len(self.en), dtype=int)
        for k, i in enumerate(self.en):
            r = find(int(i))
            if r not in frame:
                name = model.node_names[i] if i < nn else mm.names[i - nn]
                raise ModelError(f"the elastic members at node '{name}' are attached to no "
                                 "body and not to the ground: a free-floating structure is "
                                 "not solved by operation scenes", self.file,
                                 self._member_entry(i))
            node_frame[k] = frame[r][0]
        # a moving joint on a frame that carries elastic structure would ride on the
        # undeformed frame (a trolley on an elastic jib: a moving load): refused
        carrying = set(node_frame.tolist())
        for k, d in mech.driven_joints.items():
            j = model.joints[k]
            child = next((b for b in j.bodies if b != GROUND and b in mech.parent
                          and mech.parent[b][1] == k), None)
            if child is None:
                continue
            pb = mech.parent[child][0]
            if (GROUND if pb == GROUND else self._frame_of(mech, pb)) in carrying:
                raise ModelError(
                    f"drive '{d.name}' moves {j.label} on a body that carries elastic "
                    "members: the moving part would ride on the undeformed frame (a "
                    "trolley travelling along an elastic jib is a moving load on a beam, "
                    "not solved yet); use structure: rigid, or anchor the elastic "
                    "members on the moving body",
                    self.model.scene_file or self.model.file, d.entry)
        self.frames = [(int(f), np.flatnonzero(node_frame == f)) for f in sorted(carrying)]

    def _elements(self, mech, model, e, l):
        """Element arrays on the structure vector z = (u, theta): indices (ne, 12) (-1:
        held or not a coordinate), K_e, unit geometric stiffness G_e, elongation rows a_e
        and EA/l."""
        mm, sec, nt, nu = self.mm, self.sec, self.nt, self.nu
        zmap = np.full(6 * self.layout.n_nodes, -1)
        k = np.arange(len(self.en))
        for j, c in enumerate(self.comps):
            zmap[6 * self.en + c] = k * nt + j
        rot = np.intersect1d(mm.rotation_nodes(), self.en)
        nr = 0
        for c in self.rcomps:
            zmap[6 * rot + c] = nu + nr + np.arange(len(rot))
            nr += len(rot)
        self.nz, self.nr_ = nu + nr, nr
        idx, Km, Gm, a, kax = [], [], [], [], []
        b = np.flatnonzero(mm.beam)
        if len(b):
            blocks, _ = beam_blocks(model, self.layout, mm)
            axes = beam_axes(e[b], mm.orientation[b])
            Gb = to_global(beam_geometric_local(model, self.layout, mm, b, np.ones(len(b)),
                                                l[b]), axes)
            ab = np.zeros((len(b), 12))
            ab[:, 0:3], ab[:, 6:9] = -e[b], e[b]
            idx.append(zmap[blocks.idx])
            Km.append(blocks.mat)
            Gm.append(Gb)
            a.append(ab)
            kax.append(sec.E[b] * sec.A[b] / l[b])
        part = self._trusses(mech, model, zmap, l)
        if part is not None:
            for lst, x in zip((idx, Km, Gm, a, kax), part):
                lst.append(x)
        idx = np.concatenate(idx)
        self.eidx = np.where(idx < 0, self.nz, idx)          # -1 -> a padded zero
        self.eK = np.concatenate(Km)
        self.eG = np.concatenate(Gm)
        self.ea = np.concatenate(a)
        self.ekax = np.concatenate(kax)
        nzp = self.nz + 1
        self.flat = (self.eidx[:, :, None] * nzp + self.eidx[:, None, :]).ravel()
        self.K = self._scatter2(self.eK)
        self.t_ = np.arange(nu)
        self.r_ = np.arange(nu, self.nz)
        self._rr = np.ix_(self.r_, self.r_)
        self._rt = np.ix_(self.r_, self.t_)
        self._tr = np.ix_(self.t_, self.r_)
        self._tt = np.ix_(self.t_, self.t_)
        Krr = self.K[self._rr]
        if nr and np.min(np.abs(np.diag(Krr))) <= 0:
            raise ModelError("a rotation of the elastic structure has no stiffness",
                             self.file, "members")
        self._last = self._theta = None
        self._blk = {}
        # span ends on elastic model nodes: (span indices, elastic node, sign)
        sa, sb = mech.span_a, mech.span_b
        self.span_ends = []
        for f, nodes in self.frames:
            for ends, sg in ((sb, 1.0), (sa, -1.0)):
                s = np.flatnonzero(np.isin(ends, self.en[nodes]))
                if len(s):
                    self.span_ends.append((f, s, self.where[ends[s]], sg))

    def _trusses(self, mech, model, zmap, l):
        """(indices, K, G, a, EA/l) of the trusses and of the axial springs between
        structure nodes, as 12-DOF blocks (rotations zero): the truss kernel
        `spring_state`, `k e e^T` (N = 0) and `(I - e e^T)/l` (unit force, k = 0)."""
        mm, sec = self.mm, self.sec
        tr = np.flatnonzero(~mm.beam)
        pairs = [(mm.node[t, 0], mm.node[t, 1], sec.E[t] * sec.A[t] / l[t]) for t in tr]
        el = set(self.en.tolist())
        for s in model.springs:
            if s.type != "axial" or not (set(s.nodes) & el):
                continue
            bad = [i for i in s.nodes if i not in el and mech.carrier[i] == -2]
            if bad or set(s.nodes) & set(mech.free.tolist()):
                raise ModelError(f"spring '{s.name}' joins the elastic structure to a load or "
                                 "a massless node; not solved by operation scenes yet",
                                 self.file, f"springs.{s.name}")
            pairs.append((s.nodes[0], s.nodes[1], s.stiffness))
        if not pairs:
            return None
        sel = np.r_[0:3, 6:9]
        out = [[], [], [], [], []]
        for na, nb, ka in pairs:
            x = self.coords[[na, nb]]
            dref = np.linalg.norm(x[1] - x[0])
            _, _, _, K6 = spring_state(x, [0], [1], np.array([ka]), np.array([dref]),
                                       np.zeros(1))
            _, _, _, G6 = spring_state(x, [0], [1], np.zeros(1), np.array([dref]),
                                       np.ones(1))
            ee = (x[1] - x[0]) / dref
            K12, G12, a12 = np.zeros((12, 12)), np.zeros((12, 12)), np.zeros(12)
            K12[np.ix_(sel, sel)], G12[np.ix_(sel, sel)] = K6, G6
            a12[0:3], a12[6:9] = -ee, ee
            ii = np.r_[6 * na + np.arange(6), 6 * nb + np.arange(6)]
            for lst, x_ in zip(out, (zmap[ii], K12, G12, a12, ka)):
                lst.append(x_)
        return tuple(np.array(x) for x in out)

    def _scatter2(self, blocks):
        nzp = self.nz + 1
        out = np.bincount(self.flat, weights=blocks.ravel(), minlength=nzp * nzp)
        return out.reshape(nzp, nzp)[:-1, :-1]

    def _scatter1(self, vecs):
        return np.bincount(self.eidx.ravel(), weights=vecs.ravel(),
                           minlength=self.nz + 1)[:-1]

    def labels(self):
        """Labels of the elastic coordinates: 'NODE.ux' (in the frame's axes)."""
        nn, names = len(self.model.node_names), self.model.node_names
        out = []
        for i in self.en:
            nm = names[i] if i < nn else self.mm.names[i - nn]
            out += [f"{nm}.u{'xyz'[c]}" for c in self.comps]
        return out

    # ------------------------------------------------------------------ state
    def _terms(self, z):
        """Per element at z (padded): elongation rows b = a + G z, axial forces
        N = EA/l (a.z + z.G z / 2), and the linear part a.z."""
        ze = z[self.eidx]
        Gz = np.einsum("eij,ej->ei", self.eG, ze)
        az = np.einsum("ek,ek->e", self.ea, ze)
        N = self.ekax * (az + 0.5 * np.einsum("ei,ei->e", ze, Gz))
        return self.ea + Gz, N, az

    def _grad_hess(self, z):
        b, N, az = self._terms(z)
        zz = z[:-1]
        k = self.ekax
        grad = self.K @ zz + self._scatter1((N - k * az)[:, None] * b
                                            + (k * az)[:, None] * (b - self.ea))
        H = self.K + self._scatter2(k[:, None, None] * (b[:, :, None] * b[:, None, :]
                                                        - self.ea[:, :, None]
                                                        * self.ea[:, None, :])
                                    + N[:, None, None] * self.eG)
        return grad, H, N, az

    def strain(self, u):
        """(z, dU/du, tangent, U, N) at translations u (nu,): the rotations condensed
        (module docstring).

        U = 1/2 z^T K z + sum EA/l [delta^2 - (a.z)^2] / 2 with the elongation
        delta = a.z + z.G z / 2 (Green's strain of each element, exact quartic: the
        bending of a free cantilever then stores no membrane energy): gradient
        `K_b z + sum N (a + G z)` (K_b = K less the axial parts), Hessian
        `K + sum EA/l [(a + G z)(a + G z)^T - a a^T] + sum N G`. The rotations solve
        dU/dtheta = 0 by Newton's method from the last state's (N depends on them)."""
        last = self._last
        if last is not None and np.array_equal(last[0], u):
            return last[1]
        z = np.zeros(self.nz + 1)
        z[:self.nu] = u
        if self.nr_:
            z[self.nu:-1] = self._theta if self._theta is not None else \
                -np.linalg.solve(self.K[self._rr], self.K[self._rt] @ u)
        for _ in range(30):
            grad, H, N, az = self._grad_hess(z)
            if not self.nr_:
                break
            d = np.linalg.solve(H[self._rr], grad[self.nu:])
            z[self.nu:-1] -= d
            if np.abs(d).max() <= 1e-14 * max(np.abs(z[self.nu:-1]).max(), 1e-300):
                grad, H, N, az = self._grad_hess(z)
                break
        zz = z[:-1]
        Kt = H[self._tt]
        if self.nr_:
            Kt = Kt - H[self._tr] @ np.linalg.solve(H[self._rr], H[self._rt])
            self._theta = z[self.nu:-1].copy()
        k = self.ekax
        U = 0.5 * zz @ (self.K @ zz) + 0.5 * float((N * N / k - k * az * az).sum())
        out = (zz, grad[:self.nu], Kt, float(U), N)
        self._last = (u.copy(), out)
        return out

    def _split(self, mech, q, v):
        o = mech.nc + mech.nJ
        u = q[o:o + self.nu]
        ne = len(self.en)
        U3 = np.zeros((ne, 3))
        W3 = np.zeros((ne, 3))
        U3[:, self.comps] = u.reshape(ne, self.nt)
        W3[:, self.comps] = v[o:o + self.nu].reshape(ne, self.nt)
        return o, u, U3, W3

    def motions(self, mech, t):
        """The frames' motions at t (cached by time)."""
        c = getattr(self, "_mot", None)
        if c is not None and c[0] == t:
            return c[1]
        mot = mech.body_motions(t)
        self._mot = (t, mot)
        return mot

    def place(self, mech, t, q, v, X, V):
        """Positions and velocities of the elastic model nodes (in place)."""
        mot = self.motions(mech, t)
        _, _, U3, W3 = self._split(mech, q, v)
        nn = len(X)
        for f, k in self.frames:
            R, dR, _, p, dp, _ = mot[f]
            i = self.en[k]
            m = i < nn
            Y = self.coords[i[m]] + U3[k[m]]
            X[i[m]] = Y @ R.T + p
            V[i[m]] = Y @ dR.T + W3[k[m]] @ R.T + dp

    def spans(self, mech, t, D):
        """D (ns, 3, nx) with the elastic coordinates' columns: dx/du = R (comps)."""
        mot = self.motions(mech, t)
        ns = D.shape[0]
        DU = np.zeros((ns, 3, self.nu))
        for f, s, k, sg in self.span_ends:
            R = mot[f][0][:, self.comps]
            cols = k[:, None] * self.nt + np.arange(self.nt)
            DU[s[:, None], :, cols] += sg * R.T[None]
        DU = np.zeros((ns, 3, self.nu)) if ns == 0 else DU
        return np.concatenate([D, DU], axis=2)

    def forces(self, mech, t, q, v, F, K, C):
        """Add the elastic, gravity and inertial forces of the frame's motion on u."""
        o, u, U3, W3 = self._split(mech, q, v)
        sl = slice(o, o + self.nu)
        _, grad, Kt, _, _ = self.strain(u)
        F[sl] -= grad
        K[sl, sl] += Kt
        mot = self.motions(mech, t)
        c, nt = self.comps, self.nt
        for f, k in self.frames:
            R, dR, ddR, _, _, ddp = mot[f]
            A1 = R.T @ dR                      # the body's angular velocity (skew)
            A2 = R.T @ ddR                     # W' + W^2
            Y = self.coords[self.en[k]] + U3[k]
            acc = Y @ A2.T + 2 * W3[k] @ A1.T + R.T @ ddp
            m = self.me[k]
            fi = m[:, None] * ((R.T @ mech.g)[None] - acc)
            rows = (k[:, None] * nt + np.arange(nt)).ravel() + o
            F[rows] += fi[:, c].ravel()
            if A2.any() or A1.any():
                r, cc = self._blocks(k, o)
                K[r, cc] += m[:, None, None] * A2[np.ix_(c, c)][None]
                C[r, cc] += 2 * m[:, None, None] * A1[np.ix_(c, c)][None]

    def _blocks(self, k, o):
        """Row and column indices of the (nt, nt) blocks of nodes k in (n, n)."""
        key = (int(k[0]), len(k), o)
        c = self._blk.get(key)
        if c is None:
            blk = (k[:, None] * self.nt + np.arange(self.nt))[:, :, None] + o
            c = self._blk[key] = np.broadcast_arrays(blk, blk.transpose(0, 2, 1))
        return c

    # ------------------------------------------------------------------ energy
    def energy(self, mech, t, q, v):
        """(T, V_gravity, U) of the elastic nodes."""
        _, u, U3, W3 = self._split(mech, q, v)
        mot = self.motions(mech, t)
        T = Vg = 0.0
        for f, k in self.frames:
            R, dR, _, p, dp, _ = mot[f]
            Y = self.coords[self.en[k]] + U3[k]
            Vel = Y @ dR.T + W3[k] @ R.T + dp
            m = self.me[k]
            T += 0.5 * float(m @ np.einsum("ij,ij->i", Vel, Vel))
            Vg -= float(m @ ((Y @ R.T + p) @ mech.g))
        return T, Vg, self.strain(u)[3]

    def power(self, mech, ev, q, v):
        """Power fed by the frames' prescribed motion into the elastic nodes and through
        them into the ropes: sum w . m (x'' - g) + u' . F_ropes(u) (w = R'(X + u) + p',
        the carried velocity; docs/operations.md)."""
        o, _, U3, W3 = self._split(mech, q, v)
        mot = self.motions(mech, ev.t)
        A = np.zeros((len(self.en), 3))
        A[:, self.comps] = (ev.F[o:o + self.nu] / self.Mu).reshape(-1, self.nt)
        P = float(v[o:o + self.nu] @ ev._flex_rope)
        for f, k in self.frames:
            R, dR, ddR, _, dp, ddp = mot[f]
            if f == GROUND or not (dR.any() or dp.any()):
                continue
            Y = self.coords[self.en[k]] + U3[k]
            w = Y @ dR.T + dp
            acc = Y @ ddR.T + 2 * W3[k] @ dR.T + A[k] @ R.T + ddp
            P += float(self.me[k] @ np.einsum("ij,ij->i", w, acc - mech.g))
        return P

    def settle(self, mech):
        """The static state with the elastic structure: Newton's method on the loads'
        and the elastic coordinates at t = 0 (the ropes' unstretched lengths fixed),
        then the ropes' static forces of that state (S0, taut, holding torques)."""
        n = mech.n
        # at rest before the drives start: the prescribed motions' limits from the left
        # of t = 0 (a profile starting at 0 with an acceleration must not bend the
        # structure in its static state)
        t0 = math.nextafter(0.0, -math.inf)
        q = mech.q0.copy()
        o = mech.nc + mech.nJ
        idx = np.r_[0:mech.nc, o:o + self.nu]
        v = np.zeros(n)
        scale = mech.model.length_scale
        taut = np.ones(len(mech.ropes), bool)
        for it in range(60):
            ev = mech.evaluate(t0, q, v, taut, damping=False, powers=False)
            taut = ev.L >= ev.L0 * (1 - 1e-15)
            ev = mech.evaluate(t0, q, v, taut, damping=False, powers=False)
            dq = np.linalg.solve(ev.K[np.ix_(idx, idx)], ev.F[idx])
            q[idx] += dq
            step = np.abs(dq).max()
            if step <= 1e-12 * scale or (it > 10 and step <= 1e-9 * scale):
                break                    # converged (or at the round-off floor)
        else:
            raise AnalysisError(f"the static state of the elastic structure of "
                                f"{self.file} was not found (60 Newton iterations, last "
                                f"correction {step:.3g} m): a structure that gravity "
                                "buckles, or members too soft for their loads")
        ev = mech.evaluate(t0, q, v, taut, damping=False, powers=False)
        mech.q0 = q
        mech.S0 = ev.S.copy()
        mech.taut0 = ev.S > 0
        mech.hold_torque = np.zeros(mech.nd)
        for j, dd, R in zip(mech.rope_drum, mech.drum_of_end, mech.end_radius):
            mech.hold_torque[dd] += R * mech.S0[j]
        self.u0 = q[o:o + self.nu].copy()
