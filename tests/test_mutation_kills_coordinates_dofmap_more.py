"""More kill tests for cranefe/coordinates/dofmap.py (tools/mutation.py coords_dofmap;
docs/testing.md, "Mutation testing"): a body welded to the ground by a fixed joint that
lists the ground SECOND (test_mutation_kills_coordinates_dofmap.py lists it first).

The union-find of `_groups` must keep the ground as the root of its group whichever side
of the joint it is on: a body fixed to the ground does not move (docs/theory.md section
1: a group fixed to the ground is the ground). Three mutants of the root choice (`... or
True`, `rb != nb or ra < rb`, `rb == nb and ra < rb`) made such a group free.
"""

import numpy as np

from cranefe.analysis.modal import modes
from cranefe.coordinates import build_dofs
from cranefe.model import GROUND, load

# d is welded to the ground (ground listed second), then e is welded to d (e listed
# first, d's root being the ground by then): both are the ground. A 40 kg load hangs
# from e's node H on a vertical axial spring of 1e5 N/m (sway off).
WELDED = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 10], K: [0, 0, 12], H: [2, 0, 12], L: [2, 0, 8]}
ground: [O]
bodies:
  d: {mass: 50, com: K, inertia: 5, nodes: [K]}
  e: {mass: 20, com: H, inertia: 2, nodes: [H]}
masses: {L: 40}
springs:
  - {type: axial, nodes: [H, L], stiffness: 1.0e5}
joints:
  - {type: fixed, bodies: [d, ground], at: O}
  - {type: fixed, bodies: [e, d], at: K}
effects: {sway: false}
"""


def test_a_body_welded_to_the_ground_listed_second_is_the_ground():
    """Both bodies are grounded: no group, no body coordinates, K and H carried by the
    ground; the only coordinate is the load's vertical one, and the load bounces on the
    spring alone: w^2 = k / m = 1e5 / 40 = 2500 (rtol 1e-12: a 1 x 1 eigenproblem)."""
    m = load("w.yaml", WELDED)
    d = build_dofs(m)
    assert d.group_of_body.tolist() == [GROUND, GROUND]
    assert d.group_q.shape[0] == 0
    idx = {n: i for i, n in enumerate(m.node_names)}
    assert [d.carrier[idx[n]] for n in ("K", "H")] == [GROUND, GROUND]
    assert d.labels == ("node L z",)
    T = d.T_map.toarray()
    for b in range(2):                          # grounded bodies do not move
        assert not T[d.layout.body(b)].any()
    np.testing.assert_allclose(modes(m).omega ** 2, [2500.0], rtol=1e-12)
