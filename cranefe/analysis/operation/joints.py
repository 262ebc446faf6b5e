"""Joint coordinates of an operation scene: the bodies that torque, force, motor or free
joints carry, with any joints below them (docs/operations.md, "Joint coordinates").

Every point of a rigid set (the bodies moving with one joint, and the point masses at
their nodes) moves as x = R(u, t) X + p(u, t): X its reference position, u the joint
coordinates above it, t the prescribed drives' time. Its mass properties in the
reference frame are the mass m, the first moment s = int X dm and the second moment
Theta = int X X^T dm; for a body of mass m_b, com c and inertia I_c about the com
(global axes) int (X - c)(X - c)^T dm = tr(I_c)/2 I - I_c, so
Theta_b = tr(I_c)/2 I - I_c + m_b c c^T; a point mass adds m X X^T (and its rotary
inertia as a body of zero size). Integrals of two affine fields over a set are then

    int (A X + a) . (B X + b) dm = tr(A Theta B^T) + a . (B s) + b . (A s) + m a . b

(`gram`), exact at any angle.

The maps (R, p) are composed along the tree of bodies as truncated Taylor series ("jets")
in z = (u_1 .. u_n, t) about the current (u, t), to third order: a joint's own map is a
series in one variable (a hinge's Rodrigues rotation and its derivatives, a slider's
translation; a prescribed joint's s(t) to second order, its jerk left out: only the
derivatives with at most two t's are used), and the composition R_b = R_p R_j,
p_b = R_p p_j + p_p is the product of series. The partial derivatives x_a, x_ab, x_abc
(a, b, c among the u's and t) are then read off the coefficients (d^alpha f = alpha! c).
With w = (u', 1) Kane's method gives (docs/operations.md, "Joint coordinates"):

    M_ij    = int x_i . x_j dm                              (mass matrix, u-block)
    Q_i     = - int x_i . x''_0 dm,  x''_0 = sum_ab x_ab w_a w_b   (Coriolis, centrifugal,
                                                                    carried accelerations)
    dQ_i/du'_k = - int x_i . 2 sum_b x_kb w_b dm
    dQ_i/du_k  = - int (x_ik . x''_0 + x_i . sum_ab x_abk w_a w_b) dm
    dM_ij/du_k = int (x_ik . x_j + x_i . x_jk) dm
    gravity  g . (R_i s + m p_i), its derivative g . (R_ik s + m p_ik)
"""

from itertools import product

import numpy as np

ORDER = 3


def subtree_mass(model, bodies, nodes):
    """(m, s (3,), Theta (3, 3)) of the bodies (indices) and the point masses at
    `nodes` (node indices carried by those bodies), reference frame."""
    m, s, Th = 0.0, np.zeros(3), np.zeros((3, 3))
    I3 = np.eye(3)
    for bi in bodies:
        b = model.bodies[bi]
        if b.mass <= 0:
            continue
        c = np.asarray(b.com, float)
        Ic = np.asarray(b.inertia, float)
        m += b.mass
        s += b.mass * c
        Th += 0.5 * np.trace(Ic) * I3 - Ic + b.mass * np.outer(c, c)
    ms = model.masses
    on = set(int(i) for i in nodes)
    for k, i in enumerate(ms.nodes):
        if int(i) not in on:
            continue
        X = np.asarray(model.coords[i], float)
        mk = float(ms.mass[k])
        Ic = np.asarray(ms.inertia[k], float) if ms.inertia is not None else np.zeros((3, 3))
        m += mk
        s += mk * X
        Th += 0.5 * np.trace(Ic) * I3 - Ic + mk * np.outer(X, X)
    return m, s, Th


def pair(A, a, B, b, m, s, Th):
    """int (A X + a) . (B X + b) dm over a rigid set with mass properties (m, s, Th)."""
    return float(np.einsum("ij,jk,ik->", A, Th, B) + a @ (B @ s) + b @ (A @ s)
                 + m * (a @ b))


def gram(A, a, B, b, m, s, Th):
    """`pair` of every field of (A (na, 3, 3), a (na, 3)) with every one of (B, b):
    (na, nb)."""
    return (np.einsum("aij,jl,bil->ab", A, Th, B) + a @ (B @ s).T + (A @ s) @ b.T
            + m * (a @ b.T))


