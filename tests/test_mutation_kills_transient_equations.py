"""Fast kill tests for cranefe/analysis/transient/equations.py (tools/mutation.py
transient_equations; docs/testing.md, "Mutation testing"): the `Equations` of a two-mass
hoist built here by hand, and `Factor`'s solves against numpy's dense solve.

The hoist: coordinates x = (theta, z): the drum angle theta (inertia J, drum radius r) and
the load's downward displacement z (mass m) on an elastic rope of stiffness k = EA/L.
The rope's stretch is z - r theta (paying out, theta > 0, lowers the load), so its row is
R = [-r, 1], its force s = S0 + k (z - r theta) with S0 = m g (the static hanging force).
Every expected value below is written out by hand from these numbers:
- M = diag(J, m); K = diag(k_b, k_s) (a brake spring on the drum, a buffer spring on the
  load) with the rope row kept out of K; C = [[c1, c12], [c12, c2]];
- internal force K x + R^T (taut * s - S0); slack rope: K x - R^T S0;
- energy 1/2 v.M v + 1/2 x.K x + 1/2 k stretch^2 - 1/2 S0^2/k - S0 (R x) with
  stretch = max(s, 0) / k (the rope's elastic energy above the reference state);
- a linear motor M(n) = M_s (1 - n / n_s) on the drum through a gear i: generalised force
  i M(i theta') on theta, drum torque i M, its slope i^2 dM/dn = -i^2 M_s / n_s;
- the Newmark matrix alpha M + (2/h) C + K + R^T k R (taut) = ... + k [[r^2, -r], [-r, 1]].
All comparisons are to 1e-12 relative (a few roundings of O(1) numbers).
"""

import numpy as np
import pytest
import scipy.sparse as sp

from cranefe.analysis.transient.equations import (
    DENSE_OPS, Equations, Factor, MotorLoad, Signal)
from cranefe.analysis.transient.scene import Motor, Profile

J, m, r, k = 40.0, 500.0, 0.3, 2.0e6
kb, ks = 1.5e3, 7.0e2
g = 9.81
S0 = m * g
C = np.array([[3.0, -0.5], [-0.5, 11.0]])
i_gear, Ms, ns = 20.0, 150.0, 157.0
TOL = 1e-12


def close(a, b, tol=TOL):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    assert a.shape == b.shape
    scale = max(np.abs(b).max(initial=0.0), 1e-300)
    np.testing.assert_allclose(a, b, rtol=0, atol=tol * scale)


def jump(value, t_on):
    """A Signal: 0 before t_on, `value` from t_on (the left limit at t_on is 0)."""
    value = np.atleast_1d(np.asarray(value, dtype=float))

    def f(t, left=False):
        return value * float(t > t_on or (t == t_on and not left))
    return Signal(f)


def hoist(sparse=False, **kw):
    Mm = np.diag([J, m])
    Km = np.diag([kb, ks])
    R = np.array([[-r, 1.0]])
    if sparse:
        Mm, Km, R = sp.csr_matrix(Mm), sp.csr_matrix(Km), sp.csr_matrix(R)
        Cm = sp.csr_matrix(C)
    else:
        Cm = C.copy()
    motor = MotorLoad(np.array([1.0, 0.0]), Motor("linear", synchronous_speed=ns,
                                                   stall_torque=Ms), i_gear, "hoist")
    args = dict(C=Cm, R=R, c=np.array([k]), S0=np.array([S0]),
                F0=np.array([-r * S0 + 10.0, 0.0]),
                loads=[(np.array([[0.0], [1.0]]), jump(250.0, 0.5)),
                       (np.array([[2.0], [0.0]]), Signal(lambda t, left=False:
                                                         np.array([3.0 * t])))],
                motors=[motor])
    args.update(kw)
    return Equations(Mm, Km, **args)


def hand_internal(x, taut):
    s = S0 + k * (x[1] - r * x[0])
    f = np.array([kb * x[0], ks * x[1]])
    return f + np.array([-r, 1.0]) * ((s if taut else 0.0) - S0)


def hand_motor(v):
    n = i_gear * v[0]
    return np.array([i_gear * Ms * (1 - n / ns), 0.0])


def hand_force(t, left):
    on = t > 0.5 or (t == 0.5 and not left)
    return np.array([-r * S0 + 10.0 + 2.0 * 3.0 * t, 250.0 * on])


