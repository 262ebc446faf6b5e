"""Kill tests for cranefe/statics.py (tools/mutation.py statics; docs/testing.md,
"Mutation testing"): the static tensions of a rope with mass and the tension stiffness
they give (`StaticState.spans` for rope elements), written out by hand.

The partial run of the statics preset showed every mutant of the rope-element branch of
`spans()` alive (`fe = set()`, `S = None`, the `isin` arguments): with sway on, ropes with
mass (`rope_mass: n`) were in no fast test, so their tension stiffness was unchecked.
"""

import numpy as np

from cranefe.model import load
from cranefe.system import assemble

G = 9.81

HANGING = """cranefe: 1
plane: xz
nodes: {S: [0, 0, 20], L: [0, 0, 0]}
ground: [S]
masses: {L: 1000}
ropes:
  r: {EA: 1.0e8, path: [S, L], mass_per_length: 50}
effects: {rope_mass: 4}
"""


def test_hanging_rope_with_mass_tensions_and_tension_stiffness_by_hand():
    """A vertical rope, L = 20 m, mu = 50 kg/m, in 4 elements (l = 5 m), m = 1000 kg at
    its end, sway on. The consistent gravity load of an element puts mu l g / 2 on each
    of its nodes, so the tension of element k (from the top, k = 1..4) is that at its
    midpoint: S_k = g (m + mu s_k), s_k = 17.5, 12.5, 7.5, 2.5 m of rope below it:
    18393.75, 15941.25, 13488.75, 11036.25 N. Each element adds EA / l along the rope and
    S_k / l across it (string stiffness, design.md), so the lateral stiffness is the
    tridiagonal matrix of S_k / l over (L, node 1, node 2, node 3) and the axial one
    EA / l = 2e7 N/m per element. Tolerance 1e-12 relative (a linear solve of a chain)."""
    m, mu, l, EA = 1000.0, 50.0, 5.0, 1.0e8
    s = assemble(load("h.yaml", HANGING))
    S = G * (m + mu * np.array([17.5, 12.5, 7.5, 2.5]))
    np.testing.assert_allclose(s.static.element_force, S, rtol=1e-12)
    np.testing.assert_allclose(s.static.rope_tension(), [[S.min(), S.max()]], rtol=1e-12)
    assert s.dofs.labels == ("node L x", "node L z") + tuple(
        f"node rope r fall 1 node {k} {c}" for k in (1, 2, 3) for c in "xz")
    # chain order from the top: node 1, 2, 3, then L; the coordinates' positions
    x = {"1": 2, "2": 4, "3": 6, "L": 0}
    Kx = np.zeros((8, 8))
    Kz = np.zeros((8, 8))
    chain = [None, "1", "2", "3", "L"]                  # None: the fixed top S
    for k in range(4):
        a, b = chain[k], chain[k + 1]
        for K, val, off in ((Kx, S[k] / l, 0), (Kz, EA / l, 1)):
            ia = None if a is None else x[a] + off
            ib = x[b] + off
            K[ib, ib] += val
            if ia is not None:
                K[ia, ia] += val
                K[ia, ib] -= val
                K[ib, ia] -= val
    np.testing.assert_allclose(s.K.toarray(), Kx + Kz, rtol=0, atol=1e-12 * EA / l)


SPRING = """cranefe: 1
plane: xz
nodes: {S: [0, 0, 4], L: [0, 0, 0]}
ground: [S]
masses: {L: 500}
"""


def test_a_load_on_an_axial_spring_or_a_truss_swings_as_a_pendulum():
    """A mass m = 500 kg hung 4 m below S on an axial spring (k = 2e5 N/m) or on a truss
    member (EA / l = 2e5 N/m, rho = 0), sway on: the static force is N = m g, and the
    element's tension stiffness N / l across it makes the load a pendulum,
    w^2 = N / (l m) = g / l = 2.4525 s^-2; along it w^2 = k / m = 400 s^-2. Tolerance
    1e-12 (a 2 x 2 diagonal problem). The `spans()` branches of axial springs and trusses
    (the spring's force, its nodes, the truss rows) were reached by no fast test."""
    from cranefe.analysis.modal import modes
    for body in ("springs:\n  - {type: axial, nodes: [S, L], stiffness: 2.0e5}\n",
                 "members:\n  bar: {type: truss, nodes: [S, L], E: 2.0e11, A: 4.0e-6, "
                 "rho: 0}\neffects: {structure: flexible}\n"):
        r = modes(load("p.yaml", SPRING + body))
        np.testing.assert_allclose(r.omega**2, [G / 4.0, 2.0e5 / 500], rtol=1e-12)
