"""Value tests of the joint chain of cranefe/analysis/operation/joints.py (issue 20,
mutation testing): `series`, `side_motion`, the jets (`Jets`) and `JointChain`'s
motions, mass matrix M_J(u, t), Kane's terms, tangents, energies, nodes and power.

References, each independent of the code's jets and of its `pair`/Theta identity:

- `series`: the Taylor coefficients of sin(s0 + e1 z + e2 z^2) by mpmath.taylor;
- `side_motion`: a constant-jerk profile's state evaluated by hand;
- a slewing jib with a trolley (both joint coordinates, or the trolley prescribed): a
  hand Lagrangian. The jib turns by phi about the vertical axis through a, the trolley
  runs r along the jib; its points rho = X - a + r e_x (reference frame) give
  T = 1/2 J(r) phi'^2 - C phi' r' + 1/2 m_t r'^2, J(r) = J_jib + sum m (rho_x^2 + rho_y^2),
  C = sum m rho_y (x_phi . x_r = -rho_y), so with u = (phi, r) and no gravity along the
  horizontal motions: M = [[J, -C], [-C, m_t]], Kane's (Lagrange's) inertia terms
  F_phi = -J'(r) r' phi' = -2 S r' phi' (S = sum_trolley m rho_x), F_r = S phi'^2;
  K = -dF/du, C = -dF/du', dM/dr = [[2 S', 0], [0, 0]] with S' = m_t;
- a six-body chain (a prescribed gantry slider, a tilted slewing hinge coordinate with
  sign -1 and scale rho = 2, a trolley slider coordinate with rho = 0.5 on it, a
  prescribed hook hinge below, a body fixed to the hook) and a chain under a linkage's
  motion: the maps composed in plain numpy from the joints' closed forms (Rodrigues'
  rotation, s(t) = s + s' dt + s'' dt^2 / 2), evaluated at complex points, and their
  partial derivatives up to third order by Cauchy's integral formula (the Taylor
  coefficients as the FFT of samples on a torus of radius 0.5, Lyness and Moler 1967),
  not by the code's products of series; the rigid sets as point clouds, every integral
  a sum over the points: M, F, T, V, the nodes' positions, velocities and derivatives
  and the power by their definitions (M_ij = sum m x_i . x_j, F_i = sum m x_i .
  (g - x''_0), ...), the tangents K = -dF/du, C = -dF/du' and dM/du by central
  differences of those references.

Tolerances: exact-formula comparisons 1e-11 to 1e-12 relative to the matrix's scale
(sums of a few hundred products of O(1)-O(100) numbers, round-off ~1e-14; Cauchy's
formula with 16 samples per variable: aliasing 0.5^16 / 16! ~ 1e-18, round-off
1e-16 / 0.5^3 ~ 1e-15); central differences with h = 1e-5 on functions of O(1)
curvature: truncation h^2 ~ 1e-10, round-off 1e-16 / h ~ 1e-11, asserted at 1e-7.
"""

from types import SimpleNamespace

import mpmath
import numpy as np

from cranefe.analysis.operation.joints import JointChain, series, side_motion
from cranefe.analysis.operation.profiles import Motion

G = np.array([0.3, -0.2, -9.81])           # tilted, so that every axis feels gravity


def _unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def _skew(n):
    return np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])


def close(a, b, rel, scale=None):
    a, b = np.asarray(a, float), np.asarray(b, float)
    s = scale if scale is not None else max(1.0, float(np.max(np.abs(b))))
    return a.shape == b.shape and float(np.max(np.abs(a - b), initial=0.0)) <= rel * s


# -------------------------------------------------------------------- series, profiles

def test_series_is_the_taylor_expansion_of_the_composition():
    """f(s0 + e1 z + e2 z^2) for f = sin: mpmath's Taylor coefficients (50 digits)."""
    s0, e1, e2 = 0.7, -1.3, 0.45
    f = (np.sin(s0), np.cos(s0), -np.sin(s0), -np.cos(s0))
    got = series(f, (e1, e2))
    mpmath.mp.dps = 50
    ref = mpmath.taylor(lambda z: mpmath.sin(s0 + e1 * z + e2 * z * z), 0, 3)
    mpmath.mp.dps = 15
    assert len(got) == 4
    for g, r in zip(got, ref):
        assert abs(g - float(r)) < 1e-15