X = np.array([0.004, 0.0007])
V = np.array([1.3, -0.2])
A = np.array([0.7, 2.5])


@pytest.mark.parametrize("sparse", [False, True])
def test_forces_tension_internal_residual(sparse):
    eq = hoist(sparse)
    assert eq.dense                     # n = 2 <= DENSE_OPS: turned into numpy arrays
    assert not sp.issparse(eq.M) and not sp.issparse(eq.K) and not sp.issparse(eq.C)
    assert not sp.issparse(eq.R) and not sp.issparse(eq.RT)
    close(eq.M, np.diag([J, m]))
    close(eq.C, C)
    close(eq.RT, [[-r], [1.0]])
    assert list(eq.mass) == [True, True] and eq.has_damping
    close(eq.tension(X), [S0 + k * (X[1] - r * X[0])])
    for taut in (True, False):
        close(eq.internal(X, np.array([taut])), hand_internal(X, taut))
    for t, left in ((0.2, False), (0.5, True), (0.5, False), (0.9, True)):
        close(eq.force(t, left), hand_force(t, left))
    close(eq.force(0.5), hand_force(0.5, False))      # left=False is the default
    close(eq.damp(V), C @ V)
    close(eq.motor_force(V), hand_motor(V))
    res = eq.residual(0.5, X, V, A, np.array([True]), left=True)
    close(res, np.diag([J, m]) @ A + C @ V + hand_internal(X, True)
          - hand_force(0.5, True) - hand_motor(V))
    res = eq.residual(0.5, X, V, A, np.array([False]))
    close(res, np.diag([J, m]) @ A + C @ V + hand_internal(X, False)
          - hand_force(0.5, False) - hand_motor(V))


def test_motor_load():
    ml = MotorLoad(np.array([0.0, 2.0]), Motor("linear", synchronous_speed=ns,
                                               stall_torque=Ms), i_gear)
    v = np.array([5.0, 0.75])
    n = i_gear * 2.0 * 0.75              # motor speed i (e . v)
    F, T, dT = ml.force(v)
    close(F, [0.0, 2.0 * i_gear * Ms * (1 - n / ns)])
    assert T == pytest.approx(i_gear * Ms * (1 - n / ns), rel=TOL)
    assert dT == pytest.approx(-i_gear**2 * Ms / ns, rel=TOL)
    assert ml.name == ""


def test_signal_rate():
    s = Signal(lambda t, left=False: np.array([t, 2 * t]) + (5.0 if left else 0.0))
    d = s.d(3.0)
    assert d.shape == (2,) and np.all(d == 0.0)
    s = Signal(lambda t, left=False: np.array([t]),
               lambda t, left=False: np.array([7.0 if left else -7.0]))
    close(s.d(1.0), [-7.0])
    close(s.d(1.0, True), [7.0])
    close(s.d(1.0, left=True), [7.0])


def hand_energy(x, v):
    s = S0 + k * (x[1] - r * x[0])
    stretch = max(s, 0.0) / k
    return (0.5 * (J * v[0]**2 + m * v[1]**2) + 0.5 * (kb * x[0]**2 + ks * x[1]**2)
            + 0.5 * k * stretch**2 - 0.5 * S0**2 / k - S0 * (x[1] - r * x[0]))


@pytest.mark.parametrize("sparse", [False, True])
def test_energy(sparse):
    eq = hoist(sparse)
    for x in (X, np.array([0.0, -0.01])):              # taut; slack (s = S0 - 0.01 k < 0)
        e = eq.energy(x, V)
        assert isinstance(e, float)
        assert e == pytest.approx(hand_energy(x, V), rel=TOL)
    # the potential's gradient is `internal` (taut and slack both): central differences,
    # h = 1e-7 on quadratic pieces: error only rounding ~ 1e-16 * E / h
    for x in (X, np.array([0.0, -0.01])):
        taut = np.array([eq.tension(x)[0] > 0])
        grad = []
        for j in range(2):
            d = np.zeros(2)
            d[j] = 1e-7
            grad.append((eq.energy(x + d, 0 * V) - eq.energy(x - d, 0 * V)) / 2e-7)
        close(grad, eq.internal(x, taut), 1e-5)


