"""Kill tests for cranefe/analysis/operation/flexible.py (tools/mutation.py flexible;
docs/testing.md, "Mutation testing"): the elastic structure of operation scenes on
one-element members whose every term is written out by hand, in seconds.

Before these tests only tests/test_operation_flexible.py reached the module (its runs
take minutes). References, none computed by the module:

* a one-element cantilever (root clamped on a spinning hub, tip T free) has, with its
  tip slopes a, b condensed, the strain energy of module docstring's second-order
  Green strain written for the cubic (Hermite) element by hand:
      U = sum_planes EI/(2 L^3) (12 w^2 - 12 L w th + 4 L^2 th^2) + EA/(2 L) delta^2,
      delta = d + sum_planes (36 w^2 - 6 L w th + 4 L^2 th^2) / (60 L)
  (d the tip's axial displacement, w its deflections; (36, -6L, 4L^2)/(30L) the cubic's
  int v'^2 dx, i.e. the consistent geometric stiffness under a unit axial force),
  minimised over the slopes at 30 digits (mpmath), its gradient and Hessian by central
  differences at 30 digits;
* the tip's lumped mass rho A L / 2 and the frame terms of one mass in a frame turned
  by phi(t) about z: m R^T g - m (R^T R'' Y + 2 R^T R' u'), R^T R' = w S,
  R^T R'' = w' S + w^2 S^2 (S = skew(e_z)); position R Y, velocity R' Y + R u',
  kinetic and gravity energy, the power of the carried velocity R' Y;
* a free cantilever's static tip deflection P L^3 / (3 EI) under its tip load (no
  axial force: delta = 0, so the tip also shortens by 0.6 w^2 / L);
* a two-bar truss and an axial spring: K = sum k e e^T, Green's elongation
  e . u + |u_perp|^2 / (2 l).
"""

import functools
import math

import mpmath as mp
import numpy as np
import pytest
from test_operation_flexible import JIB, ROTOR, write

from cranefe.analysis.operation.flexible import active
from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse
from cranefe.errors import ModelError
from cranefe.model import load

EI, EA, L, RHOA = 2.1e5, 2.1e10, 10.0, 7.85          # ROTOR's blade
MT = RHOA * L / 2                                     # the tip's lumped mass
GRAV = np.array([-3.0, 0.0, -9.81])
ALPHA, T1 = 0.6, 1.0            # spin-up: w = ALPHA t, phi = ALPHA t^2 / 2


def mechanism(model):
    return Mechanism(model, parse(model))


def _rotor():
    """A fresh mechanism each time (not cached: mutmut's forked runs must build it with
    the mutant)."""
    import tempfile
    from pathlib import Path
    tmp = Path(tempfile.mkdtemp(prefix="kill-flexible-"))
    text = ROTOR.replace("gravity: [0, 0, 0]", "gravity: [-3.0, 0, -9.81]")
    model = load(write(tmp, text, "  duration: 3\n  drives:\n    spin: {hinge: spin, "
                       "profile: {type: table, speed: [[0, 0], [2, 1.2]]}}\n", NEL=1))
    return mechanism(model)


# ------------------------------------------------------------ the hand strain energy
mp.mp.dps = 30


def _U_slopes(d, wy, wz, a, b):
    L_, EI_, k = mp.mpf(L), mp.mpf(EI), mp.mpf(EA) / L

    def bend(w, th):
        return EI_ / (2 * L_**3) * (12 * w**2 - 12 * L_ * w * th + 4 * L_**2 * th**2)

    def elong(w, th):
        return (36 * w**2 - 6 * L_ * w * th + 4 * L_**2 * th**2) / (60 * L_)
    delta = d + elong(wy, a) + elong(wz, b)
    return bend(wy, a) + bend(wz, b) + k / 2 * delta**2


def _U(u):
    """U(d, wy, wz) minimised over the slopes: dU/da = 0, dU/db = 0 (written out) by
    Newton at 30 digits from the linear slopes 3 w / (2 L)."""
    d, wy, wz = (mp.mpf(float(x)) if not isinstance(x, mp.mpf) else x for x in u)
    L_, EI_, k = mp.mpf(L), mp.mpf(EI), mp.mpf(EA) / L

    def f(a, b):
        delta = d + sum((36 * w**2 - 6 * L_ * w * th + 4 * L_**2 * th**2) / (60 * L_)
                        for w, th in ((wy, a), (wz, b)))
        return [EI_ / (2 * L_**3) * (-12 * L_ * w + 8 * L_**2 * th)
                + k * delta * (-6 * L_ * w + 8 * L_**2 * th) / (60 * L_)
                for w, th in ((wy, a), (wz, b))]
    a, b = mp.findroot(f, (3 * wy / (2 * L_), 3 * wz / (2 * L_)), tol=mp.mpf(10)**-50)
    return _U_slopes(d, wy, wz, a, b)