def _profile():
    """A rest at speed 0.2 until t0 = 1, then 2 s of a = 0.5, jerk 0.3, then 1 s of
    a = -0.4: by hand s(1) = 0.2, s(3) = 0.2 + 0.4 + 1.0 + 0.4 = 2.0,
    v(3) = 0.2 + 1.0 + 0.6 = 1.8, a(3-) = 0.5 + 0.6 = 1.1, a(3+) = -0.4,
    s(4) = 2.0 + 1.8 - 0.2 = 3.6, v(4) = 1.4."""
    return Motion.build(1.0, [(2.0, 0.5, 0.3), (1.0, -0.4, 0.0)], "table", v0=0.2)


def test_side_motion_by_hand():
    m = _profile()
    cases = [
        # (t, left, (s, s', s''))
        (2.0, False, (0.7, 0.85, 0.8)),            # tau = 1: 0.2+0.2+0.25+0.05
        (2.0, True, (0.7, 0.85, 0.8)),
        (3.0, False, (2.0, 1.8, -0.4)),            # a breakpoint: the segment after
        (3.0, True, (2.0, 1.8, 1.1)),              # ... and before
        (3.0 - 2e-12, False, (2.0, 1.8, -0.4)),    # within 1e-12 |t|: at the breakpoint
        (3.0 + 2e-12, True, (2.0, 1.8, 1.1)),
        (3.0 - 1e-9, False, (2.0, 1.8, 1.1)),      # beyond: the segment it is in
        (1.0 - 1.5e-12, False, (0.2, 0.2, 0.0)),   # 1.5e-12 before t0 = 1: not at it
        (0.5, False, (0.1, 0.2, 0.0)),             # before the profile: v0 t
        (1.0, True, (0.2, 0.2, 0.0)),              # its start from the left: the rest
        (1.0, False, (0.2, 0.2, 0.5)),
        (4.0, True, (3.6, 1.4, -0.4)),
        (4.0, False, (3.6, 1.4, 0.0)),             # after the end: constant speed
        (5.5, False, (3.6 + 1.4 * 1.5, 1.4, 0.0)),
    ]
    for t, left, ref in cases:
        got = side_motion(m, t, left)
        assert len(got) == 3
        # 1e-8 covers the cases 2e-12 and 1e-9 off a breakpoint (|s'| |dt| < 2e-9)
        assert np.allclose(got, ref, rtol=0, atol=1e-8), (t, left, got, ref)


def test_side_motion_is_left_by_default_false():
    m = _profile()
    assert side_motion(m, 3.0)[2] == -0.4


def test_side_motion_holds_the_speed_after_the_last_breakpoint():
    """t[-1] ends the last segment (profiles.Motion): after it the speed is constant,
    whatever acceleration and jerk the arrays hold there (5 and 7 here)."""
    m = Motion(np.array([0.0, 1.0]), np.array([0.0, 1.0]), np.array([1.0, 1.0]),
               np.array([0.0, 5.0]), np.array([0.0, 7.0]))
    for t, left, ref in ((1.0, False, (1.0, 1.0, 0.0)), (2.5, False, (2.5, 1.0, 0.0)),
                         (2.5, True, (2.5, 1.0, 0.0)), (0.5, False, (0.5, 1.0, 0.0))):
        assert np.allclose(side_motion(m, t, left), ref, rtol=0, atol=1e-15), (t, left)


# --------------------------------------------------- slewing jib + trolley, by hand

A_PIV = np.array([1.0, 2.0, 0.0])         # the slewing axis: vertical through A_PIV


