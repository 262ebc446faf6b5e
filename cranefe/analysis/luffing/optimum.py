"""The energy-optimal luffing law: eq. 16 of Loveikin et al. (2013) solved four ways.

In dimensionless time tau = t / t_k (dots are d/dtau) eq. 16 reads

    J(alpha) alpha.. + 1/2 J'(alpha) alpha.^2 = 0,   alpha(0) = alpha0, alpha(1) = alphak,

i.e. alpha.. + f(alpha) alpha.^2 = 0 with f = J'/(2J) (the paper's eq. 22). Because
d/dtau (J alpha.^2) = 2 alpha. (eq. 16), J alpha.^2 is constant along the optimum:

- ``exact_law``: quadrature, tau(alpha) = S(alpha) / S(alphak), S = int_alpha0 sqrt(J);
  the mean kinetic energy is T_mean = S(alphak)^2 / (2 t_k^2) (Cauchy-Schwarz: no law
  does better, equality only for J alpha.^2 = const);
- ``paper_collocation``: the paper's 3-point collocation with its fixed-point iteration
  (eq. 17-25), as printed and corrected (docs/luffing.md derives the corrections);
- ``collocation``: n-point collocation solved by Newton (equally spaced or Chebyshev
  points), the paper's trial function (eq. 17) in a Chebyshev basis;
- ``bvp``: scipy's solve_bvp.

Each solver takes ``f(alpha)`` (vectorised) and returns a `LawSolution`; errors are
measured against the exact law by `law_error`.
"""

import time
from dataclasses import dataclass, field

import numpy as np

GRID = np.linspace(0.0, 1.0, 401)       # instants where law errors are measured


@dataclass
class LawSolution:
    """A boom-angle law alpha(tau), tau = t / t_k in [0, 1].

    ``evaluate(tau)`` returns (alpha, alpha., alpha..) (derivatives in tau)."""

    name: str
    evaluate: object
    status: int = 0                   # 0 converged; 1 not converged; 2 diverged
    message: str = ""
    iterations: int = 0
    evaluations: int = 0              # calls of f (number of angles)
    time_s: float = 0.0
    info: dict = field(default_factory=dict)


class _Counted:
    """f with a count of the angles it was evaluated at."""

    def __init__(self, f):
        self.f, self.count = f, 0

    def __call__(self, alpha):
        alpha = np.asarray(alpha, dtype=float)
        self.count += alpha.size
        return self.f(alpha)


# ---------------------------------------------------------------------- exact law
def exact_law(sqrtJ_int, sqrtJ, dJ_over_2J, alpha0, alphak, name="optimal"):
    """The optimum by quadrature (eq. 16 integrated once: J alpha.^2 = const).

    Parameters
    ----------
    sqrtJ_int : callable, S(alpha) = int_alpha0^alpha sqrt(J) (vectorised)
    sqrtJ : callable, sqrt(J(alpha)); dJ_over_2J : callable, f(alpha) = J'/(2J)
    """
    total = float(sqrtJ_int(np.array([alphak]))[0])
    D = alphak - alpha0
    lo, hi = min(alpha0, alphak), max(alpha0, alphak)

    def alpha_of(tau):
        tau = np.clip(np.atleast_1d(np.asarray(tau, dtype=float)), 0.0, 1.0)
        a = alpha0 + D * tau
        for _ in range(50):                          # Newton on S(alpha) = tau S_k
            step = (sqrtJ_int(a) - tau * total) / sqrtJ(a)
            a = np.clip(a - step, lo, hi)
            if np.abs(step).max() < 1e-15 * max(1.0, abs(D)):
                break
        return a

    def evaluate(tau):
        a = alpha_of(tau)
        da = total / sqrtJ(a)                        # J alpha.^2 = S_k^2
        dda = -dJ_over_2J(a) * da**2                 # Loveikin et al. (2013) eq. 16
        return a, da, dda

    return LawSolution(name, evaluate, info={"S": total})