def _shifted(u, *shifts):
    v = [mp.mpf(float(x)) for x in u]
    for i, s in shifts:
        v[i] += s
    return _U(v)


H_DIFF = mp.mpf("1e-8")


def _grad(u):
    """Central differences at 30 digits (truncation h^2 U3 / 6 ~ 1e-16 relative)."""
    h = H_DIFF
    return np.array([(_shifted(u, (i, h)) - _shifted(u, (i, -h))) / (2 * h)
                     for i in range(3)], float)


def _grad_hess(u):
    h = H_DIFF
    H = [[(_shifted(u, (i, h), (j, h)) - _shifted(u, (i, h), (j, -h))
           - _shifted(u, (i, -h), (j, h)) + _shifted(u, (i, -h), (j, -h))) / (4 * h * h)
          for j in range(3)] for i in range(3)]
    return _grad(u), np.array(H, float)


U_TEST = np.array([2e-4, -0.3, 0.5])      # large deflections: the quartic terms count


@functools.cache
def _hand():
    return float(_U(U_TEST)), *_grad_hess(U_TEST)


def test_one_element_cantilever_strain_energy_gradient_tangent():
    """The engine's U, dU/du and condensed tangent at u = (0.2 mm, -0.3 m, 0.5 m) against
    the hand energy (to 1e-9, 1e-8, 1e-6 relative: the 30-digit references' central
    differences are exact to ~1e-12; the engine's slope Newton stops at 1e-14);
    the tangent at u = 0 is diag(EA/L, 3EI/L^3, 3EI/L^3) exactly (to 1e-12)."""
    mech = _rotor()
    f = mech.flex
    f._last = f._theta = None
    z, grad, Kt, U, N = f.strain(U_TEST.copy())
    U0, g0, H0 = _hand()
    assert abs(U / U0 - 1) < 1e-9, (U, U0)
    np.testing.assert_allclose(grad, g0, rtol=1e-8, atol=1e-8 * np.abs(g0).max())
    np.testing.assert_allclose(Kt, H0, rtol=1e-6, atol=1e-6 * np.abs(H0).max())
    # the axial force EA/L delta
    np.testing.assert_allclose(N, [g0[0]], rtol=1e-8)
    np.testing.assert_allclose(z[:3], U_TEST, rtol=0, atol=0)
    # the cache: the same u returns the same tuple; the slopes start from the last
    assert f.strain(U_TEST.copy())[2] is Kt
    f._last = f._theta = None
    _, _, K0, U00, N0 = f.strain(np.zeros(3))
    np.testing.assert_allclose(K0, np.diag([EA / L, 3 * EI / L**3, 3 * EI / L**3]),
                               rtol=1e-12, atol=1e-12 * EA / L)
    assert U00 == 0.0 and N0[0] == 0.0


def test_masses_labels_and_layout():
    mech = _rotor()
    f = mech.flex
    assert active(mech.model)
    assert not active(mech.model.with_effects(structure="rigid"))
    assert f.labels() == ["T.ux", "T.uy", "T.uz"] and f.nu == 3 and f.nt == 3
    np.testing.assert_allclose(f.me, [MT], rtol=1e-15)
    np.testing.assert_allclose(f.Mu, [MT] * 3, rtol=1e-15)
    np.testing.assert_allclose(mech.M, [MT] * 3, rtol=1e-15)


def _frame(t):
    phi, w, dw = ALPHA * t * t / 2, ALPHA * t, ALPHA
    c, s = math.cos(phi), math.sin(phi)
    R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    S = np.array([[0, -1.0, 0], [1.0, 0, 0], [0, 0, 0]])
    return R, w, dw, S


Q = np.array([2e-4, -0.3, 0.5])
V = np.array([0.7, -1.1, 0.4])


