"""Kill tests for cranefe/analysis/luffing/optimum.py (issue 20, mutation testing): the
solvers of eq. 16 (J alpha.. + J' alpha.^2 / 2 = 0, alpha(0) = alpha0, alpha(1) = alphak)
on inertias whose optimum is a closed form.

J alpha.^2 is constant along the optimum, so sqrt(J) alpha. = S_k with S(alpha) =
int_alpha0^alpha sqrt(J):
- J = exp(2 k alpha) (f = J'/(2J) = k): e^(k alpha) is linear in tau,
  alpha = ln(E0 + tau (Ek - E0)) / k, E = e^(k alpha); alpha. = (Ek - E0) / (k E),
  alpha.. = -k alpha.^2, S_k = (Ek - E0) / k;
- J = (c + alpha)^2 (f = 1 / (c + alpha)): (c + alpha)^2 is linear in tau,
  alpha = -c + sqrt(P0 + tau (Pk - P0)), P = (c + alpha)^2, alpha. = (Pk - P0) / (2 (c +
  alpha)), alpha.. = -alpha.^2 / (c + alpha), S_k = (Pk - P0) / 2.
The paper's trial function (eq. 17) alpha0 + D t + t (1 - t)(a0 + a1 t + a2 t^2) is
differentiated here by numpy's polynomial class; the 3-point map's fixed point is checked
by the residuals of eq. 16 it must make zero at t = 1/4, 1/2, 3/4; for J constant (f = 0)
the map is linear and its matrix is written out from the module's docstring equations.

Tolerances: 1e-12 for closed forms evaluated to rounding (a Newton solve stopped at
1e-15 D, a few operations); the collocation of the log law with 14 Chebyshev points:
its interpolation error is below 1e-11 (the law's nearest singularity at tau =
-E0 / (Ek - E0) = -1.54, far outside [0, 1]): 1e-10 on alpha, 1e-9 on its derivatives
(a derivative of an interpolant loses about n^2 at the ends); solve_bvp at tol 1e-8: 1e-7 (its
residual tolerance, O(1) solution); the Chebyshev quadrature law with m = 24: 1e-12.
"""

import math

import numpy as np
import pytest
from numpy.polynomial import Polynomial as P

from cranefe.analysis.luffing import optimum as O

K, A0, AK = 0.8, 0.3, 1.1          # f = k; E0 = e^0.24, Ek = e^0.88
C_ = 0.5                           # J = (c + alpha)^2
PI4 = math.pi / 4
TAUS = np.array([0.0, 0.13, 0.5, 0.71, 1.0])


def _log_law(tau, a0=A0, ak=AK, k=K):
    E0, Ek = math.exp(k * a0), math.exp(k * ak)
    E = E0 + np.asarray(tau) * (Ek - E0)
    al = np.log(E) / k
    d1 = (Ek - E0) / (k * E)
    return al, d1, -k * d1**2


def _sqrt_law(tau, a0=A0, ak=AK, c=C_):
    P0, Pk = (c + a0) ** 2, (c + ak) ** 2
    s = np.sqrt(P0 + np.asarray(tau) * (Pk - P0))
    d1 = (Pk - P0) / (2 * s)
    return s - c, d1, -d1**2 / s


def _exp_exact(a0=A0, ak=AK, k=K):
    return O.exact_law(lambda a: (np.exp(k * a) - math.exp(k * a0)) / k,
                       lambda a: np.exp(k * a), lambda a: k + 0 * a, a0, ak)


def _f_const(a):
    return K + 0.0 * np.asarray(a)


def _allclose(got, want, tol=1e-12):
    np.testing.assert_allclose(np.asarray(got), np.asarray(want), rtol=0,
                               atol=tol)