class Jets:
    """Index tables of truncated Taylor series in nz variables up to ORDER: monomials,
    the product's pairs (all, and those with a pure power of one variable on the
    right: a joint's own series), and the maps from coefficients to the partial
    derivatives of order 1, 2, 3."""

    def __init__(self, nz):
        self.nz = nz
        mono = [a for a in product(range(ORDER + 1), repeat=nz) if sum(a) <= ORDER]
        mono.sort(key=lambda a: (sum(a), [-x for x in a]))
        self.mono = mono
        idx = {a: k for k, a in enumerate(mono)}
        self.nm = nm = len(mono)
        pairs = [(idx[a], idx[b], idx[tuple(x + y for x, y in zip(a, b))])
                 for a in mono for b in mono if sum(a) + sum(b) <= ORDER]

        def table(ps):
            ia = np.array([p[0] for p in ps], dtype=int)
            ib = np.array([p[1] for p in ps], dtype=int)
            S = np.zeros((nm, len(ps)))
            S[[p[2] for p in ps], np.arange(len(ps))] = 1.0
            return ia, ib, S
        self.full = table(pairs)
        # pure powers n e_k of one variable (n = 0..ORDER)
        self.uni = [[idx[tuple(n if i == k else 0 for i in range(nz))]
                     for n in range(ORDER + 1)] for k in range(nz)]
        self.by_var = [table([p for p in pairs if p[1] in set(self.uni[k])])
                       for k in range(nz)]

        def deriv(order):
            shape = (nz,) * order
            I = np.zeros(shape, dtype=int)
            F = np.zeros(shape)
            for ks in product(range(nz), repeat=order):
                e = [0] * nz
                for k in ks:
                    e[k] += 1
                I[ks] = idx[tuple(e)]
                F[ks] = _fact(e)
            return I, F
        self.d1 = deriv(1)
        self.d2 = deriv(2)
        self.d3 = deriv(3)

    def constant(self, R, p):
        Rj = np.zeros((self.nm, 3, 3))
        pj = np.zeros((self.nm, 3))
        Rj[0], pj[0] = R, p
        return Rj, pj

    def univariate(self, k, Rc, pc):
        """A joint's series in variable k: coefficients Rc (ORDER+1, 3, 3), pc."""
        Rj = np.zeros((self.nm, 3, 3))
        pj = np.zeros((self.nm, 3))
        Rj[self.uni[k]] = Rc
        pj[self.uni[k]] = pc
        return Rj, pj

    def compose(self, parent, joint, k):
        """(R_p R_j, R_p p_j + p_p) of the parent's jets and a joint's series in
        variable k (k None: any series)."""
        Rp, pp = parent
        Rj, pj = joint
        ia, ib, S = self.full if k is None else self.by_var[k]
        A = Rp[ia]
        R = (S @ np.einsum("pij,pjk->pik", A, Rj[ib]).reshape(len(ia), 9)).reshape(-1, 3, 3)
        p = S @ np.einsum("pij,pj->pi", A, pj[ib]) + pp
        return R, p

    def derivatives(self, R, p):
        """((R_a, p_a), (R_ab, p_ab), (R_abc, p_abc)) from the coefficients."""
        out = []
        for I, F in (self.d1, self.d2, self.d3):
            out.append((R[I] * F[..., None, None], p[I] * F[..., None]))
        return out


def _fact(e):
    out = 1.0
    for x in e:
        for k in range(2, x + 1):
            out *= k
    return out


def series(f, e):
    """Taylor coefficients (ORDER + 1) of f(s0 + eps), eps = e1 z + e2 z^2 (+ O(z^3)),
    from f's derivatives f = (f0, f1, f2, f3) at s0."""
    f0, f1, f2, f3 = f
    e1, e2 = e
    return [f0, f1 * e1, f1 * e2 + f2 * (e1 * e1 / 2), f2 * (e1 * e2) + f3 * (e1 ** 3 / 6)]


def hinge_series(K, K2, point, ang):
    """Derivatives by the angle of Rodrigues' R = I + sin K + (1 - cos) K^2 and of
    p = a - R a (elements.motion.hinge_motion): (R, R', R'', R'''), (p, ...)."""
    sn, cs = np.sin(ang), np.cos(ang)
    R = np.eye(3) + sn * K + (1 - cs) * K2
    R1 = cs * K + sn * K2
    R2 = -sn * K + cs * K2
    R3 = -cs * K - sn * K2
    return (R, R1, R2, R3), (point - R @ point, -R1 @ point, -R2 @ point, -R3 @ point)


def slider_series(axis, s):
    Z = np.zeros((3, 3))
    z = np.zeros(3)
    return (np.eye(3), Z, Z, Z), (s * axis, axis, z, z)