def test_frame_terms_of_the_tip_mass():
    """At t = 1 s of the spin-up (phi = 0.3, w = w' = 0.6): F = -dU/du + m R^T g
    - m ((w' S + w^2 S^2) Y + 2 w S u') with Y = X + u (to 1e-8 of the largest term),
    K = tangent + m (w' S + w^2 S^2), C = 2 m w S."""
    mech = _rotor()
    mech.flex._last = mech.flex._theta = None
    ev = mech.evaluate(T1, Q, V, mech.taut0)
    R, w, dw, S = _frame(T1)
    Y = np.array([L, 0, 0]) + Q
    A2 = dw * S + w * w * S @ S
    _, g0, H0 = _hand()
    F = -g0 + MT * (R.T @ GRAV) - MT * (A2 @ Y + 2 * w * S @ V)
    np.testing.assert_allclose(ev.F, F, rtol=0, atol=1e-8 * np.abs(g0).max())
    np.testing.assert_allclose(ev.K, H0 + MT * A2, rtol=0, atol=1e-6 * np.abs(H0).max())
    np.testing.assert_allclose(ev.C, 2 * MT * w * S, rtol=1e-14, atol=1e-14)


def test_place_energy_and_power_of_the_tip():
    """x = R Y, x' = R' Y + R u' (R' = w R S); T = m |x'|^2 / 2, V = -m x . g, U; the
    power of the frame's motion m w_c . (x'' - g) with the carried velocity w_c = R' Y
    and x'' = R'' Y + 2 R' u' + R u'' (u'' = F / m, R'' = R (w' S + w^2 S^2))."""
    mech = _rotor()
    mech.flex._last = mech.flex._theta = None
    R, w, dw, S = _frame(T1)
    dR, ddR = w * R @ S, R @ (dw * S + w * w * S @ S)
    Y = np.array([L, 0, 0]) + Q
    X, Vn = mech.place(T1, Q, V)[:2]
    np.testing.assert_allclose(X[1], R @ Y, rtol=1e-14, atol=1e-14)
    np.testing.assert_allclose(Vn[1], dR @ Y + R @ V, rtol=1e-14, atol=1e-14)
    ev = mech.evaluate(T1, Q, V, mech.taut0)
    T, Vg, U = mech.energy(ev, mech.taut0)
    xd = dR @ Y + R @ V
    np.testing.assert_allclose(T, 0.5 * MT * xd @ xd, rtol=1e-13)
    np.testing.assert_allclose(Vg, -MT * (R @ Y) @ GRAV, rtol=1e-13)
    np.testing.assert_allclose(U, _hand()[0], rtol=1e-9)
    acc = ddR @ Y + 2 * dR @ V + R @ (ev.F / MT)
    P = MT * (dR @ Y) @ (acc - GRAV)
    np.testing.assert_allclose(mech.flex.power(mech, ev, Q, V), P, rtol=1e-10)


def test_static_state_of_the_rotor_under_gravity():
    """settle(): at rest before the spin-up (R = I) the tip is in equilibrium under its
    weight, dU/du = m g by the hand energy (to 1e-7 of m g: the Newton stop 1e-12 m in
    a tangent up to EA/L = 2e9 N/m, and the hand gradient's 1e-9)."""
    mech = _rotor()
    q0 = mech.q0
    g = _grad(q0)
    np.testing.assert_allclose(g, MT * GRAV, rtol=0, atol=1e-7 * MT * 9.81)
    assert q0[2] < -0.5                                    # a soft blade: 0.63 m down
    np.testing.assert_allclose(mech.flex.u0, q0, rtol=0, atol=0)


DIRECT = JIB.replace("path: [hoist, T, HOOK]", "path: [T, HOOK]")


def test_jib_tip_deflection_under_a_hanging_load(tmp_path):
    """A one-element jib (EI = 4.2e9, L = 12 m) with a 1500 kg load hanging from its tip
    on a vertical rope: static tip deflection P L^3 / (3 EI), P = (1500 + rho A L / 2) g,
    to 1e-10 relative (no axial force: exact), the tip shortened by 0.6 w^2 / L (Green:
    delta = 0) to 1e-12 m, the rope force 1500 g, the load below the tip."""
    model = load(write(tmp_path, DIRECT, "  duration: 1\n", IYVAL=2.0e-2, NEL=1,
                       MASS="lumped", GVAL=-9.81))
    mech = mechanism(model)
    lab = mech.flex.labels()
    assert lab == ["T.ux", "T.uz"]
    o = mech.nc + mech.nJ
    ux, uz = mech.q0[o:o + 2]
    P = (1500 + 7850 * 0.012 * 12 / 2) * 9.81
    w = P * 12**3 / (3 * 2.1e11 * 2.0e-2)
    np.testing.assert_allclose(uz, -w, rtol=1e-10)
    np.testing.assert_allclose(ux, -0.6 * w * w / 12, rtol=1e-6, atol=1e-12)
    np.testing.assert_allclose(mech.S0, [1500 * 9.81], rtol=1e-12)
    np.testing.assert_allclose(mech.q0[0], 12 + ux, atol=1e-12)
    assert mech.taut0.all()
    np.testing.assert_allclose(mech.hold_torque, [0.0])
    # the power through the rope of a tip moving at u' = (0.3, -0.2) m/s on the ground
    # frame (no frame power): u' . (0, -S) with S = 1500 g
    v = np.zeros(mech.n)
    v[o:o + 2] = [0.3, -0.2]
    ev = mech.evaluate(0.0, mech.q0, v, mech.taut0)
    np.testing.assert_allclose(mech.flex.power(mech, ev, mech.q0, v), 0.2 * 1500 * 9.81,
                               rtol=1e-9)