def _jib_trolley(trolley_drive=None):
    """Jib: points (X, m) about the axis; trolley: points on a rail along x at height
    30, its com off the rail in y. Chain entries (body, parent, drive, sign, hinge, K,
    K2, point, axis, coordinate)."""
    ez = np.array([0.0, 0.0, 1.0])
    ex = np.array([1.0, 0.0, 0.0])
    K = _skew(ez)
    jib_X = np.array([[3.0, 2.0, 30.0], [13.0, 2.5, 30.0], [25.0, 1.0, 31.0]])
    jib_m = np.array([500.0, 1500.0, 800.0])
    tr_X = np.array([[11.0, 2.7, 30.5], [12.0, 1.6, 29.8]])
    tr_m = np.array([250.0, 350.0])
    drive = SimpleNamespace(motion=trolley_drive) if trolley_drive is not None else True
    chain = [(0, -1, True, 1.0, True, K, K @ K, A_PIV, None, 0),
             (1, 0, drive, 1.0, False, None, None, np.zeros(3), ex,
              None if trolley_drive is not None else 1)]
    sets = [(b, float(m.sum()), m @ X, np.einsum("k,ki,kj->ij", m, X, X), None, True)
            for b, (X, m) in ((0, (jib_X, jib_m)), (1, (tr_X, tr_m)))]
    nJ = 1 if trolley_drive is not None else 2
    ch = JointChain(chain, [1.0] * nJ, sets, [], np.array([0.0, 0.0, -9.81]))
    return ch, (jib_X, jib_m), (tr_X, tr_m)


def _hand(phi, r, jib, tr):
    """J(r), C, S, m_t of the hand Lagrangian (module docstring)."""
    (jX, jm), (tX, tm) = jib, tr
    rj = jX - A_PIV
    rt = tX - A_PIV + np.array([r, 0.0, 0.0])
    J = float(jm @ (rj[:, 0] ** 2 + rj[:, 1] ** 2) + tm @ (rt[:, 0] ** 2 + rt[:, 1] ** 2))
    return J, float(tm @ rt[:, 1]), float(tm @ rt[:, 0]), float(tm.sum())


def test_slewing_jib_with_a_trolley_both_coordinates_against_a_hand_lagrangian():
    ch, jib, tr = _jib_trolley()
    phi, r, w, v = 0.7, 2.5, 0.3, -1.2
    st = ch.state(0.0, np.array([phi, r]), np.array([w, v]))
    J, C, S, mt = _hand(phi, r, jib, tr)
    assert close(st.M, [[J, -C], [-C, mt]], 1e-12)
    # F = dT/du - d/dt dT/du' at u'' = 0: dT/dphi = 0, dT/dr = S w^2 (J' = 2 S);
    # d/dt (J w - C v) = 2 S v w, d/dt (-C w + m v) = 0 (C does not depend on r)
    assert close(st.F, [-2 * S * v * w, S * w * w], 1e-12, scale=J)
    assert not st.Fg.any()                     # gravity is along the slewing axis
    # K = -dF/du (S' = m_t), C = -dF/du'
    assert close(st.K, [[0.0, 2 * mt * v * w], [0.0, -mt * w * w]], 1e-12, scale=J)
    assert close(st.C, [[2 * S * v, 2 * S * w], [-2 * S * w, 0.0]], 1e-12, scale=J)
    dM = np.zeros((2, 2, 2))
    dM[0, 0, 1] = 2 * S                        # dJ/dr; dC/dr = 0
    assert close(st.dM, dM, 1e-12, scale=J)
    assert np.isclose(st.T, 0.5 * J * w * w - C * w * v + 0.5 * mt * v * v, rtol=1e-12)
    # the potential: -g . sum m x, heights unchanged by the motions
    (jX, jm), (tX, tm) = jib, tr
    assert np.isclose(st.Vg, 9.81 * (jm @ jX[:, 2] + tm @ tX[:, 2]), rtol=1e-12)
    assert st.pw == [] and ch.power(st, np.zeros(2)) == 0.0
    # without the tangent: the same M and F, no K, C, dM
    s2 = ch.state(0.0, np.array([phi, r]), np.array([w, v]), tangent=False)
    assert close(s2.M, st.M, 1e-15) and close(s2.F, st.F, 1e-15)
    assert not s2.K.any() and not s2.C.any() and not s2.dM.any()