def side_motion(motion, t, left=False):
    """(s, s', s'') of a piecewise constant-jerk profile (profiles.Motion) at t, the
    acceleration (and jerk) of the segment after t, or with `left` of the segment before
    it: at a breakpoint the two limits differ. A time within 1e-12 (relative) of a
    breakpoint is taken at it (a step's end t0 + h may miss it by a rounding)."""
    tl = motion.t
    eps = 1e-12 * max(1.0, abs(t))
    k = int(np.searchsorted(tl, t - eps if left else t + eps, side="right")) - 1
    if k < 0:
        return motion(t) if t < tl[0] else (float(motion.s[0]), float(motion.v[0]), 0.0)
    if k >= len(tl) - 1:
        k = len(tl) - 1
        tau = t - tl[k]
        return float(motion.s[k] + motion.v[k] * tau), float(motion.v[k]), 0.0
    tau = t - tl[k]
    s, v, a, jk = motion.s[k], motion.v[k], motion.a[k], motion.j[k]
    return (float(s + v * tau + a * tau * tau / 2 + jk * tau ** 3 / 6),
            float(v + a * tau + jk * tau * tau / 2), float(a + jk * tau))


class JointState:
    """The joint coordinates' terms at one (t, u, u') (JointChain.state)."""

    __slots__ = ("M", "dM", "F", "Fg", "K", "C", "T", "Vg", "groups", "pw")


