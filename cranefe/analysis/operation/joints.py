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

(`pair`; in JointChain the quadratic form of the flattened maps [R | p]), exact at
any angle.

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
    on = {int(i) for i in nodes}
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


class Jets:
    """Truncated Taylor series in nz variables up to ORDER of affine maps [R | p]
    (3 x 4, acting on (X, 1)): the monomials, the product's pairs (all, and those with a
    pure power of one variable on the right: a joint's own series), and the maps from
    coefficients to the partial derivatives of order 1, 2, 3."""

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
        # pure powers n e_k of one variable (n = 0..ORDER)
        self.uni = [[idx[tuple(n if i == k else 0 for i in range(nz))]
                     for n in range(ORDER + 1)] for k in range(nz)]
        self.by_var = [table([p for p in pairs if p[1] in set(self.uni[k])])
                       for k in range(nz)]

        def deriv(order):
            shape = (nz,) * order
            Ix = np.zeros(shape, dtype=int)
            F = np.zeros(shape)
            for ks in product(range(nz), repeat=order):
                e = [0] * nz
                for k in ks:
                    e[k] += 1
                Ix[ks] = idx[tuple(e)]
                F[ks] = _fact(e)
            return Ix, F[..., None]
        self.d = [deriv(1), deriv(2), deriv(3)]
        self.ident = np.zeros((nm, 3, 4))
        self.ident[0, :, :3] = np.eye(3)

    def univariate(self, k, Rc, pc):
        """A joint's series in variable k, homogeneous (nm, 4, 4): coefficients Rc
        (ORDER+1, 3, 3), pc (ORDER+1, 3); the constant's last row (0, 0, 0, 1)."""
        B = np.zeros((self.nm, 4, 4))
        u = self.uni[k]
        B[u, :3, :3] = Rc
        B[u, :3, 3] = pc
        B[u[0], 3, 3] = 1.0
        return B

    def compose(self, parent, joint, k):
        """The child's [R_p R_j | R_p p_j + p_p] from the parent's series (nm, 3, 4)
        and a joint's series in variable k (nm, 4, 4)."""
        ia, ib, S = self.by_var[k]
        P = np.matmul(parent[ia], joint[ib])
        return (S @ P.reshape(len(ia), 12)).reshape(-1, 3, 4)

    def derivatives(self, H):
        """The partial derivatives of order 1, 2, 3 (flattened maps, 12 each) from the
        coefficients (d^alpha f = alpha! c_alpha)."""
        Hf = H.reshape(len(H), 12)
        return [Hf[Ix] * F for Ix, F in self.d]


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

    __slots__ = ("C", "F", "Fg", "K", "M", "T", "Vg", "dM", "groups", "pw")


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

    With maps A = [R | p] flattened to 12 numbers, `pair` is the quadratic form
    A W B^T with W = kron(I, Theta~) (kron(proj, Theta~) for a projected set),
    Theta~ = [[Theta, s], [s^T, m]] the homogeneous second moment, and gravity's
    g . (R s + m p) = A . kron(g, (s, m)).
    """

    def __init__(self, chain, rho, sets, groups, g, linear=None):
        self.chain, self.rho = chain, np.asarray(rho, float)
        self.nJ = len(rho)
        self.nz = self.nJ + 1
        self.jets = Jets(self.nz)
        self.sets_spec, self.groups_spec, self.g, self.linear = sets, groups, g, linear
        self.sets = []
        for b, m, s, Th, proj, energy in sets:
            Tt = np.zeros((4, 4))
            Tt[:3, :3], Tt[:3, 3], Tt[3, :3], Tt[3, 3] = Th, s, s, m
            W = np.kron(np.eye(3) if proj is None else proj, Tt)
            gv = np.kron(g, np.append(s, m)) if proj is None else None
            self.sets.append((b, W, gv, energy))
        self.groups = [(b, idx, np.hstack([Xr, np.ones((len(Xr), 1))]), proj)
                       for b, idx, Xr, proj in groups]
        self.bodies = sorted({x[0] for x in sets} | {x[0] for x in groups})

    def motions(self, t, u, left=False):
        """Jets (nm, 3, 4) of every body of the chain at (t, u); `left`: the prescribed
        drives' accelerations approached from the left (a step ending at a breakpoint)."""
        J, nz = self.jets, self.nz
        out = {}
        link = self.linear.motions(t) if self.linear is not None else None
        for b, p, d, sign, hinge, K, K2, point, axis, c in self.chain:
            if link is not None and b in link:
                R, dR, ddR, pp, dp, ddp = link[b]
                H = np.zeros((J.nm, 3, 4))
                for n, (Rn, pn) in enumerate(((R, pp), (dR, dp), (ddR / 2, ddp / 2))):
                    H[J.uni[nz - 1][n], :, :3], H[J.uni[nz - 1][n], :, 3] = Rn, pn
                out[b] = H
                continue
            par = out.get(p, J.ident)
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
            out[b] = J.compose(par, J.univariate(k, np.array(series(fR, e)),
                                                 np.array(series(fp, e))), k)
        return out

    def state(self, t, u, v, left=False, tangent=True):
        """Mass matrix, generalised forces (Kane's inertia terms and gravity), their
        tangents, energies and the nodes' positions and derivatives at (t, u, u')."""
        nJ, nz = self.nJ, self.nz
        jets = self.motions(t, u, left)
        w = np.append(np.asarray(v, float), 1.0)
        ww = np.outer(w, w).ravel()
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
            H = jets[b]
            D1, D2, D3 = self.jets.derivatives(H)
            # fields: x_i (nJ), x''_0, d x''_0 / du'_k (nJ), d x''_0 / du_k (nJ), x_t
            B = np.concatenate([D1[:nJ], (ww @ D2.reshape(nz * nz, 12))[None],
                                2 * np.matmul(w, D2[:nJ]),
                                np.tensordot(ww, D3[:, :, :nJ].reshape(nz * nz, nJ, 12),
                                             axes=1),
                                D1[nJ:]])
            per[b] = (H[0].ravel(), B, D2[:nJ, :nJ].reshape(nJ * nJ, 12), w @ D1)
        pw = []
        for b, W, gv, energy in self.sets:
            H0, B, X2, vel = per[b]
            BW = B[:nJ] @ W
            G1 = BW @ B.T                                   # x_i . every field
            M += G1[:, :nJ]
            F -= G1[:, nJ]
            if tangent:
                C += G1[:, nJ + 1:2 * nJ + 1]
                G2 = X2 @ W @ B[:nJ + 1].T                   # x_ik . (x_j, x''_0)
                K += G2[:, nJ].reshape(nJ, nJ) + G1[:, 2 * nJ + 1:3 * nJ + 1]
                G = G2[:, :nJ].reshape(nJ, nJ, nJ)           # [i, k, j]
                dM += G.transpose(0, 2, 1) + G.transpose(2, 0, 1)
            if gv is not None:
                fg = B[:nJ] @ gv
                F += fg
                Fg += fg
                if tangent:
                    K -= (X2 @ gv).reshape(nJ, nJ)
            if energy:
                T += 0.5 * float(vel @ W @ vel)
                Vg -= float(H0 @ gv)
            if B[-1].any():
                pw.append((B[:nJ], B[nJ], B[-1], W, gv))
        groups = []
        for b, idx, Xh, proj in self.groups:
            H0, B, X2, vel = per[b]
            XJ = np.matmul(B[:nJ].reshape(nJ, 3, 4), Xh.T).transpose(2, 1, 0)
            XJJ = np.matmul(X2.reshape(nJ * nJ, 3, 4), Xh.T).transpose(2, 1, 0) \
                .reshape(len(idx), 3, nJ, nJ)
            if proj is not None:
                XJ = np.einsum("ij,kja->kia", proj, XJ)
                XJJ = np.einsum("ij,kjab->kiab", proj, XJJ)
                X = V = None
            else:
                X = Xh @ H0.reshape(3, 4).T
                V = Xh @ vel.reshape(3, 4).T
            groups.append((idx, X, V, XJ, XJJ, proj is None))
        st.M, st.dM, st.F, st.Fg, st.K, st.C = M, dM, F, Fg, K, C
        st.T, st.Vg, st.groups, st.pw = T, Vg, groups, pw
        return st

    def power(self, st, a):
        """Power of the prescribed motions on the sets the coordinates carry:
        int (x'' - g) . x_t dm, x_t the velocity with u' held (the carried velocity),
        x'' = x''_0 + sum x_i u''_i with the coordinates' accelerations a."""
        P = 0.0
        for X1, A0, xt, W, gv in st.pw:
            P += float((A0 + a @ X1) @ W @ xt)
            if gv is not None:
                P -= float(xt @ gv)
        return P