def test_slewing_jib_with_a_prescribed_trolley_against_a_hand_lagrangian():
    """The trolley runs a profile: r(t), r'(t), r''(t) at t = 2 of `_profile` (0.7,
    0.85, 0.8). F_phi = -J'(r) r' w + C r'' (the carried acceleration), K_phi = 0,
    C_phi = J'(r) r' = 2 S r'; the power of the prescribed motion on the sets,
    int (x'' - g) . x_t dm = r' sum_trolley m (-rho_x w^2 - rho_y phi'' + r'')."""
    ch, jib, tr = _jib_trolley(_profile())
    phi, w, a = -0.4, 0.25, 0.6
    r, rv, ra = 0.7, 0.85, 0.8
    st = ch.state(2.0, np.array([phi]), np.array([w]))
    J, C, S, mt = _hand(phi, r, jib, tr)
    assert close(st.M, [[J]], 1e-12)
    assert close(st.F, [-2 * S * rv * w + C * ra], 1e-12, scale=J)
    assert close(st.K, [[0.0]], 1e-12, scale=J)
    assert close(st.C, [[2 * S * rv]], 1e-12, scale=J)
    assert close(st.dM, [[[0.0]]], 1e-12, scale=J)
    assert np.isclose(st.T, 0.5 * J * w * w - C * w * rv + 0.5 * mt * rv * rv, rtol=1e-12)
    P = rv * (-S * w * w - C * a + mt * ra)
    assert np.isclose(ch.power(st, np.array([a])), P, rtol=1e-12)
    # at the profile's breakpoint t = 3 the trolley's acceleration from the left (1.1)
    # and from the right (-0.4) enter the carried term C r''
    r, rv = 2.0, 1.8
    J, C, S, mt = _hand(phi, r, jib, tr)
    for left, ra in ((True, 1.1), (False, -0.4)):
        st = ch.state(3.0, np.array([phi]), np.array([w]), left=left)
        assert close(st.F, [-2 * S * rv * w + C * ra], 1e-12, scale=J)
        assert np.isclose(ch.power(st, np.array([a])), rv * (-S * w * w - C * a + mt * ra),
                          rtol=1e-12)
    # by default from the right (the segment after): state and motions
    st = ch.state(3.0, np.array([phi]), np.array([w]))
    assert close(st.F, [-2 * S * rv * w + C * -0.4], 1e-12, scale=J)
    H = ch.motions(3.0, np.array([phi]))
    x_tt = ch.jets.derivatives(H[1])[1][1, 1].reshape(3, 4)[:, 3]   # r'' Rz(phi) e_x
    assert close(x_tt, -0.4 * np.array([np.cos(phi), np.sin(phi), 0.0]), 1e-14)


# ----------------------------------- a general chain, by Cauchy's integral formula

T0 = 2.0                                   # the state's time (inside _profile's 1st seg)


def _rodrigues(n, th):
    """Rodrigues' rotation by the angles th (any shape, complex allowed): (..., 3, 3)."""
    K = _skew(n)
    th = np.asarray(th)[..., None, None]
    return np.eye(3) + np.sin(th) * K + (1 - np.cos(th)) * (K @ K)


def _compose(par, joint):
    Rp, pp = par
    Rj, pj = joint
    return Rp @ Rj, np.einsum("...ij,...j->...i", Rp, pj) + pp


def _hinge(n, a, th):
    R = _rodrigues(n, th)
    return R, a - np.einsum("...ij,j->...i", R, a)


def _slider(n, s):
    s = np.asarray(s)
    return np.broadcast_to(np.eye(3), s.shape + (3, 3)), s[..., None] * n


NF, RF = 16, 0.5                       # Cauchy's formula: samples per variable, radius


def _taylor(maps_of, z0):
    """Partial derivatives of order 0-3 at z0 (3 variables) of the maps [R | p] of
    every body, by Cauchy's integral formula on the torus |z_a - z0_a| = RF: the
    Taylor coefficients are the FFT of NF^3 samples / (NF^3 RF^|alpha|) (aliasing
    ~ RF^NF / NF! relative, round-off ~ 1e-16 / RF^3), times alpha!."""
    om = RF * np.exp(2j * np.pi * np.arange(NF) / NF)
    Z = np.meshgrid(*[z0[a] + om for a in range(3)], indexing="ij")
    out = {}
    for b, (R, p) in maps_of(*Z).items():
        A = np.concatenate([R, p[..., None]], axis=-1)          # (NF, NF, NF, 3, 4)
        C = np.fft.fftn(A, axes=(0, 1, 2)) / NF ** 3

        def d(*ks):
            al = [0, 0, 0]
            for k in ks:
                al[k] += 1
            fact = np.prod([np.prod(np.arange(1, x + 1)) for x in al])
            return (C[tuple(al)] / RF ** sum(al) * fact).real
        d1 = [d(a) for a in range(3)]
        d2 = [[d(a, c) for c in range(3)] for a in range(3)]
        d3 = [[[d(a, c, e) for e in range(3)] for c in range(3)] for a in range(3)]
        out[b] = [C[0, 0, 0].real, d1, d2, d3]
    return out