class JointChain:
    """The bodies below joint coordinates, composed as jets (module docstring).

    chain : [(body, parent, drive or None, sign, hinge, K, K2, point, axis, c)] in tree
        order (the bodies under a joint coordinate and their ancestors); c the
        coordinate's index for a torque, force, motor or free joint, else None.
    rho : (nJ,) the coordinates' scales (u = rho s).
    sets : [(body, m, s, Theta, proj, energy)] rigid sets moving with `body`; proj a
        (3, 3) projection (the horizontal inertia of a load guided by the body, sway
        off) or None; energy: whether its kinetic and potential energy are counted here.
    groups : [(body, node indices, X_ref (k, 3), proj)] the nodes moving with `body`.
    linear : a LinkageDrive (its bodies' motions in time) or None.
    """

    def __init__(self, chain, rho, sets, groups, g, linear=None):
        self.chain, self.rho = chain, np.asarray(rho, float)
        self.nJ = nJ = len(rho)
        self.nz = nJ + 1
        self.jets = Jets(self.nz)
        self.sets, self.groups_spec, self.g, self.linear = sets, groups, g, linear
        self.ident = self.jets.constant(np.eye(3), np.zeros(3))
        self.bodies = sorted({s[0] for s in sets} | {gr[0] for gr in groups})

    def motions(self, t, u, left=False):
        """Jets (R, p) of every body of the chain at (t, u); `left`: the prescribed
        drives' accelerations approached from the left (a step ending at a breakpoint)."""
        J, nz = self.jets, self.nz
        out = {}
        link = self.linear.motions(t) if self.linear is not None else None
        for b, p, d, sign, hinge, K, K2, point, axis, c in self.chain:
            if link is not None and b in link:
                R, dR, ddR, pp, dp, ddp = link[b]
                out[b] = J.univariate(nz - 1, np.array([R, dR, ddR / 2, 0 * R]),
                                      np.array([pp, dp, ddp / 2, 0 * pp]))
                continue
            par = out.get(p, self.ident)
            if d is None:
                out[b] = par
                continue
            if c is not None:
                s0, e, k = u[c] / self.rho[c], (sign / self.rho[c], 0.0), c
            else:
                s0, ds, dds = side_motion(d.motion, t, left)
                e, k = (sign * ds, sign * dds / 2), nz - 1
            fR, fp = hinge_series(K, K2, point, sign * s0) if hinge else \
                slider_series(axis, sign * s0)
            jt = J.univariate(k, np.array(series(fR, e)), np.array(series(fp, e)))
            out[b] = jt if par is self.ident else J.compose(par, jt, k)
        return out

    def state(self, t, u, v, left=False, tangent=True):
        """Mass matrix, generalised forces (Kane's inertia terms and gravity), their
        tangents, energies and the nodes' positions and derivatives at (t, u, u')."""
        nJ, g = self.nJ, self.g
        jets = self.motions(t, u, left)
        w = np.append(np.asarray(v, float), 1.0)
        st = JointState()
        M = np.zeros((nJ, nJ))
        dM = np.zeros((nJ, nJ, nJ))
        F = np.zeros(nJ)
        Fg = np.zeros(nJ)
        K = np.zeros((nJ, nJ))
        C = np.zeros((nJ, nJ))
        T = Vg = 0.0
        per = {}
        for b in self.bodies:
            R, p = jets[b]
            (R1, p1), (R2, p2), (R3, p3) = self.jets.derivatives(R, p)
            A0 = (np.einsum("abij,a,b->ij", R2, w, w), np.einsum("abi,a,b->i", p2, w, w))
            vel = (np.einsum("aij,a->ij", R1, w), np.einsum("ai,a->i", p1, w))
            per[b] = (R[0], p[0], R1, p1, R2, p2, R3, p3, A0, vel)
        pw = []
        for b, m, s, Th, proj, energy in self.sets:
            R0, p0, R1, p1, R2, p2, R3, p3, A0, vel = per[b]
            # fields: x_i (nJ), x''_0, d x''_0 / du'_k (nJ), d x''_0 / du_k (nJ),
            # x_t; and x_ik (nJ^2)
            BR = np.concatenate([R1[:nJ], A0[0][None],
                                 2 * np.einsum("kbij,b->kij", R2[:nJ], w),
                                 np.einsum("abkij,a,b->kij", R3[:, :, :nJ], w, w),
                                 R1[nJ][None]])
            Bp = np.concatenate([p1[:nJ], A0[1][None],
                                 2 * np.einsum("kbi,b->ki", p2[:nJ], w),
                                 np.einsum("abki,a,b->ki", p3[:, :, :nJ], w, w),
                                 p1[nJ][None]])
            X2R, X2p = R2[:nJ, :nJ].reshape(-1, 3, 3), p2[:nJ, :nJ].reshape(-1, 3)
            if proj is not None:
                BR, Bp = proj @ BR, Bp @ proj.T
                X2R, X2p = proj @ X2R, X2p @ proj.T
            G1 = gram(BR[:nJ], Bp[:nJ], BR, Bp, m, s, Th)     # x_i . every field
            M += G1[:, :nJ]
            F -= G1[:, nJ]
            if tangent:
                C += G1[:, nJ + 1:2 * nJ + 1]
                G2 = gram(X2R, X2p, BR[:nJ + 1], Bp[:nJ + 1], m, s, Th)
                K += G2[:, nJ].reshape(nJ, nJ) + G1[:, 2 * nJ + 1:3 * nJ + 1]
                G = G2[:, :nJ].reshape(nJ, nJ, nJ)                 # [i, k, j]
                dM += G.transpose(0, 2, 1) + G.transpose(2, 0, 1)
            if proj is None:
                fg = g @ R1[:nJ] @ s + m * (p1[:nJ] @ g)
                F += fg
                Fg += fg
                if tangent:
                    K -= g @ R2[:nJ, :nJ] @ s + m * (p2[:nJ, :nJ] @ g)
            if energy:
                T += 0.5 * pair(*vel, *vel, m, s, Th)
                Vg -= float(g @ (R0 @ s + m * p0))
            if BR[-1].any() or Bp[-1].any():
                pw.append(((BR[:nJ], Bp[:nJ]), (BR[nJ:nJ + 1], Bp[nJ:nJ + 1]),
                           (BR[-1:], Bp[-1:]), m, s, Th, proj is None))
        groups = []
        for b, idx, Xr, proj in self.groups_spec:
            R0, p0, R1, p1, R2, p2, R3, p3, A0, vel = per[b]
            XJ = np.einsum("kj,aij->kia", Xr, R1[:nJ]) + p1[:nJ].T
            XJJ = np.einsum("kj,abij->kiab", Xr, R2[:nJ, :nJ]) + \
                p2[:nJ, :nJ].transpose(2, 0, 1)
            if proj is not None:
                XJ = np.einsum("ij,kja->kia", proj, XJ)
                XJJ = np.einsum("ij,kjab->kiab", proj, XJJ)
                X = V = None
            else:
                X = Xr @ R0.T + p0
                V = Xr @ vel[0].T + vel[1]
            groups.append((idx, X, V, XJ, XJJ, proj is None))
        st.M, st.dM, st.F, st.Fg, st.K, st.C = M, dM, F, Fg, K, C
        st.T, st.Vg, st.groups, st.pw = T, Vg, groups, pw
        return st

    def power(self, st, a):
        """Power of the prescribed motions on the sets the coordinates carry:
        int (x'' - g) . x_t dm, x_t the velocity with u' held (the carried velocity),
        x'' = x''_0 + sum x_i u''_i with the coordinates' accelerations a."""
        P = 0.0
        for (XR, Xp), (AR, Ap), (tR, tp), m, s, Th, grav in st.pw:
            accR = AR[0] + np.einsum("kij,k->ij", XR, a)
            accp = Ap[0] + a @ Xp
            P += pair(accR, accp, tR[0], tp[0], m, s, Th)
            if grav:
                P -= float(self.g @ (tR[0] @ s + m * tp[0]))
        return P