@pytest.mark.parametrize("a0, ak", [(A0, AK), (AK, A0)])
def test_exact_law_log_case(a0, ak):
    law = _exp_exact(a0, ak)
    assert law.name == "optimal" and law.status == 0
    _allclose(law.info["S"], (math.exp(K * ak) - math.exp(K * a0)) / K)
    for got, want in zip(law.evaluate(TAUS), _log_law(TAUS, a0, ak)):
        _allclose(got, want)
    # outside [0, 1] the law is held at its ends (clipped)
    al = law.evaluate(np.array([-0.5, 1.5]))[0]
    _allclose(al, [a0, ak])
    _allclose(law.evaluate(0.4)[0], _log_law(0.4, a0, ak)[0])   # a scalar tau


def test_exact_law_sqrt_case_and_range():
    c = C_
    law = O.exact_law(lambda a: c * (a - A0) + (a**2 - A0**2) / 2, lambda a: c + a,
                      lambda a: 1 / (c + a), A0, AK, name="x")
    assert law.name == "x"
    for got, want in zip(law.evaluate(TAUS), _sqrt_law(TAUS)):
        _allclose(got, want)
    # a large swing (|D| > 1: the Newton stop scales with D), negative direction
    law = O.exact_law(lambda a: (np.exp(0.3 * a) - math.exp(0.3 * 4.0)) / 0.3,
                      lambda a: np.exp(0.3 * a), lambda a: 0.3 + 0 * a, 4.0, 0.5)
    for got, want in zip(law.evaluate(TAUS), _log_law(TAUS, 4.0, 0.5, 0.3)):
        _allclose(got, want, 1e-11)


@pytest.mark.parametrize("k", [8.0, -8.0])
def test_exact_law_newton_stays_in_the_range(k):
    # S strongly convex (k > 0) or concave (k < 0): Newton from the linear law jumps past
    # alphak (convex) or alpha0 (concave) at tau = 1/2 (first step 3.3 rad on a range of
    # 1); sqrt(J) here exists only on [alpha0, alphak] (like a linkage's inertia past its
    # range: nan), so the iterates must be held in it
    def sqrtJ(a):
        a = np.asarray(a, float)
        return np.where((a >= 0) & (a <= 1), np.exp(k * a), np.nan)
    law = O.exact_law(lambda a: (sqrtJ(a) - 1) / k, sqrtJ, lambda a: k + 0 * a, 0.0, 1.0)
    for got, want in zip(law.evaluate(TAUS), _log_law(TAUS, 0.0, 1.0, k)):
        np.testing.assert_allclose(got, want, rtol=1e-12)   # alpha. up to e^8: relative


def test_quadrature_law_from_values_of_J():
    calls = []

    def reduced(a):
        calls.append(np.array(a))
        return {"J": np.exp(2 * K * a), "dJ": 2 * K * np.exp(2 * K * a),
                "Jp": (C_ + a) ** 2, "dJp": 2 * (C_ + a)}
    m = 24
    law = O.quadrature_law(reduced, A0, AK, m)
    assert law.name == "quadrature m=24" and law.evaluations == m
    assert 0 <= law.time_s < 60
    # the m Chebyshev points of [alpha0, alphak]
    x = np.cos(np.pi * (np.arange(m) + 0.5) / m)
    _allclose(np.sort(calls[0]), np.sort(0.7 + 0.4 * x), 1e-15)
    for got, want in zip(law.evaluate(TAUS), _log_law(TAUS)):
        _allclose(got, want)
    _allclose(law.info["S"], (math.exp(K * AK) - math.exp(K * A0)) / K)
    # which="reduced": the 'Jp' entries, J = (c + alpha)^2; and a decreasing swing
    law = O.quadrature_law(reduced, AK, A0, m, which="reduced")
    for got, want in zip(law.evaluate(TAUS), _sqrt_law(TAUS, AK, A0)):
        _allclose(got, want)
    # m = 2: sqrt(J) = c + alpha is linear, so its 2-point interpolant is exact and so
    # are alpha and alpha.; alpha.. uses the linear interpolant of f = 1 / (c + alpha)
    # through the two Chebyshev points 0.7 -+ 0.4 cos(pi / 4)
    law = O.quadrature_law(reduced, A0, AK, 2, which="reduced")
    al, d1, d2 = law.evaluate(TAUS)
    ref = _sqrt_law(TAUS)
    _allclose(al, ref[0])
    _allclose(d1, ref[1])
    p, q = 0.7 - 0.4 * math.cos(PI4), 0.7 + 0.4 * math.cos(PI4)
    fp, fq = 1 / (C_ + p), 1 / (C_ + q)
    f_lin = fp + (fq - fp) * (ref[0] - p) / (q - p)
    _allclose(d2, -f_lin * ref[1] ** 2)