def test_energy_rows_without_stiffness():
    """A row with c = 0 (a rope whose stiffness is left out) adds only -S0 (R x)."""
    eq = Equations(np.diag([J, m]), np.diag([kb, ks]), R=np.array([[-r, 1.0], [0.0, 1.0]]),
                   c=np.array([k, 0.0]), S0=np.array([S0, 40.0]))
    e = eq.energy(X, V)
    assert e == pytest.approx(hand_energy(X, V) - 40.0 * X[1], rel=TOL)
    assert not eq.has_damping


def test_defaults():
    eq = Equations(np.diag([J, 0.0, m]), np.eye(3))
    close(eq.F0, np.zeros(3))
    assert eq.F0.shape == (3,)
    assert eq.R.shape == (0, 3) and len(eq.c) == 0 and len(eq.S0) == 0
    assert eq.contacts.dtype.kind == "i" and len(eq.contacts) == 0 and len(eq.up) == 0
    assert list(eq.mass) == [True, False, True]
    assert not eq.has_damping and eq.dense
    close(eq.internal(X[[0, 1, 1]], np.zeros(0, dtype=bool)), X[[0, 1, 1]])
    close(eq.damp(np.ones(3)), np.zeros(3))
    close(eq.force(1.0), np.zeros(3))
    close(eq.motor_force(np.ones(3)), np.zeros(3))
    assert eq.energy(np.ones(3), np.ones(3)) == pytest.approx(0.5 * (J + m) + 1.5, rel=TOL)
    # low-rank damping alone
    U = np.array([[1.0], [2.0], [0.0]])
    eq = Equations(np.eye(3), np.eye(3), U=U, W=np.array([3.0]))
    assert eq.has_damping
    close(eq.damp(np.array([1.0, 1.0, 5.0])), [9.0, 18.0, 0.0])


def test_damping_both():
    U = np.array([[1.0], [-2.0]])
    eq = hoist(U=U, W=np.array([0.5]))
    close(eq.damp(V), C @ V + U @ (0.5 * (U.T @ V)))


def test_known():
    eq = hoist(prescribed={0: Profile(np.array([0.0, 2.0]), np.array([[0.0], [4.0]]))},
               contacts=np.array([1]), up=np.array([-1.0]))
    idx, xq, xv, xa = eq.known(1.0, np.array([True]))
    assert list(idx) == [0, 1] and idx.dtype.kind == "i"
    # speed 2 t: angle t^2, rate 2 (x'' left and right the same inside the ramp)
    close(xq, [1.0, 0.0]); close(xv, [2.0, 0.0]); close(xa, [2.0, 0.0])
    idx, xq, xv, xa = eq.known(2.0, np.array([False]))
    assert list(idx) == [0]
    close(xq, [4.0]); close(xv, [4.0]); close(xa, [2.0])        # left limit by default
    idx, xq, xv, xa = eq.known(2.0, np.array([False]), left=False)
    close(xa, [0.0])
    idx, xq, xv, xa = eq.known(2.0, np.array([False]), False)
    close(xa, [0.0])
    eq = hoist(contacts=np.array([1]), up=np.array([-1.0]))
    idx, xq, xv, xa = eq.known(1.0, np.array([True]))
    assert list(idx) == [1] and len(xq) == len(xv) == len(xa) == 1


def hand_matrix(h, taut, alpha, with_C=True):
    Aa = alpha * np.diag([J, m]) + np.diag([kb, ks]) + (2.0 / h * C if with_C else 0)
    if taut:
        Aa = Aa + k * np.array([[r * r, -r], [-r, 1.0]])
    return Aa


@pytest.mark.parametrize("sparse", [False, True])
def test_matrix(sparse):
    eq = hoist(sparse)
    for taut in (True, False):
        close(eq.matrix(0.01, np.array([taut]), 4.0e4), hand_matrix(0.01, taut, 4.0e4))
    eq = hoist(sparse, C=None)
    assert not eq.has_damping
    close(eq.matrix(0.01, np.array([True]), 4.0e4), hand_matrix(0.01, True, 4.0e4, False))


