"""Kill test for cranefe/analysis/operation/fast.py (issue 20, mutation testing;
tools/mutation.py fast_step) in a configuration the other fast kill tests do not build:
a Newton matrix 4/h^2 M + 2/h C + K whose partial pivoting swaps rows, so that the
pivot array the step keeps is read back by the solve (with the steps of
test_mutation_kills_lean_fast.py the matrix is diagonally dominant: no swap, and a
pivot array of floats went unnoticed in plain Python; numba refuses it when compiling).

The trolley pendulum of test_mutation_kills_lean.py (1000 kg on 10 m of rope, EA 1e7 N)
swung out to 37 deg (the load at (6, 2) with the trolley at 0: the rope along
(0.6, -0.8)), damped, one step of h = 0.3 s: EA/L e e^T has the off-diagonal entry
0.48 EA/L = 4.8e5 N/m against the diagonal's 4 m / h^2 + 0.36 EA/L + ... = 3.9e5 N/m,
so the first column's pivot is the second row. FastLean.step (plain Python without
numba, compiled with it) against integrate.Stepper.step with Lean (fast=False: the
numpy reference, mutation-tested against hand values itself): q1, v1, a1, the error,
the iteration and tangent counts, the last iterate's forces.

Tolerance: 1e-10 of each quantity's scale (the same formulas in another order; compiled
code rounds differently), as test_mutation_kills_lean_fast.py.
"""

import numpy as np
import pytest
from test_mutation_kills_lean import _mech

from cranefe.analysis.operation import fast
from cranefe.analysis.operation import integrate as integ
from cranefe.analysis.operation.integrate import Stepper
from cranefe.analysis.operation.lean import Lean
from cranefe.analysis.operation.scene import parse

REF = 1e-10


@pytest.mark.parametrize("jerk", [None, np.array([0.4, -0.2])])
def test_a_step_whose_newton_matrix_needs_a_row_swap(jerk):
    mech = _mech("trolley", "{damping: exact}")
    spec = parse(mech.model)
    ref = Stepper(mech, spec, mech.model.length_scale, fast=False)
    assert type(ref.ops) is Lean
    fl = fast.FastLean(mech)
    t, h = 0.0, 0.3
    q, v, taut = np.array([6.0, 2.0]), np.array([0.5, 0.3]), np.array([True])
    a, _ = ref.accel(t, q, v, taut)
    # the first Newton matrix (at the predictor) swaps its rows
    q1 = q + h * v + 0.5 * h * h * a + (0.0 if jerk is None else 0.25 * h ** 3 * jerk)
    ev = mech.evaluate(t + h, q1, 2 / h * (q1 - q) - v, taut)
    J = ev.K + 2 / h * ev.C + 4 / h ** 2 * np.diag(ref.M)
    assert abs(J[1, 0]) > 1.1 * abs(J[0, 0])
    piv = np.zeros(2, np.int64)
    assert fast._lu(J.copy(), piv) and piv[0] == 1
    n0 = (ref.newton_iterations, ref.tangents)
    x = ref.step(t, q, v, a, h, taut, jerk)
    y = fl.step(t + h, q, v, a, h, taut, jerk, ref.M, ref.newton_tol, integ.NEWTON_MAX,
                ref.fscale, ref.sfloor, ref.tol)
    assert x is not None and y[0] == 0
    assert y[5] == ref.newton_iterations - n0[0] and y[5] >= 3
    assert y[6] == ref.tangents - n0[1]
    evr, evf = x[3], y[7]
    s = np.abs(evr.S).max() + np.abs(evr.Sd).max() + np.abs(mech.Fg).max()
    for u, w, sc in ((x[0], y[1], 10.0), (x[1], y[2], 1.0),
                     (x[2], y[3], np.abs(x[2]).max() + 1.0), (evr.F, evf.F, s),
                     (evr.S, evf.S, s), (evr.Sd, evf.Sd, s), (evr._q, evf._q, 10.0)):
        np.testing.assert_allclose(w, u, rtol=0, atol=REF * sc)
    assert y[4] == pytest.approx(x[4], rel=1e-8, abs=1e-12)