def test_paper_trial_by_polynomials():
    a = np.array([0.3, -0.7, 0.45])
    t = P([0, 1])
    al = A0 + (AK - A0) * t + t * (1 - t) * (a[0] + a[1] * t + a[2] * t**2)
    tau = np.array([0.0, 0.2, 0.25, 0.5, 0.9, 1.0])
    got = O.paper_trial(a, tau, A0, AK)
    for g, p in zip(got, (al, al.deriv(), al.deriv(2))):
        _allclose(g, p(tau))
    # no coefficients: the linear law
    got = O.paper_trial([], tau, A0, AK)
    _allclose(got[0], A0 + 0.8 * tau)
    _allclose(got[1], 0.8 + 0 * tau)
    _allclose(got[2], 0 * tau)


def test_points():
    _allclose(O.equally_spaced(3), [0.25, 0.5, 0.75], 0)
    _allclose(O.equally_spaced(1), [0.5], 0)
    for n in (1, 2, 5):
        t = O.chebyshev_points(n)
        assert len(t) == n
        # zeros of T_n(2 t - 1) = cos(n arccos(2 t - 1))
        _allclose(np.cos(n * np.arccos(2 * t - 1)), np.zeros(n), 1e-14)
        assert len(set(np.round(t, 12))) == n and np.all((t > 0) & (t < 1))
    _allclose(O.chebyshev_points(2), [0.5 - math.sqrt(2) / 4, 0.5 + math.sqrt(2) / 4],
              1e-15)


@pytest.mark.parametrize("with_df", [False, True])
def test_collocation_converges_to_the_log_law(with_df):
    n = 14
    df = (lambda a: 0 * np.asarray(a)) if with_df else None
    law = O.collocation(_f_const, A0, AK, O.chebyshev_points(n), df=df)
    assert law.status == 0 and law.message == "converged" and law.name == "collocation n=14"
    assert 1 <= law.iterations <= 10
    # f at the n points, and twice more for the differenced f' without df
    assert law.evaluations == law.iterations * n * (1 if with_df else 3)
    assert len(law.info["coefficients"]) == n
    assert 0 <= law.time_s < 60
    for got, want in zip(law.evaluate(TAUS), _log_law(TAUS)):
        _allclose(got, want, 1e-9)
    _allclose(law.evaluate(0.5)[0], _log_law(0.5)[0], 1e-10)
    # a wrong f' still converges (to the same law), only more slowly
    slow = O.collocation(_f_const, A0, AK, O.chebyshev_points(n),
                         df=lambda a: 5 + 0 * a)
    assert slow.status == 0 and slow.iterations > law.iterations
    # the sqrt law: f = 1 / (c + alpha), f' = -f^2; its singularity at tau = -P0 / (Pk -
    # P0) = -1/3 is nearer (Bernstein ellipse rho = 3.0): 24 points, 3^-24 ~ 4e-12
    law = O.collocation(lambda a: 1 / (C_ + a), A0, AK, O.chebyshev_points(24),
                        df=(lambda a: -1 / (C_ + a) ** 2) if with_df else None)
    assert law.status == 0
    # Newton with the exact matrix converges quadratically from the linear law: 5
    # iterations to 1e-14 here, with f' exact or by central differences (error 1e-12 of
    # f': the same iterates); a wrong Newton matrix converges linearly, in more
    assert law.iterations <= 5
    for got, want in zip(law.evaluate(TAUS), _sqrt_law(TAUS)):
        _allclose(got, want, 1e-9)