def _spec():
    """The six-body chain (module docstring): joints, mass points, nodes."""
    return dict(
        gantry=dict(axis=_unit([0.6, 0.8, 0.0]), sign=1.0),
        jib=dict(axis=_unit([0.1, -0.2, 1.0]), point=np.array([1.0, -0.5, 0.3]),
                 sign=-1.0, rho=2.0),
        trolley=dict(axis=_unit([0.8, 0.1, -0.3]), sign=1.0, rho=0.5),
        hook=dict(axis=_unit([0.2, 1.0, 0.1]), point=np.array([6.0, 0.5, 2.0]),
                  sign=-1.0),
        pts={1: (np.array([[2.0, 0.0, 1.0], [5.0, 1.0, 0.5], [-1.0, 0.5, 2.0]]),
                 np.array([3.0, 2.0, 1.5])),
             2: (np.array([[6.0, 0.3, 2.2], [6.5, 0.8, 1.8]]), np.array([1.2, 0.7])),
             4: (np.array([[6.2, 0.4, 0.5], [5.5, 0.6, -0.5], [6.8, 0.2, 0.0]]),
                 np.array([0.9, 0.4, 1.1])),
             5: (np.array([[-2.0, 0.5, 1.5], [-1.0, -0.5, 1.0]]), np.array([4.0, 2.5]))},
        proj_pt=(2, np.array([6.1, 0.5, 1.0]), 2.5),      # a guided load on the trolley
        nodes={1: np.array([[4.0, 1.0, 1.0]]), 4: np.array([[6.0, 0.5, -1.0],
                                                           [7.0, 0.0, 0.0]])},
    )


def _drive(motion):
    return SimpleNamespace(motion=motion)


def _gantry_motion():
    # a = -0.7 + 1.1 tau from t = 0.5 at rest, 3 s long, then rest at constant speed
    return Motion.build(0.5, [(3.0, -0.7, 1.1)], "table")


def _hook_motion():
    return Motion.build(0.0, [(3.0, 0.3, -0.2), (1.5, 0.5, 0.0)], "table", v0=0.1)


def _hand_state(t0):
    """(s, s', s'') of the gantry and hook profiles at T0 by hand (inside segments)."""
    tau = t0 - 0.5                           # gantry: s0 = v0 = 0 at t = 0.5
    g = (-0.7 * tau ** 2 / 2 + 1.1 * tau ** 3 / 6, -0.7 * tau + 1.1 * tau ** 2 / 2,
         -0.7 + 1.1 * tau)
    tau = t0                                 # hook: from t = 0 with s0 = 0, v0 = 0.1
    h = (0.1 * tau + 0.3 * tau ** 2 / 2 - 0.2 * tau ** 3 / 6,
         0.1 + 0.3 * tau - 0.2 * tau ** 2 / 2, 0.3 - 0.2 * tau)
    return g, h


def _chain(linear=None):
    sp_ = _spec()
    ga, ji, tr, ho = sp_["gantry"], sp_["jib"], sp_["trolley"], sp_["hook"]
    Kj, Kh = _skew(ji["axis"]), _skew(ho["axis"])
    chain = [
        (0, -1, _drive(_gantry_motion()), ga["sign"], False, None, None, np.zeros(3),
         ga["axis"], None),
        (1, 0, True, ji["sign"], True, Kj, Kj @ Kj, ji["point"], None, 0),
        (5, 1, None, 1.0, False, None, None, np.zeros(3), None, None),
        (2, 1, True, tr["sign"], False, None, None, np.zeros(3), tr["axis"], 1),
        (3, 2, _drive(_hook_motion()), ho["sign"], True, Kh, Kh @ Kh, ho["point"], None,
         None),
        (4, 3, None, 1.0, False, None, None, np.zeros(3), None, None),
    ]
    sets = []
    for b, (X, m) in sp_["pts"].items():
        sets.append((b, float(m.sum()), m @ X, np.einsum("k,ki,kj->ij", m, X, X), None,
                     True))
    b, X, m = sp_["proj_pt"]
    H = np.eye(3) - np.outer([0, 0, 1.0], [0, 0, 1.0])
    sets.append((b, m, m * X, m * np.outer(X, X), H, False))
    groups = [(b, np.arange(len(X)) + 10 * b, X, None) for b, X in sp_["nodes"].items()]
    groups.append((b, np.array([99]), X[None], H))
    return JointChain(chain, [ji["rho"], tr["rho"]], sets, groups, G, linear)


