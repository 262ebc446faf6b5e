"""Value tests that kill the mutants of cranefe/elements/ropes.py that the fast tests left
alive (tools/mutation.py ropes; docs/testing.md, "Mutation testing").

One span from a = (1, 2, -1) to b = a + (3, 0, 4) (l = 5, e = (0.6, 0, 0.8), a 3-4-5 triangle, so
every geometric number is exact in binary up to one rounding), f = 2 falls, EA = 1000 N,
L0 = 9 m: L = f l = 10 m, S = EA ln(L / L0) = 1000 ln(10/9) N, c = dS/dL = EA / L = 100 N/m.
The tangent stiffness is written out by hand: c r r^T with r = f (-e, e), plus the span's
tension stiffness (f S / l)(I - e e^T) on [[1, -1], [-1, 1]] (docs/theory.md).
Tolerances: 1e-12 relative, a few roundings of numbers of order 1e3.
"""

import math

import numpy as np

from cranefe.elements.ropes import (hencky_energy, hencky_tension, projected_tangent,
                                    rope_force, rope_mass, rope_spans, rope_state,
                                    spring_state)

X = np.array([[1.0, 2.0, -1.0], [4.0, 2.0, 3.0]])   # a = (1, 2, -1), b = a + (3, 0, 4)
E = np.array([0.6, 0.0, 0.8])
A, B, F, ROPE = np.array([0]), np.array([1]), np.array([2.0]), np.array([0])
EA, L0 = np.array([1000.0]), np.array([9.0])
RTOL = 1e-12


def _blocks(g):
    return np.kron(np.array([[1.0, -1.0], [-1.0, 1.0]]), g)


def _rope_K(S, c, L):
    r = np.concatenate([-2.0 * E, 2.0 * E])
    return c * np.outer(r, r) + _blocks(2.0 * S / 5.0 * (np.eye(3) - np.outer(E, E)))


def test_hencky_tension_is_ea_log_stretch_with_tangent_ea_over_length():
    """S = EA ln(L/L0), dS/dL = EA/L (docs/operations.md, "Rope law"); kills EA / ln and
    ln(L * L0). Also the energy U = EA (L ln(L/L0) - L + L0), whose derivative is S."""
    S, c = hencky_tension(1000.0, 10.0, 9.0)
    assert math.isclose(S, 1000.0 * math.log(10.0 / 9.0), rel_tol=RTOL)
    assert math.isclose(c, 100.0, rel_tol=RTOL)
    U = hencky_energy(1000.0, 10.0, 9.0)
    assert math.isclose(U, 1000.0 * (10.0 * math.log(10.0 / 9.0) - 1.0), rel_tol=RTOL)


def test_rope_state_of_one_inclined_span_by_hand():
    """L, S, r and K of rope_state against the hand values above (the operation engine's
    kernel; before this test only tests/test_operation.py reached it, in 70 s)."""
    L, S, r, K = rope_state(X, A, B, F, ROPE, EA, L0)
    S_ex = 1000.0 * math.log(10.0 / 9.0)
    assert np.allclose(L, [10.0], rtol=RTOL) and np.allclose(S, [S_ex], rtol=RTOL)
    assert np.allclose(r[0], [-2.0 * E, 2.0 * E], rtol=RTOL, atol=0.0)
    assert np.allclose(K, _rope_K(S_ex, 100.0, 10.0), rtol=RTOL, atol=1e-12)
    # length not in the spans (drum turns): L = 10 + 1, tension and c follow it
    L, S, r, K = rope_state(X, A, B, F, ROPE, EA, L0, extra=np.array([1.0]))
    S_ex = 1000.0 * math.log(11.0 / 9.0)
    assert np.allclose(L, [11.0], rtol=RTOL) and np.allclose(S, [S_ex], rtol=RTOL)
    assert np.allclose(K, _rope_K(S_ex, 1000.0 / 11.0, 11.0), rtol=RTOL, atol=1e-12)
    # slack (L0 > L): no force, no stiffness
    L, S, r, K = rope_state(X, A, B, F, ROPE, EA, np.array([12.0]))
    assert S[0] == 0.0 and not K.any()
    # taut given by the caller overrides L > L0
    L, S, r, K = rope_state(X, A, B, F, ROPE, EA, L0, taut=np.array([False]))
    assert S[0] == 0.0 and not K.any()