TRUSS2 = """cranefe: 1
name: a two-bar truss with a spring
plane: xz
gravity: [0, 0, -9.81]
nodes:
  A: [0.0, 0.0, 3.0]
  B: [0.0, 0.0, 0.0]
  C: [4.0, 0.0, -3.0]
  T: [4.0, 0.0, 0.0]
ground: [A, B, C]
masses: {T: 200}
members:
  bars: {type: truss, pairs: [[A, T], [B, T]], E: 2.0e+9, A: 0.001, rho: 1000,
         mass: lumped}
springs:
  - {name: tie, type: axial, nodes: [C, T], stiffness: 3.0e5}
"""


def test_truss_and_spring_by_hand(tmp_path):
    """Bars A-T (5 m, along (4, -3)/5) and B-T (4 m, along x), a spring C-T (3 m, along
    z): tangent at u = 0 sum k e e^T (k = EA/l, 3e5); at a displacement u the energy
    sum k/2 (e . u + |u_perp|^2 / (2 l))^2 and its gradient (Green); the tip's mass
    200 + rho A (5 + 4) / 2."""
    model = load(write(tmp_path, TRUSS2, "  duration: 1\n"))
    mech = mechanism(model)
    f = mech.flex
    assert f.labels() == ["T.ux", "T.uz"]
    np.testing.assert_allclose(f.me, [200 + 1000 * 0.001 * 9 / 2], rtol=1e-14)
    bars = [(np.array([0.8, -0.6]), 5.0, 2.0e9 * 0.001 / 5), (np.array([1.0, 0.0]), 4.0,
            2.0e9 * 0.001 / 4), (np.array([0.0, 1.0]), 3.0, 3.0e5)]
    f._last = None
    K0 = f.strain(np.zeros(2))[2]
    np.testing.assert_allclose(K0, sum(k * np.outer(e, e) for e, _, k in bars), rtol=1e-12,
                               atol=1e-6)
    u = np.array([0.01, -0.02])

    def U(u):
        tot = 0.0
        for e, l, k in bars:
            ue = e @ u
            d = ue + (u @ u - ue * ue) / (2 * l)
            tot += k / 2 * d * d
        return tot
    _, grad, _, Uu, _ = f.strain(u)
    np.testing.assert_allclose(Uu, U(u), rtol=1e-12)
    h = 1e-6
    g = [(U(u + h * np.eye(2)[i]) - U(u - h * np.eye(2)[i])) / (2 * h) for i in range(2)]
    np.testing.assert_allclose(grad, g, rtol=1e-7)


@pytest.mark.parametrize("edit, words, entry", [
    (("masses: {T: 200}", "masses: {T: {mass: 200, inertia: [1, 1, 1]}}"),
     "has a rotary inertia", "masses.T"),
    (("rho: 1000,", "rho: 0,", "masses: {T: 200}\n", ""), "has no mass", "members.bars"),
    (("ground: [A, B, C]", "ground: [A, B, C]\nsupports:\n  T: {fix: [ux]}"),
     "has a support", None),
    (("mass: lumped", "mass: consistent"), "consistent mass matrix", "members.bars.mass"),
    (("ground: [A, B, C]", "ground: [C]", ("springs:\n  - {name: tie, type: axial, nodes: "
                                           "[C, T], stiffness: 3.0e5}\n"), ""),
     "free-floating structure", "members.bars"),
    (("ground: [A, B, C]", "ground: [A, B]", "masses: {T: 200}", "masses: {T: 200, C: 50}"),
     "joins the elastic structure to a load", "springs.tie"),
])
def test_what_the_structure_refuses(tmp_path, edit, words, entry):
    text = TRUSS2
    for a, b in zip(edit[::2], edit[1::2]):
        assert a in text
        text = text.replace(a, b)
    model = load(write(tmp_path, text, "  duration: 1\n"))
    with pytest.raises(ModelError) as exc:
        mechanism(model)
    assert words in str(exc.value), str(exc.value)
    if entry:
        assert entry in str(exc.value)