def _maps(t0=T0):
    """The six bodies' maps as functions of (u0, u1, t) (module docstring)."""
    sp_ = _spec()
    g, h = _hand_state(t0)
    ga, ji, tr, ho = sp_["gantry"], sp_["jib"], sp_["trolley"], sp_["hook"]

    def maps(u0, u1, t):
        tau = t - t0
        m = {0: _slider(ga["axis"], ga["sign"] * (g[0] + g[1] * tau + g[2] * tau ** 2 / 2))}
        m[1] = _compose(m[0], _hinge(ji["axis"], ji["point"], ji["sign"] * u0 / ji["rho"]))
        m[5] = m[1]                       # a counter-jib fixed to the jib
        m[2] = _compose(m[1], _slider(tr["axis"], tr["sign"] * u1 / tr["rho"]))
        m[3] = _compose(m[2], _hinge(ho["axis"], ho["point"],
                                     ho["sign"] * (h[0] + h[1] * tau + h[2] * tau ** 2 / 2)))
        m[4] = m[3]
        return m
    return maps


def _ref(u, v, t0=T0):
    """Reference quantities by their definitions, sums over the mass points."""
    sp_ = _spec()
    D = _taylor(_maps(t0), (u[0], u[1], t0))
    w = np.array([v[0], v[1], 1.0])
    nJ = 2
    M = np.zeros((2, 2))
    F = np.zeros(2)
    T = V = 0.0
    P_parts = []

    def fields(b, X, P):
        A, d1, d2, d3 = D[b]
        Xh = np.append(X, 1.0)
        xa = [P @ (d1[a] @ Xh) for a in range(3)]
        xab = [[P @ (d2[a][c] @ Xh) for c in range(3)] for a in range(3)]
        x = A @ Xh
        vel = sum(w[a] * (d1[a] @ Xh) for a in range(3))
        acc0 = sum(w[a] * w[c] * xab[a][c] for a in range(3) for c in range(3))
        return x, vel, xa, acc0

    I3 = np.eye(3)
    pts = [(b, X, m, I3, True) for b, (Xs, ms) in sp_["pts"].items()
           for X, m in zip(Xs, ms)]
    b, X, m = sp_["proj_pt"]
    H = np.eye(3) - np.outer([0, 0, 1.0], [0, 0, 1.0])
    pts.append((b, X, m, H, False))
    for b, X, m, P, full in pts:
        x, vel, xa, acc0 = fields(b, X, P)
        gg = G if full else np.zeros(3)
        for i in range(nJ):
            F[i] += m * xa[i] @ (gg - acc0)
            for j in range(nJ):
                M[i, j] += m * xa[i] @ xa[j]
        if full:
            T += 0.5 * m * vel @ vel
            V -= m * G @ x
        P_parts.append((m, xa, acc0, gg))

    def power(a):
        return sum(m * (acc0 + a[0] * xa[0] + a[1] * xa[1] - gg) @ xa[2]
                   for m, xa, acc0, gg in P_parts)
    nodes = {}
    for b, Xs in sp_["nodes"].items():
        rows = []
        for X in Xs:
            A, d1, d2, d3 = D[b]
            Xh = np.append(X, 1.0)
            rows.append((A @ Xh, sum(w[a] * (d1[a] @ Xh) for a in range(3)),
                         np.array([d1[i] @ Xh for i in range(nJ)]).T,
                         np.array([[d2[i][k] @ Xh for k in range(nJ)]
                                   for i in range(nJ)]).transpose(2, 0, 1)))
        nodes[b] = rows
    b, X, _ = sp_["proj_pt"]
    A, d1, d2, d3 = D[b]
    Xh = np.append(X, 1.0)
    guided = (np.array([H @ (d1[i] @ Xh) for i in range(nJ)]).T,
              np.array([[H @ (d2[i][k] @ Xh) for k in range(nJ)]
                        for i in range(nJ)]).transpose(2, 0, 1))
    return dict(M=M, F=F, T=T, V=V, power=power, nodes=nodes, guided=guided)