def test_rope_force_keeps_the_stiffness_of_a_rope_with_a_small_tension():
    """A rope taut by 0.5 N still has c = EA / L: the taut test is S > 0, not S > 1 N
    (a mutant that zeroed c below 1 N survived). L0 = 10 exp(-0.5/1000) gives S = 0.5 N.
    Without `extra`, L is the spans' length alone (the default extra is 0)."""
    L0s = np.array([10.0 * math.exp(-0.5 / 1000.0)])
    rf = rope_force(X, A, B, F, ROPE, EA, L0s)
    assert np.allclose(rf.L, [10.0], rtol=RTOL)
    assert np.allclose(rf.S, [0.5], rtol=1e-9)       # ln of 1 + 5e-4: 1e-13 / 5e-4 relative
    assert np.allclose(rf.c, [100.0], rtol=RTOL)
    l, e, L, S = rope_spans(X, A, B, F, ROPE, EA, L0)
    assert np.allclose(L, [10.0], rtol=RTOL) and np.allclose(l, [5.0], rtol=RTOL)
    assert np.allclose(S, [1000.0 * math.log(10.0 / 9.0)], rtol=RTOL)


def test_spring_state_of_one_inclined_spring_by_hand():
    """N = N_ref + k (d - d_ref) = 10 + 200 (5 - 3) = 410 N; K = k e e^T + (N/d)(I - e e^T)
    on [[1, -1], [-1, 1]]."""
    d, N, r, K = spring_state(X, A, B, np.array([200.0]), np.array([3.0]),
                              np.array([10.0]))
    assert np.allclose(d, [5.0], rtol=RTOL) and np.allclose(N, [410.0], rtol=RTOL)
    assert np.allclose(r[0], [-E, E], rtol=RTOL, atol=0.0)
    K_ex = _blocks(200.0 * np.outer(E, E) + 410.0 / 5.0 * (np.eye(3) - np.outer(E, E)))
    assert np.allclose(K, K_ex, rtol=RTOL, atol=1e-12)


def test_rope_mass_consistent_and_lumped_by_hand():
    """mu l = 2 kg/m x 3 m = 6 kg: consistent mu l / 6 [[2, 1], [1, 2]] per direction
    (linear shape functions), lumped 3 kg at each end; both carry 6 kg in a translation."""
    Mc = rope_mass(np.array([2.0]), np.array([3.0]))[0]
    assert np.allclose(Mc, np.kron([[2.0, 1.0], [1.0, 2.0]], np.eye(3)), rtol=RTOL, atol=0)
    Ml = rope_mass(np.array([2.0]), np.array([3.0]), lumped=True)[0]
    assert np.allclose(Ml, 3.0 * np.eye(6), rtol=RTOL, atol=0.0)


def test_projected_tangent_is_the_string_stiffness_on_end_differences():
    """With D = [-I, I] (span-end difference on (x_a, x_b)) and w = f S / l, the projected
    tangent is (w)(I - e e^T) on [[1, -1], [-1, 1]]; two spans add."""
    D = np.hstack([-np.eye(3), np.eye(3)])[None]
    e2 = np.array([0.0, 1.0, 0.0])
    K = projected_tangent(np.array([7.0, 3.0]), np.array([E, e2]), np.concatenate([D, D]))
    K_ex = _blocks(7.0 * (np.eye(3) - np.outer(E, E)) + 3.0 * (np.eye(3) - np.outer(e2, e2)))
    assert np.allclose(K, K_ex, rtol=RTOL, atol=1e-12)