def test_collocation_reports_failure():
    law = O.collocation(_f_const, A0, AK, O.chebyshev_points(6), maxiter=1)
    assert law.status == 1 and law.iterations == 1
    assert law.message == "Newton did not converge"
    with np.errstate(all="ignore"):
        law = O.collocation(lambda a: np.full_like(a, np.nan), A0, AK,
                            O.chebyshev_points(3))
    assert law.status == 2 and law.iterations == 1


def _residuals(a, f, a0=A0, ak=AK):
    """eq. 16's residual alpha.. + f alpha.^2 of the trial function at 1/4, 1/2, 3/4."""
    t = P([0, 1])
    al = a0 + (ak - a0) * t + t * (1 - t) * (a[0] + a[1] * t + a[2] * t**2)
    x = np.array([0.25, 0.5, 0.75])
    return al.deriv(2)(x) + f(al(x)) * al.deriv()(x) ** 2


def test_paper_map_variants_by_hand():
    a = np.array([0.2, -0.1, 0.05])
    D = AK - A0
    t = P([0, 1])
    al = A0 + D * t + t * (1 - t) * (a[0] + a[1] * t + a[2] * t**2)
    f = lambda x: 1 / (C_ + x)
    f1, f2, f3 = f(al(np.array([0.25, 0.5, 0.75])))
    V1, V2, V3 = al.deriv()(np.array([0.25, 0.5, 0.75]))      # the correct alpha. values
    first = (a[1] + 1.5 * a[2]) / 4 + 0.5 * V1**2 * f1
    _allclose(O.paper_map(a, f, A0, AK),
              [first, -2 * a[0] + V2**2 * f2,
               -8 / 9 * a[0] - 10 / 9 * a[1] + 4 / 9 * V3**2 * f3])
    # eq. 21 and eq. 25 as printed (V's as the module: the correct values)
    _allclose(O.paper_map(a, f, A0, AK, "eq21"),
              [first, a[0] - V2**2 * f2, -2 / 3 * a[0] - 10 / 9 * a[1] + 4 / 9 * V3**2 * f3])
    _allclose(O.paper_map(a, f, A0, AK, "printed"),
              [first, a[0] - V2**2 * f2, -2 / 3 * a[0] - 10 / 9 * a[2] + 4 / 9 * V3**2 * f3])
    with pytest.raises(ValueError, match="other"):
        O.paper_map(a, f, A0, AK, "other")


def _hand_G(a, f):
    """The corrected map (paper_map's docstring) with alpha. at 1/4, 1/2, 3/4 of the
    trial function, written out; complex a allowed."""
    a0, a1, a2 = a
    D = AK - A0
    x = np.array([0.25, 0.5, 0.75])
    al = A0 + D * x + x * (1 - x) * (a0 + a1 * x + a2 * x**2)
    V = D + a0 * (1 - 2 * x) + a1 * (2 * x - 3 * x**2) + a2 * (3 * x**2 - 4 * x**3)
    f1, f2, f3 = f(al)
    return np.array([(a1 + 1.5 * a2) / 4 + 0.5 * V[0] ** 2 * f1, -2 * a0 + V[1] ** 2 * f2,
                     -8 / 9 * a0 - 10 / 9 * a1 + 4 / 9 * V[2] ** 2 * f3])


def _hand_jacobian(a, f, h=1e-30):
    return np.column_stack([_hand_G(np.asarray(a, complex) + 1j * h * e, f).imag / h
                            for e in np.eye(3)])