def quadrature_law(reduced_f, alpha0, alphak, m, which="complete"):
    """The quadrature optimum from m values of J only (Chebyshev interpolation of sqrt(J)
    at m points, integrated exactly): the cheap form of the exact law, for the cost study.

    reduced_f : callable alpha -> dict with 'J', 'dJ' (or 'Jp', 'dJp') arrays."""
    from numpy.polynomial import chebyshev as C
    t0 = time.perf_counter()
    lo, hi = min(alpha0, alphak), max(alpha0, alphak)
    x = np.cos(np.pi * (np.arange(m) + 0.5) / m)
    a = 0.5 * (hi + lo) + 0.5 * (hi - lo) * x
    v = reduced_f(a)
    key = "J" if which == "complete" else "Jp"
    cs = C.chebfit(x, np.sqrt(v[key]), m - 1)
    cf = C.chebfit(x, 0.5 * v["d" + key] / v[key], m - 1)
    ci = C.chebint(cs) * (hi - lo) / 2

    def unit(al):
        return (2 * np.asarray(al) - hi - lo) / (hi - lo)

    law = exact_law(lambda al: C.chebval(unit(al), ci) - C.chebval(unit(alpha0), ci),
                    lambda al: C.chebval(unit(al), cs), lambda al: C.chebval(unit(al), cf),
                    alpha0, alphak, name=f"quadrature m={m}")
    law.evaluations = m
    law.time_s = time.perf_counter() - t0
    return law


# ---------------------------------------------------------------------- trial functions
def paper_trial(a, tau, alpha0, alphak):
    """Eq. 17 (with t for the printed t_n): alpha = alpha0 + [D + (1-t) sum a_i t^i] t,
    and its first two derivatives in tau. a : (n,) coefficients a_0..a_{n-1}."""
    tau = np.asarray(tau, dtype=float)
    D = alphak - alpha0
    al = alpha0 + D * tau
    d1 = D + 0.0 * tau
    d2 = 0.0 * tau
    for i, ai in enumerate(a):
        al = al + ai * (tau ** (i + 1) - tau ** (i + 2))
        d1 = d1 + ai * ((i + 1) * tau**i - (i + 2) * tau ** (i + 1))
        d2 = d2 + ai * (i + 1) * ((i * tau ** (i - 1) if i > 0 else 0.0)
                                  - (i + 2) * tau**i)
    return al, d1, d2


def _cheb_basis(n, tau):
    """phi_i = tau (1 - tau) T_i(2 tau - 1), i < n, and derivatives: (3, len(tau), n)."""
    from numpy.polynomial import Chebyshev
    x = Chebyshev.identity(domain=[0, 1])
    out = np.empty((3, len(tau), n))
    for i in range(n):
        p = x * (1 - x) * Chebyshev.basis(i, domain=[0, 1])
        out[0, :, i] = p(tau)
        out[1, :, i] = p.deriv()(tau)
        out[2, :, i] = p.deriv(2)(tau)
    return out


def equally_spaced(n):
    """t_j = j / (n + 1): the paper's 1/4, 1/2, 3/4 for n = 3."""
    return np.arange(1, n + 1) / (n + 1)


def chebyshev_points(n):
    """Zeros of T_n mapped to (0, 1)."""
    return 0.5 * (1 - np.cos((2 * np.arange(1, n + 1) - 1) * np.pi / (2 * n)))


def collocation(f, alpha0, alphak, points, df=None, tol=1e-14, maxiter=50):
    """n-point collocation of eq. 16 solved by Newton.

    Trial function (eq. 17): alpha = alpha0 + D tau + tau (1 - tau) sum_i a_i T_i(2 tau - 1)
    (the paper's polynomial space in a Chebyshev basis), residual at the points
    r_j = alpha.. + f(alpha) alpha.^2. The Newton matrix needs f'; without ``df`` it
    comes from central differences of f (step 1e-6 rad; only the Newton matrix uses it,
    the residuals are exact)."""
    t0 = time.perf_counter()
    fc = _Counted(f)
    pts = np.asarray(points, dtype=float)
    n = len(pts)
    D = alphak - alpha0
    B = _cheb_basis(n, pts)
    c = np.zeros(n)
    status, it = 1, 0
    for it in range(1, maxiter + 1):
        al = alpha0 + D * pts + B[0] @ c
        d1 = D + B[1] @ c
        d2 = B[2] @ c
        fv = fc(al)
        r = d2 + fv * d1**2
        if df is None:
            h = 1e-6
            dfv = (fc(al + h) - fc(al - h)) / (2 * h)
        else:
            dfv = df(al)
        Jm = B[2] + (dfv * d1**2)[:, None] * B[0] + (2 * fv * d1)[:, None] * B[1]
        step = np.linalg.solve(Jm, -r)
        c += step
        if not np.all(np.isfinite(c)):
            status = 2
            break
        if np.abs(step).max() < tol * max(1.0, abs(D)):
            status = 0
            break

    def evaluate(tau):
        tau = np.atleast_1d(np.asarray(tau, dtype=float))
        Bt = _cheb_basis(n, tau)
        return alpha0 + D * tau + Bt[0] @ c, D + Bt[1] @ c, Bt[2] @ c

    return LawSolution(f"collocation n={n}", evaluate, status,
                       "converged" if status == 0 else "Newton did not converge", it,
                       fc.count, time.perf_counter() - t0, {"coefficients": c.tolist()})