def test_rope_over_the_tip_of_a_luffed_boom(tmp_path):
    """The boom of a hinge luffed by phi(t) = 0.05 t^2 / 2 about -y through F (R by
    Rodrigues' formula, written out): at t = 1.5 s the rope over the boom's tip BT pulls
    the tip's coordinates (in the frame's axes) with -S dL/du, L = |X_BT - X_D| +
    |X_HOOK - X_BT| and X_BT = R (X_BT0 - F + u) + F (a central difference of the hand
    L, to 1e-7 of S): the difference of the forces with the rope taut and slack."""
    from test_operation_flexible import BOOM
    model = load(write(tmp_path, BOOM, "  duration: 3\n  drives:\n    luff: {hinge: luff, "
                       "profile: {type: table, speed: [[0, 0], [2, 0.1]]}}\n"))
    mech = mechanism(model)
    assert mech.flex.labels()[:2] == ["BT.ux", "BT.uz"] and mech.nc == 2
    t = 1.5
    phi = 0.05 * t * t / 2
    c, s = math.cos(phi), math.sin(phi)
    R = np.array([[c, 0, -s], [0, 1, 0], [s, 0, c]])        # about (0, -1, 0)
    Fp, D = np.array([0.0, 0, 2.0]), np.array([-1.0, 0, 2.0])
    BT0 = np.array([14.1421, 0.0, 16.1421])
    q = mech.q0.copy()
    q[2:4] += [0.03, -0.05]
    hook = np.array([q[0], 0.0, q[1]])

    def length(u):
        x = R @ (BT0 - Fp + np.array([u[0], 0.0, u[1]])) + Fp
        return np.linalg.norm(x - D) + np.linalg.norm(hook - x)
    h = 1e-6
    dL = np.array([(length(q[2:4] + h * e) - length(q[2:4] - h * e)) / (2 * h)
                   for e in np.eye(2)])
    v = np.zeros(mech.n)
    taut = mech.evaluate(t, q, v, np.array([True]))
    slack = mech.evaluate(t, q, v, np.array([False]))
    S = float(taut.S[0])
    assert S > 1000
    np.testing.assert_allclose(taut.F[2:4] - slack.F[2:4], -S * dL, rtol=0, atol=1e-7 * S)
    X = mech.place(t, q, v)[0]
    np.testing.assert_allclose(X[model.node_names.index("BT")],
                               R @ (BT0 - Fp + [q[2], 0, q[3]]) + Fp,
                               atol=1e-12)
    # the tip's velocity with u' = (0.2, -0.1): R' (X - F + u) + R u' (the hinge point
    # F fixed: p = F - R F, p' = -R' F), R' = w [a]x R, w = 0.05 t, a = (0, -1, 0)
    v[2:4] = [0.2, -0.1]
    ax = np.array([[0, 0, -1.0], [0, 0, 0], [1.0, 0, 0]])        # [a]x
    dR = 0.05 * t * ax @ R
    Vn = mech.place(t, q, v)[1]
    np.testing.assert_allclose(Vn[model.node_names.index("BT")],
                               dR @ (BT0 - Fp + [q[2], 0, q[3]]) + R @ [0.2, 0, -0.1],
                               atol=1e-12)


def test_elastic_jib_with_a_drum_coordinate(tmp_path):
    """A torque-driven drum (its angle a coordinate after the elastic ones) hoisting over
    the one-element jib's tip: the static state holds the load with S = 1500 g (the
    span to the hook vertical) and the drum with R S (R = 0.2 m); the elastic rows are
    the structure's own (the drum's row is not one of them)."""
    model = load(write(tmp_path, JIB, "  duration: 1\n  drives:\n    h: {drum: hoist, "
                       f"torque: {0.2 * 1500 * 9.81}}}\n", IYVAL=2.0e-2, NEL=1,
                       MASS="lumped", GVAL=-9.81))
    mech = mechanism(model)
    assert mech.n == mech.nc + mech.nJ + mech.flex.nu + 1
    np.testing.assert_allclose(mech.S0, [1500 * 9.81], rtol=1e-9)
    np.testing.assert_allclose(mech.hold_torque, [0.2 * 1500 * 9.81], rtol=1e-9)
    ev = mech.evaluate(0.0, mech.q0, np.zeros(mech.n), mech.taut0)
    assert np.abs(ev.F).max() < 1e-6 * 1500 * 9.81