def test_matrix_two_rows_one_taut():
    R = np.array([[-r, 1.0], [1.0, 2.0]])
    eq = Equations(np.diag([J, m]), np.diag([kb, ks]), C=C, R=R, c=np.array([k, 3.0]),
                   S0=np.array([S0, 1.0]))
    out = eq.matrix(0.02, np.array([False, True]), 10.0)
    close(out, 10.0 * np.diag([J, m]) + np.diag([kb, ks]) + 100.0 * C
          + 3.0 * np.array([[1.0, 2.0], [2.0, 4.0]]))
    out = eq.matrix(0.02, np.array([True, True]), 10.0)
    close(out, hand_matrix(0.02, True, 10.0) + 3.0 * np.array([[1.0, 2.0], [2.0, 4.0]]))


def big(n=DENSE_OPS + 3):
    """A sparse chain of n coordinates (n > DENSE_OPS: kept sparse): masses 1..n,
    springs between neighbours, two rope rows."""
    main = 2.0 + np.arange(n) * 0.01
    K = sp.diags([main, -np.ones(n - 1), -np.ones(n - 1)], [0, 1, -1], format="csr")
    M = sp.diags(np.r_[np.arange(1.0, n), 0.0], format="csr")
    Cm = sp.diags(0.1 * np.ones(n), format="csr")
    R = sp.csr_matrix((np.array([1.0, -1.0, 2.0]), (np.array([0, 0, 1]),
                                                     np.array([0, 5, 7]))), shape=(2, n))
    return M, K, Cm, R


def test_sparse_large():
    M, K, Cm, R = big()
    n = M.shape[0]
    c, S = np.array([5.0, 7.0]), np.array([2.0, 3.0])
    eq = Equations(M, K, Cm, R=R, c=c, S0=S)
    assert not eq.dense and sp.issparse(eq.M) and sp.issparse(eq.RT)
    assert eq.n == n
    assert list(np.flatnonzero(~eq.mass)) == [n - 1]
    x = np.linspace(-1, 1, n)
    Rd = R.toarray()
    close(eq.tension(x), S + c * (Rd @ x))
    taut = np.array([True, False])
    s = np.where(taut, S + c * (Rd @ x), 0.0)
    close(eq.internal(x, taut), K.toarray() @ x + Rd.T @ (s - S))
    A = eq.matrix(0.1, taut, 3.0)
    hand = 3.0 * M.toarray() + K.toarray() + 20.0 * Cm.toarray() + 5.0 * np.outer(Rd[0],
                                                                                   Rd[0])
    close(A.toarray(), hand)
    A = eq.matrix(0.1, np.array([True, True]), 3.0)
    close(A.toarray(), hand + 7.0 * np.outer(Rd[1], Rd[1]))
    e = eq.energy(x, x)
    st = np.maximum(S + c * (Rd @ x), 0) / c
    assert e == pytest.approx(0.5 * x @ (M.toarray() + K.toarray()) @ x + np.sum(
        0.5 * c * st**2 - 0.5 * S**2 / c - S * (Rd @ x)), rel=TOL)


def test_dense_with_sparse_R():
    eq = Equations(np.diag([J, m]), np.diag([kb, ks]), R=sp.csr_matrix([[-r, 1.0]]),
                   c=np.array([k]), S0=np.array([S0]))
    assert not sp.issparse(eq.R) and not sp.issparse(eq.RT)
    close(eq.R, [[-r, 1.0]]); close(eq.RT, [[-r], [1.0]])
    close(eq.internal(X, np.array([True])), hand_internal(X, True))


def test_dense_C_kept_when_small_sparse_M():
    """Small sparse M/K with no C: only M and K turned dense."""
    eq = Equations(sp.csr_matrix(np.diag([J, m])), sp.csr_matrix(np.diag([kb, ks])))
    assert eq.dense and eq.C is None


# ------------------------------------------------------------------ Factor
def spd(n, seed):
    rng = np.random.default_rng(seed)
    B = rng.standard_normal((n, n))
    return B @ B.T + n * np.eye(n)