U, V_ = np.array([0.9, -0.6]), np.array([0.35, -0.8])


def test_general_chain_mass_matrix_forces_energies_against_cauchy():
    ch = _chain()
    st = ch.state(T0, U, V_)
    ref = _ref(U, V_)
    sM = float(np.max(np.abs(ref["M"])))
    assert close(st.M, ref["M"], 1e-11)
    assert close(st.F, ref["F"], 1e-11, scale=sM)
    assert np.isclose(st.T, ref["T"], rtol=1e-11)
    assert np.isclose(st.Vg, ref["V"], rtol=1e-11)
    # Fg: gravity's part alone (F at rest minus the inertia terms: the reference
    # with g = 0 is not separate, so check Fg = sum m x_i . g through F(g) - F(0))
    ch0 = _chain()
    ch0.sets = [(b, W, None if gv is None else 0 * gv, e) for b, W, gv, e in ch0.sets]
    st0 = ch0.state(T0, U, V_)
    assert close(st.Fg, st.F - st0.F, 1e-11, scale=sM)
    assert np.abs(st.Fg).max() > 1.0
    a = np.array([0.4, -1.7])
    assert np.isclose(ch.power(st, a), ref["power"](a), rtol=1e-11)


def test_general_chain_nodes_against_cauchy():
    ch = _chain()
    st = ch.state(T0, U, V_)
    ref = _ref(U, V_)
    sp_ = _spec()
    assert len(st.groups) == len(sp_["nodes"]) + 1
    for (idx, X, V, XJ, XJJ, full), (b, rows) in zip(st.groups, ref["nodes"].items()):
        assert full and np.array_equal(idx, np.arange(len(rows)) + 10 * b)
        for k, (x, vel, xj, xjj) in enumerate(rows):
            assert close(X[k], x, 1e-12, scale=10.0)
            assert close(V[k], vel, 1e-12, scale=10.0)
            assert close(XJ[k], xj, 1e-12, scale=10.0)
            assert close(XJJ[k], xjj, 1e-12, scale=10.0)
    idx, X, V, XJ, XJJ, full = st.groups[-1]
    assert not full and X is None and V is None and list(idx) == [99]
    assert close(XJ[0], ref["guided"][0], 1e-12, scale=10.0)
    assert close(XJJ[0], ref["guided"][1], 1e-12, scale=10.0)


def test_general_chain_tangents_against_central_differences():
    """K = -dF/du, C = -dF/du', dM = dM/du by central differences (h = 1e-5) of the
    references (Cauchy's formula: derivatives to ~1e-13)."""
    ch = _chain()
    st = ch.state(T0, U, V_)
    h = 1e-5
    K = np.zeros((2, 2))
    C = np.zeros((2, 2))
    dM = np.zeros((2, 2, 2))
    for k in range(2):
        e = np.zeros(2)
        e[k] = h
        rp, rm = _ref(U + e, V_), _ref(U - e, V_)
        K[:, k] = -(rp["F"] - rm["F"]) / (2 * h)
        dM[:, :, k] = (rp["M"] - rm["M"]) / (2 * h)
        rp, rm = _ref(U, V_ + e), _ref(U, V_ - e)
        C[:, k] = -(rp["F"] - rm["F"]) / (2 * h)
    s = float(np.max(np.abs(st.M)))
    assert close(st.K, K, 1e-7, scale=s)
    assert close(st.C, C, 1e-7, scale=s)
    assert close(st.dM, dM, 1e-7, scale=s)
    # every term is present (a tangent that dropped one would still be small otherwise)
    assert np.abs(st.K).min() > 1e-3 and np.abs(st.C).max() > 1e-2


# -------------------------------------------------- a chain under a linkage's motion

