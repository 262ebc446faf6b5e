"""Kill test for cranefe/analysis/operation/constraints.py (tools/mutation.py
constraints; docs/testing.md, "Mutation testing"): a step long enough for Newton's
method to contract slowly, so that the stepper refreshes its tangent.

The step's Newton iteration keeps its tangent while each correction shrinks by 10x and
makes a new one otherwise. The pendulum steps of tests/test_mutation_kills_constraints.py
converge at once, so the refresh never fired there. Here one trapezoidal step of
h = 1 s of the pendulum (l = 10 m, released at th = 0.7 rad with 1.3 m/s tangential)
from its exact multiplier: the predictor is off by 0.78 m and the tangent is
refreshed (measured: 3 tangents, 10 iterations). Reference, not computed by the
module: the trapezoidal index-1 equations of the step (module docstring)

    v1 = 2 (q1 - q0) / h - v0,   a1 = 4 (q1 - q0 - h v0) / h^2 - a0,
    m a1 = (0, -m g) - e1 S1,    e1 . a1 + (|v1|^2 - (e1 . v1)^2) / l1 = 0

(e1 the unit vector pivot -> q1, l1 = |q1 - pivot|) solved at 30 digits by mpmath,
then the step's one-correction projection, which for one mass on one rope is radial:
q = pivot + 10 e1, v = v1 - (e1 . v1) e1; the end state's acceleration
(F - e S) / m with S = m g cos th + m |v_perp|^2 / l, and the error estimate
h^2 / 12 |a1 - a0| / (tol l_scale) with the step's a1 before the projection.
"""

import functools
import math

import mpmath as mp
import numpy as np
from test_mutation_kills_constraints import PENDULUM, G, M, stepper

TH, VT, H = 0.7, 1.3, 1.0
PIVOT = np.array([0.0, 10.0])


def _start():
    e = np.array([math.sin(TH), -math.cos(TH)])
    q0 = PIVOT + 10 * e
    v0 = VT * np.array([math.cos(TH), math.sin(TH)])
    S0 = M * G * math.cos(TH) + M * VT * VT / 10
    a0 = (np.array([0.0, -M * G]) - e * S0) / M
    return q0, v0, a0, S0


@functools.cache
def _trapezoidal():
    """(q1, S1) of the trapezoidal equations at 30 digits (a hand reference: cached)."""
    q0, v0, a0, S0 = (np.asarray(x, float) for x in _start())
    q0m, v0m, a0m = ([mp.mpf(float(x)) for x in y] for y in (q0, v0, a0))
    h, m, g = mp.mpf(H), mp.mpf(M), mp.mpf(G)

    def res(x, z, S):
        q = [x, z]
        v = [2 * (q[i] - q0m[i]) / h - v0m[i] for i in range(2)]
        a = [4 * (q[i] - q0m[i] - h * v0m[i]) / h**2 - a0m[i] for i in range(2)]
        d = [q[0] - 0, q[1] - 10]
        l = mp.sqrt(d[0]**2 + d[1]**2)
        e = [d[0] / l, d[1] / l]
        ev = e[0] * v[0] + e[1] * v[1]
        return [m * a[0] + e[0] * S, m * a[1] + m * g + e[1] * S,
                e[0] * a[0] + e[1] * a[1] + (v[0]**2 + v[1]**2 - ev**2) / l]
    guess = (q0m[0] + h * v0m[0], q0m[1] + h * v0m[1], mp.mpf(float(S0)))
    with mp.workdps(30):
        x, z, S = mp.findroot(res, guess, tol=mp.mpf(10)**-40)
    return np.array([float(x), float(z)]), float(S)


def test_a_long_step_refreshes_its_tangent_and_solves_the_trapezoidal_equations(tmp_path):
    """The step's end state against the 30-digit trapezoidal solution, projected (to
    1e-8 m and 1e-8 m/s: Newton stops at a weighted correction of 1e-4 tol = 1e-9 m, and
    converges linearly at worst with the refreshed tangents; the projection then is
    exact), the acceleration there (to 1e-7 m/s^2 and S to 1e-7 relative, from q, v's
    1e-8), the error estimate (to 1e-6 relative: |a1 - a0| is 3.1 m/s^2, a1 = 4 q1 / h^2
    + ... known to 4e-8 m/s^2); and the tangent was refreshed (more than one made).
    Measured: every difference at round-off (1e-15 m, 7e-12 relative in the error)."""
    st, _ = stepper(tmp_path, PENDULUM, "  duration: 2\n  tolerance: 1.0e-6\n")
    q0, v0, a0, S0 = _start()
    taut = np.array([True])
    st._Sguess = np.array([S0])                 # the exact multiplier of the start
    t0 = st.tangents
    out = st.step(0.0, q0, v0, a0, H, taut)
    assert out is not None
    assert st.tangents - t0 > 1                 # the refresh fired
    q1, v1, a1, ev1, err = out
    qt, _ = _trapezoidal()
    vt = 2 * (qt - q0) / H - v0
    at = 4 * (qt - q0 - H * v0) / H**2 - a0
    e = (qt - PIVOT) / np.linalg.norm(qt - PIVOT)
    np.testing.assert_allclose(q1, PIVOT + 10 * e, rtol=0, atol=1e-8)
    vp = vt - (e @ vt) * e
    np.testing.assert_allclose(v1, vp, rtol=0, atol=1e-8)
    S = M * G * (-e[1]) + M * (vp @ vp) / 10
    np.testing.assert_allclose(ev1.S, [S], rtol=1e-7)
    np.testing.assert_allclose(a1, (np.array([0.0, -M * G]) - e * S) / M, rtol=0,
                               atol=1e-7)
    err_hand = float(np.abs(at - a0).max()) / st.tol * H * H / 12
    np.testing.assert_allclose(err, err_hand, rtol=1e-6)
    assert np.linalg.norm(qt - (q0 + H * v0 + 0.5 * H * H * a0)) > 0.1   # a hard step