@pytest.mark.parametrize("sparse", [False, True])
def test_factor(sparse):
    n = 6
    A = spd(n, 1)
    rng = np.random.default_rng(2)
    Vl = rng.standard_normal((n, 2))
    D = np.array([0.7, 1.9])
    free = np.array([0, 2, 3, 5])
    Af = A[np.ix_(free, free)]
    b = rng.standard_normal(len(free))
    Aop = sp.csr_matrix(A) if sparse else A
    f = Factor(Aop, free)
    close(f.solve(b), np.linalg.solve(Af, b), 1e-10)      # condition ~ 10: 1e-10 ample
    Vf = Vl[free]
    f = Factor(Aop, free, Vf, D)
    full = Af + Vf @ np.diag(D) @ Vf.T
    close(f.solve(b), np.linalg.solve(full, b), 1e-10)
    E = rng.standard_normal((len(free), 1))
    d = np.array([2.5])
    close(f.solve(b, (E, d)), np.linalg.solve(full + d[0] * E @ E.T, b), 1e-10)
    close(f.solve(b, (E, d)), np.linalg.solve(full + d[0] * E @ E.T, b), 1e-10)  # cached
    E2 = rng.standard_normal((len(free), 2))
    d2 = np.array([0.3, 4.0])
    close(f.solve(b, (E2, d2)), np.linalg.solve(full + E2 @ np.diag(d2) @ E2.T, b), 1e-10)
    g = Factor(Aop, free)
    close(g.solve(b, (E, d)), np.linalg.solve(Af + d[0] * E @ E.T, b), 1e-10)
    # an empty low-rank part is no low-rank part
    h = Factor(Aop, free, np.zeros((len(free), 0)), np.zeros(0))
    assert h.Z is None
    close(h.solve(b), np.linalg.solve(Af, b), 1e-10)
    close(h.solve_lowrank(b, None, None, None), np.linalg.solve(Af, b), 1e-10)


# ------------------------------------------------------------------ survivors' kills
def test_signal_rate_depends_on_time_and_unknown_rate_is_zero():
    """The rate is called at t; an unknown rate is exactly 0 even where the value is 0
    (not 0/0)."""
    s = Signal(lambda t, left=False: np.array([t, 0.0]),
               lambda t, left=False: np.array([2.0 * t, 0.0]))
    close(s.d(1.5), [3.0, 0.0])
    with np.errstate(all="raise"):
        d = Signal(lambda t, left=False: np.array([0.0, t])).d(0.0)
    assert np.all(d == 0.0) and np.all(np.isfinite(d))


def test_dense_up_to_DENSE_OPS():
    n = DENSE_OPS
    eq = Equations(sp.identity(n, format="csr"), sp.identity(n, format="csr"))
    assert eq.dense and not sp.issparse(eq.M)
    eq = Equations(sp.identity(n + 1, format="csr"), sp.identity(n + 1, format="csr"))
    assert not eq.dense


def test_two_motors_add():
    mot = Motor("linear", synchronous_speed=ns, stall_torque=Ms)
    eq = Equations(np.diag([J, m]), np.eye(2),
                   motors=[MotorLoad(np.array([1.0, 0.0]), mot, i_gear),
                           MotorLoad(np.array([0.0, 1.0]), mot, 2.0)])
    v = np.array([0.4, 3.0])
    close(eq.motor_force(v), [i_gear * Ms * (1 - i_gear * 0.4 / ns),
                              2.0 * Ms * (1 - 2.0 * 3.0 / ns)])


def test_energy_soft_row():
    """A row with 0 < c < 1 (a soft rope, N/m) counts like any other."""
    eq = Equations(np.diag([J, m]), np.diag([kb, ks]), R=np.array([[0.0, 1.0]]),
                   c=np.array([0.5]), S0=np.array([2.0]))
    x = np.array([0.0, 3.0])
    s = 2.0 + 0.5 * 3.0
    hand = 0.5 * ks * 9.0 + 0.5 * 0.5 * (s / 0.5)**2 - 0.5 * 4.0 / 0.5 - 2.0 * 3.0
    assert eq.energy(x, 0 * x) == pytest.approx(hand, rel=TOL)


def test_known_empty_is_an_integer_index():
    eq = hoist(contacts=np.array([1]), up=np.array([-1.0]))
    idx, xq, xv, xa = eq.known(1.0, np.array([False]))
    assert len(idx) == 0 and idx.dtype.kind == "i"
    close(X[idx], np.zeros(0))             # usable as an index (a float array is not)


def test_factor_keeps_its_free_set():
    free = np.array([0, 2])
    f = Factor(spd(3, 4), free)
    assert f.free is free
