"""Value tests that kill the mutants of cranefe/analysis/damping/element.py that
tests/test_values.py and tests/test_damping.py left alive (tools/mutation.py
damping_element; docs/testing.md, "Mutation testing"): the k1 of eq. 13 was only ever 1,
small elongation amplitudes (den < 1) were never given to k1, and no beam carried psi.
"""

import math

import numpy as np

from cranefe.analysis.damping import (damping_matrix, equivalent_viscous, polyharmonic_k1,
                                      psi_stiffness)
from cranefe.model import load
from cranefe.system import assemble


def test_equivalent_viscous_divides_by_k1():
    """b = psi c / (2 pi w k1) (Heletiy 2016 eq. 13): psi 0.2, c 3e5 N/m, w 4 rad/s,
    k1 = 2.5: b = 0.2 * 3e5 / (2 pi * 4 * 2.5) = 60000 / (20 pi) N s/m."""
    b = equivalent_viscous(0.2, 3.0e5, 4.0, k1=2.5)
    assert math.isclose(b, 60000.0 / (20.0 * math.pi), rel_tol=1e-14)
    bs = equivalent_viscous([0.2, 0.1], [3.0e5, 1.0e5], [4.0, 2.0], k1=np.array([2.5, 0.5]))
    assert np.allclose(bs, [60000.0 / (20.0 * math.pi), 1.0e4 / (2.0 * math.pi)], rtol=1e-14)


def test_polyharmonic_k1_with_small_amplitudes_and_none():
    """k1 = sum a_j^2 r_j^2 / sum a_j^2 r_j (r_j = w_j / w_1), which does not depend on the
    amplitudes' scale: a = (0.1, 0.1) mm-size elongations, w = (1, 2): (0.01 + 0.04) /
    (0.01 + 0.02) = 5/3, the same as for a = (1, 1); no motion at all (den = 0) gives 1."""
    assert math.isclose(polyharmonic_k1([0.1, 0.1], [1.0, 2.0]), 5.0 / 3.0, rel_tol=1e-14)
    assert math.isclose(polyharmonic_k1([1e-4, 1e-4], [1.0, 2.0]), 5.0 / 3.0, rel_tol=1e-12)
    assert polyharmonic_k1([0.0, 0.0], [1.0, 2.0]) == 1.0


BEAM = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {O: [0, 0, 0], T: [4, 0, 0]}
ground: [O]
masses: {T: 100.0}
members:
  arm: {type: beam, nodes: [O, T], E: 2.1e11, A: 1.0e-3, Iy: 1.0e-6, rho: 0,
        elements: 2, psi: 0.3}
effects: {structure: flexible}
"""


def test_beam_absorption_weights_the_beam_stiffness():
    """A cantilever of beams only, gravity off (no tension or load stiffness), so K is the
    beams' elastic stiffness and every element has psi = 0.3: K_psi = sum psi_e K_e =
    0.3 K, and B(w) = psi K / (2 pi w k1) for the beams (eq. 12-13), also at a beam
    frequency and k1 of their own. Tolerance 1e-14 of K's largest entry (one product)."""
    s = assemble(load("beam.yaml", BEAM))
    K = s.K.toarray()
    tol = 1e-14 * abs(K).max()
    assert np.allclose(psi_stiffness(s).toarray(), 0.3 * K, rtol=0.0, atol=tol)
    B = damping_matrix(s, 5.0).toarray()
    assert np.allclose(B, 0.3 / (2 * math.pi * 5.0) * K, rtol=0.0, atol=tol)
    B = damping_matrix(s, 5.0, k1_beams=2.0, omega_beams=8.0).toarray()
    assert np.allclose(B, 0.3 / (2 * math.pi * 8.0 * 2.0) * K, rtol=0.0, atol=tol)
    # the cantilever's tip compliance is L^3 / (3 EI) (K is right, not only proportional)
    w_tip = np.linalg.solve(K, np.asarray(s.dofs.T.T @ _tip_force(s))
                            ).ravel()
    assert math.isclose(abs(np.asarray(s.dofs.T @ w_tip)[_tip_z(s)]),
                        4.0**3 / (3 * 2.1e11 * 1e-6), rel_tol=1e-9)


def _tip_z(s):
    return s.dofs.layout.node(s.model.node_index["T"])[2]


def _tip_force(s):
    f = np.zeros(s.dofs.T.shape[0])
    f[_tip_z(s)] = 1.0
    return f


def test_element_frequency_weighting_is_one_over_w_squared():
    """element_frequencies picks, per element, the mode with the largest c (r v_j)^2 / w_j^2
    (the share of the element's strain energy; docs/damping.md). Hand-made modes at
    w = (1, 2) rad/s (the function takes V and w as given): element 1 elongates 1 and
    sqrt 6 in them, shares 1 and 6/4 -> w = 2 (a weight 1/w^3 gives 1 and 6/8 -> w = 1);
    element 2 elongates 1 and sqrt 3: shares 1 and 3/4 -> w = 1 (no weighting gives 3 -> 2);
    element 3 is not strained by either mode and gets the lowest frequency. Beams: the
    same numbers as energies v^T K_e v of two elements, K_e = diag(1, 0) and diag(0, 1)."""
    from types import SimpleNamespace as NS

    from cranefe.analysis.damping import element_frequencies
    V = np.array([[1.0, math.sqrt(6.0)], [1.0, math.sqrt(3.0)], [0.0, 0.0]])
    omega = np.array([1.0, 2.0])
    system = NS(dofs=NS(T=np.eye(3)), springs=NS(R=np.eye(3), c=np.array([5.0, 0.5, 1.0])),
                beams=NS(idx=np.array([[0, 1], [0, 1]]),
                         mat=np.array([np.diag([1.0, 0.0]), np.diag([0.0, 1.0])])))
    rows, beams = element_frequencies(system, V, omega)
    assert rows.tolist() == [2.0, 1.0, 1.0]
    assert beams.tolist() == [2.0, 1.0]
    system = NS(dofs=NS(T=np.eye(3)), springs=NS(R=np.eye(3), c=np.ones(3)), beams=None)
    rows, beams = element_frequencies(system, V, omega)
    assert rows.tolist() == [2.0, 1.0, 1.0] and beams.shape == (0,)


SPRING = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {G: [0, 0, 0], N0: [1, 0, 0]}
ground: [G]
masses: {N0: 10}
springs:
  - {name: k0, type: axial, nodes: [G, N0], stiffness: 1000, psi: 0.2}
effects: {sway: false}
"""


def test_spring_rows_use_their_k1():
    """One axial spring k = 1000 N/m, psi = 0.2, on its one free coordinate: K = [[1000]],
    K_psi = [[200]], B(w = 5, k1 = 2) = 200 / (2 pi 5 2) (eq. 13 per spring row)."""
    s = assemble(load("spring.yaml", SPRING))
    assert np.allclose(s.K.toarray(), [[1000.0]], rtol=1e-14)
    assert np.allclose(psi_stiffness(s).toarray(), [[200.0]], rtol=1e-14)
    B = damping_matrix(s, 5.0, k1=2.0).toarray()
    assert np.allclose(B, [[200.0 / (2 * math.pi * 5.0 * 2.0)]], rtol=1e-14)