def test_paper_collocation_fixed_point_solves_the_residuals():
    f = lambda x: 1 / (C_ + x)
    # relax 0.45: the plain iteration (relax 1) diverges here, radius 1.42 (below)
    law = O.paper_collocation(f, A0, AK, relax=0.45)
    assert law.status == 0 and law.name == "paper 3-point (corrected)"
    assert law.message == f"fixed-point iteration converged in {law.iterations} iterations"
    a = np.array(law.info["iterate"])
    _allclose(_residuals(a, f), np.zeros(3), 1e-12)
    assert law.info["fixed_point_found"]
    _allclose(law.info["fixed_point"], a, 1e-12)
    assert law.info["variant"] == "corrected" and law.info["relax"] == 0.45
    h = law.info["history"]
    assert len(h) == law.iterations and h[-1] < 1e-13 <= h[-2]
    assert law.evaluations > 3 * law.iterations and 0 <= law.time_s < 60
    _allclose(law.evaluate(TAUS)[0], O.paper_trial(a, TAUS, A0, AK)[0], 0)
    # the 3-point law is near the exact one (a coarse approximation: 1e-3 rad here)
    assert np.abs(law.evaluate(TAUS)[0] - _sqrt_law(TAUS)[0]).max() < 2e-3
    # the radius at the fixed point: > 1 for relax = 1, < 1 relaxed by 0.45
    lam = np.array([complex(*v) for v in law.info["eigenvalues"]])
    _allclose(law.info["spectral_radius"], np.abs(lam).max(), 1e-14)
    assert law.info["spectral_radius"] > 1.4
    _allclose(law.info["spectral_radius_relaxed"], np.abs(0.55 + 0.45 * lam).max(), 1e-14)
    assert law.info["spectral_radius_relaxed"] < 1
    plain = O.paper_collocation(f, A0, AK)
    assert plain.status == 2 and plain.info["fixed_point_found"]
    assert plain.info["relax"] == 1.0 and plain.name == "paper 3-point (corrected)"
    # the iteration's matrix at the fixed point by complex steps (exact to rounding) of
    # the corrected map written out by hand: its eigenvalues (the module's central
    # differences with h = 1e-7: 1e-9)
    mu = np.linalg.eigvals(_hand_jacobian(a, f))
    _allclose(law.info["spectral_radius"], np.abs(mu).max(), 1e-7)
    _allclose(plain.info["fixed_point"], a, 1e-12)     # the same fixed point, Newton's
    _allclose(plain.evaluate(TAUS)[0], law.evaluate(TAUS)[0], 1e-12)


def test_paper_collocation_linear_map_spectrum():
    # f = 0: the corrected map is linear, G(a) = M a; the start a = 0 is its fixed point
    M = np.array([[0, 1 / 4, 3 / 8], [-2, 0, 0], [-8 / 9, -10 / 9, 0]])
    law = O.paper_collocation(lambda x: 0 * x, A0, AK, relax=0.5)
    assert law.status == 0 and law.iterations == 1
    lam = np.linalg.eigvals(M)
    _allclose(law.info["spectral_radius"], np.abs(lam).max(), 1e-7)
    _allclose(law.info["spectral_radius_relaxed"], np.abs(0.5 + 0.5 * lam).max(), 1e-7)
    got = np.sort_complex(np.array([complex(*v) for v in law.info["eigenvalues"]]))
    _allclose(got, np.sort_complex(lam.astype(complex)), 1e-7)
    # the best relaxation on the grid 0.001 .. 1.5 (1500 values)
    ws = np.linspace(0.001, 1.5, 1500)
    radii = np.array([np.abs(1 - w + w * lam).max() for w in ws])
    _allclose(law.info["relax_best"], ws[np.argmin(radii)], 2e-3)
    _allclose(law.info["spectral_radius_best"], radii.min(), 1e-6)
    _allclose(law.evaluate(TAUS)[0], A0 + 0.8 * TAUS)
    # the linear map's radius > 1: from a nonzero start the plain iteration diverges;
    # a large f drives the iterates off: diverged (status 2), the Newton point known
    law = O.paper_collocation(lambda x: 6 + 0 * x, A0, AK, "printed")
    assert law.status == 2 and law.message.startswith("fixed-point iteration diverged")
    h = law.info["history"]          # stopped at the first change above 1e6
    assert h[-1] > 1e6 >= max(h[:-1]) and np.isfinite(h[-1])
    assert law.info["variant"] == "printed" and law.name == "paper 3-point (printed)"
    # the printed map's own fixed point (Newton), not the corrected one's (f = 1/(c + a):
    # the printed iteration neither converges nor diverges in 500 sweeps)
    f = lambda x: 1 / (C_ + x)
    law = O.paper_collocation(f, A0, AK, "printed")
    assert law.status == 1 and law.iterations == 500 and law.info["fixed_point_found"]
    fp = np.array(law.info["fixed_point"])
    _allclose(O.paper_map(fp, f, A0, AK, "printed"), fp, 1e-12)
    assert np.abs(O.paper_map(fp, f, A0, AK) - fp).max() > 0.1
    # a slow iteration keeps the first 200 changes of its history
    law = O.paper_collocation(lambda x: 1 / (C_ + x), A0, AK, relax=0.01, maxiter=230)
    assert law.status == 1 and law.iterations == 230 and len(law.info["history"]) == 200
    law = O.paper_collocation(lambda x: 1 / (C_ + x), A0, AK, maxiter=3)
    assert law.status == 1 and law.iterations == 3
    assert law.message == "fixed-point iteration did not converge in 3 iterations"
    # not converged: the law is the Newton fixed point's, which solves the residuals
    _allclose(_residuals(np.array(law.info["fixed_point"]), lambda x: 1 / (C_ + x)),
              np.zeros(3), 1e-12)
    _allclose(law.evaluate(TAUS)[0],
              O.paper_trial(law.info["fixed_point"], TAUS, A0, AK)[0], 0)