# ---------------------------------------------------------------------- the paper's method
# Values of eq. 17 at t = 1/4, 1/2, 3/4 (n = 2, coefficients a0, a1, a2):
#   alpha.  = D + a0/2 + 5 a1/16 + a2/8,   D + a1/4 + a2/4,   D - a0/2 - 3 a1/16
#   alpha.. = -2 a0 + a1/2 + 3 a2/4,       -2 a0 - a1,         -2 a0 - 5 a1/2 - 9 a2/4
# The paper prints (eq. 19-20) alpha._2 = D + a0/2 + a1/4 + a2/4, alpha.._2 = -a0 - a1 - a2,
# alpha._3 = D + a0/2 - 3 a1/16 - a2/8, alpha.._3 = -3 a0/2 - 10 a1/4 - 9 a2/4.
def paper_map(a, f, alpha0, alphak, variant="corrected"):
    """One sweep of the fixed-point iteration (Loveikin et al. (2013) eq. 25).

    variant 'printed': eq. 25 exactly as printed (its line 3 has a_2 where eq. 21 has
    a_1); 'eq21': eq. 21 as printed; 'corrected': each residual of eq. 16 at t_j solved
    for a_{j-1}, from the correct values above:
        a0 = (a1 + 3/2 a2)/4 + 1/2 V1^2 f1
        a1 = -2 a0 + V2^2 f2
        a2 = -8/9 a0 - 10/9 a1 + 4/9 V3^2 f3."""
    a0, a1, a2 = a
    D = alphak - alpha0
    al = paper_trial(a, np.array([0.25, 0.5, 0.75]), alpha0, alphak)[0]
    f1, f2, f3 = f(al)
    V1 = D + 0.5 * (a0 + 5 / 8 * a1 + a2 / 4)
    V2 = D + (a1 + a2) / 4
    V3 = D - 0.5 * (a0 + 3 / 8 * a1)
    first = (a1 + 1.5 * a2) / 4 + 0.5 * V1**2 * f1          # eq. 21/25 line 1 (correct)
    if variant == "corrected":
        return np.array([first, -2 * a0 + V2**2 * f2,
                         -8 / 9 * a0 - 10 / 9 * a1 + 4 / 9 * V3**2 * f3])
    if variant == "eq21":
        return np.array([first, a0 - V2**2 * f2, -2 / 3 * a0 - 10 / 9 * a1 + 4 / 9 * V3**2 * f3])
    if variant == "printed":
        return np.array([first, a0 - V2**2 * f2, -2 / 3 * a0 - 10 / 9 * a2 + 4 / 9 * V3**2 * f3])
    raise ValueError(variant)


def _jacobian(g, a, h=1e-7):
    base = g(a)
    out = np.empty((len(a), len(a)))
    for k in range(len(a)):
        e = np.zeros(len(a))
        e[k] = h
        out[:, k] = (g(a + e) - g(a - e)) / (2 * h)
    return out, base