TH = (0.3, 0.45, -0.9)                      # the linkage body's angle, rate, accel. at T1
PL = (np.array([0.5, 0.0, 1.2]), np.array([0.2, 0.0, -0.3]), np.array([-0.1, 0.0, 0.4]))
T1 = 1.5


def _ry(th):
    c, s = np.cos(th), np.sin(th)
    return (np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
            np.array([[-s, 0, c], [0, 0, 0], [-c, 0, -s]]),
            np.array([[-c, 0, -s], [0, 0, 0], [s, 0, -c]]))


def _linkage_chain():
    """Body 0 moved by a linkage (its R(t) = Ry(theta(t)), p(t) given with their time
    derivatives by the chain rule), the trolley slider coordinate on it and the jib
    hinge coordinate below the trolley (rho 2 and 0.5)."""
    R, R1, R2 = _ry(TH[0])
    motions = {0: (R, R1 * TH[1], R2 * TH[1] ** 2 + R1 * TH[2], PL[0], PL[1], PL[2])}
    linear = SimpleNamespace(motions=lambda t: motions if t == T1 else None)
    sp_ = _spec()
    ji, tr = sp_["jib"], sp_["trolley"]
    Kj = _skew(ji["axis"])
    chain = [(0, -1, True, 1.0, False, None, None, np.zeros(3), np.array([1.0, 0, 0]),
              None),
             (1, 0, True, tr["sign"], False, None, None, np.zeros(3), tr["axis"], 1),
             (2, 1, True, ji["sign"], True, Kj, Kj @ Kj, ji["point"], None, 0)]
    sets = []
    for b, key in ((1, 2), (2, 1)):
        X, m = sp_["pts"][key]
        sets.append((b, float(m.sum()), m @ X, np.einsum("k,ki,kj->ij", m, X, X), None,
                     True))
    return JointChain(chain, [ji["rho"], tr["rho"]], sets, [], G, linear)


def _linkage_maps(u0, u1, t):
    sp_ = _spec()
    tau = t - T1
    th = TH[0] + TH[1] * tau + TH[2] * tau ** 2 / 2
    c, s = np.cos(th), np.sin(th)
    o, z = np.ones_like(th), np.zeros_like(th)
    R0 = np.stack([np.stack([c, z, s], -1), np.stack([z, o, z], -1),
                   np.stack([-s, z, c], -1)], -2)
    p0 = PL[0] + PL[1] * tau[..., None] + PL[2] * tau[..., None] ** 2 / 2
    ji, tr = sp_["jib"], sp_["trolley"]
    m = {0: (R0, p0)}
    m[1] = _compose(m[0], _slider(tr["axis"], tr["sign"] * u1 / tr["rho"]))
    m[2] = _compose(m[1], _hinge(ji["axis"], ji["point"], ji["sign"] * u0 / ji["rho"]))
    return m


def test_chain_under_a_linkage_against_cauchy():
    ch = _linkage_chain()
    st = ch.state(T1, U, V_)
    sp_ = _spec()
    D = _taylor(_linkage_maps, (U[0], U[1], T1))
    w = np.array([V_[0], V_[1], 1.0])
    M = np.zeros((2, 2))
    F = np.zeros(2)
    T = 0.0
    parts = []
    for b, key in ((1, 2), (2, 1)):
        A, d1, d2, _ = D[b]
        for X, m in zip(*sp_["pts"][key]):
            Xh = np.append(X, 1.0)
            xa = [d1[a] @ Xh for a in range(3)]
            acc0 = sum(w[a] * w[c] * (d2[a][c] @ Xh) for a in range(3) for c in range(3))
            vel = sum(w[a] * xa[a] for a in range(3))
            for i in range(2):
                F[i] += m * xa[i] @ (G - acc0)
                for j in range(2):
                    M[i, j] += m * xa[i] @ xa[j]
            T += 0.5 * m * vel @ vel
            parts.append((m, xa, acc0))
    assert close(st.M, M, 1e-11)
    assert close(st.F, F, 1e-11, scale=float(np.abs(M).max()))
    assert np.isclose(st.T, T, rtol=1e-11)
    a = np.array([-0.3, 0.8])
    P = sum(m * (acc0 + a[0] * xa[0] + a[1] * xa[1] - G) @ xa[2] for m, xa, acc0 in parts)
    assert np.isclose(ch.power(st, a), P, rtol=1e-11)