def test_paper_collocation_nan_f():
    # f nan everywhere: the iteration diverges at once and Newton finds no fixed point
    law = O.paper_collocation(lambda x: np.full_like(x, np.nan), A0, AK)
    assert law.status == 2 and law.iterations == 1
    assert law.info["fixed_point_found"] is False and "spectral_radius" not in law.info
    assert np.isnan(law.evaluate(TAUS)[0][1:-1]).all()


def test_paper_collocation_raising_f_is_divergence():
    calls = []

    def f(x):
        calls.append(1)
        if len(calls) == 3:                 # the third sweep leaves the linkage's range
            raise ValueError("outside the linkage")
        return 1 / (C_ + x)
    law = O.paper_collocation(f, A0, AK, relax=0.45)
    assert law.status == 2 and law.iterations == 3
    assert law.message == "fixed-point iteration diverged after 3 iterations"
    assert law.info["fixed_point_found"]


def test_bvp_log_law():
    law = O.bvp(_f_const, A0, AK)
    assert law.status == 0 and law.name == "solve_bvp tol=1e-08"
    assert "converged" in law.message and 0 <= law.time_s < 60
    assert law.info["nodes"] >= 11 and law.evaluations > 0 and law.iterations >= 1
    for got, want in zip(law.evaluate(TAUS), _log_law(TAUS)):
        _allclose(got, want, 1e-7)
    law = O.bvp(lambda a: 1 / (C_ + a), AK, A0, tol=1e-10, nodes=5)
    assert law.name == "solve_bvp tol=1e-10"
    for got, want in zip(law.evaluate(TAUS), _sqrt_law(TAUS, AK, A0)):
        _allclose(got, want, 1e-8)


def test_law_error_and_counted():
    exact = _exp_exact()
    off = O.LawSolution("off", lambda t: (exact.evaluate(t)[0] + 0.01 * np.sin(np.pi * t),
                                          None, None))
    _allclose(O.law_error(off, exact), 0.01, 1e-15)          # at tau = 1/2 on the grid
    assert O.GRID.size == 401 and O.GRID[0] == 0 and O.GRID[-1] == 1
    _allclose(O.law_error(off, exact, tau=np.array([0.0, 1 / 6])), 0.005, 1e-15)
    c = O._Counted(lambda a: 2 * a)
    _allclose(c([1, 2, 3]), [2, 4, 6], 0)
    c(0.5)
    assert c.count == 4