def paper_collocation(f, alpha0, alphak, variant="corrected", relax=1.0, maxiter=500,
                      tol=1e-13):
    """The paper's 3-point collocation with fixed-point iteration (eq. 25).

    a_{k+1} = (1 - relax) a_k + relax G(a_k) from a = 0 (the linear law). Reports whether
    it converged, the iterations, and the spectral radius of the iteration at the
    fixed point of G (found by Newton, so it is known even when the iteration diverges)
    and for relax = 1. info['relax_best'] is the relaxation that minimises that radius."""
    t0 = time.perf_counter()
    fc = _Counted(f)

    def G(a):
        return paper_map(a, fc, alpha0, alphak, variant)

    a = np.zeros(3)
    status, k, history = 1, 0, []
    with np.errstate(all="ignore"):
        for k in range(1, maxiter + 1):
            try:
                new = (1 - relax) * a + relax * G(a)
            except Exception:          # iterates left the linkage's range: diverged
                status = 2
                break
            change = np.abs(new - a).max()
            history.append(float(change))
            a = new
            if not np.all(np.isfinite(a)) or change > 1e6:
                status = 2
                break
            if change < tol:
                status = 0
                break
    iterate = a
    # the fixed point of G by Newton (from the linear law), and the iteration's radius
    fixed = np.zeros(3)
    newton_ok = False
    with np.errstate(all="ignore"):
        for _ in range(60):
            Jg, g = _jacobian(G, fixed)
            step = np.linalg.solve(Jg - np.eye(3), -(g - fixed))
            fixed = fixed + step
            if not np.all(np.isfinite(fixed)):
                break
            if np.abs(step).max() < 1e-14:
                newton_ok = True
                break
    info = {"variant": variant, "relax": relax, "history": history[:200],
            "fixed_point": fixed.tolist(), "fixed_point_found": newton_ok,
            "iterate": iterate.tolist()}
    if newton_ok:
        Jg, _ = _jacobian(G, fixed)
        lam = np.linalg.eigvals(Jg)
        info["eigenvalues"] = [[float(v.real), float(v.imag)] for v in lam]
        info["spectral_radius"] = float(np.abs(lam).max())
        info["spectral_radius_relaxed"] = float(np.abs(1 - relax + relax * lam).max())
        ws = np.linspace(0.001, 1.5, 1500)
        radii = [np.abs(1 - w + w * lam).max() for w in ws]
        info["relax_best"] = float(ws[int(np.argmin(radii))])
        info["spectral_radius_best"] = float(min(radii))
    coef = iterate if status == 0 else fixed

    def evaluate(tau):
        return paper_trial(coef, np.atleast_1d(tau), alpha0, alphak)

    msg = {0: f"fixed-point iteration converged in {k} iterations",
           1: f"fixed-point iteration did not converge in {k} iterations",
           2: f"fixed-point iteration diverged after {k} iterations"}[status]
    return LawSolution(f"paper 3-point ({variant})", evaluate, status, msg, k, fc.count,
                       time.perf_counter() - t0, info)


# ---------------------------------------------------------------------- solve_bvp
def bvp(f, alpha0, alphak, tol=1e-8, nodes=11):
    """scipy.integrate.solve_bvp on y = (alpha, alpha.), y' = (alpha., -f alpha.^2)."""
    from scipy.integrate import solve_bvp
    t0 = time.perf_counter()
    fc = _Counted(f)
    D = alphak - alpha0
    tau = np.linspace(0, 1, nodes)
    y0 = np.vstack([alpha0 + D * tau, D * np.ones_like(tau)])
    sol = solve_bvp(lambda x, y: np.vstack([y[1], -fc(y[0]) * y[1] ** 2]),
                    lambda ya, yb: np.array([ya[0] - alpha0, yb[0] - alphak]),
                    tau, y0, tol=tol, max_nodes=100000)

    def evaluate(tau):
        y = sol.sol(np.atleast_1d(tau))
        return y[0], y[1], -f(y[0]) * y[1] ** 2

    return LawSolution(f"solve_bvp tol={tol:g}", evaluate, sol.status, sol.message,
                       sol.niter, fc.count, time.perf_counter() - t0,
                       {"nodes": int(sol.x.size)})


def law_error(law, exact, tau=GRID):
    """max |alpha - alpha_exact| (rad) over the instants tau."""
    return float(np.abs(law.evaluate(tau)[0] - exact.evaluate(tau)[0]).max())
