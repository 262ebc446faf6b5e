"""Kill test for cranefe/condense.py's `massless_map` (the E of `massless_motions`) as
read by the graded eigen-solution (analysis/graded.py `graded_eigen`; tools/mutation.py
condense; docs/testing.md, "Mutation testing", condense.py): a graded model (stiffness
contrast 1e7 > GRADED = 1e6) with a massless body carrying an off-centre point mass, whose
massless motion is the rotation about that point, a combination of the body's
coordinates.

The model (gravity off): a massless rigid bar A (0, 0, 0) - P (1, 0, 0), m = 10 kg at P,
springs s1 A-G1 along x and s2 A-G2 along z (k1 = k2 = 1e9 N/m), s3 P-G3 along z
(k3 = 100 N/m). The bar's rotation about P has no inertia and is condensed: it turns so
that s2 is not stretched whatever P does (A's z = 0), leaving by hand
- P along z held by s3 only: w1 = sqrt(k3 / m) = sqrt(10) rad/s, A at rest;
- P along x (the rigid bar moves A with it) held by s1: w2 = sqrt(k1 / m) = 1e4 rad/s.
Without the map (the coordinates taken as if the body rotation were the massless one)
the slow mode comes out wrong (2 sqrt(10), measured with the mutant applied).
"""

import math

import numpy as np

from cranefe.analysis.modal import modes
from cranefe.condense import condense
from cranefe.model import load
from cranefe.system import assemble

BAR = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {A: [0, 0, 0], P: [1, 0, 0], G1: [-1, 0, 0], G2: [0, 0, -1], G3: [1, 0, -1]}
ground: [G1, G2, G3]
masses: {P: 10}
bodies:
  bar: {mass: 0, nodes: [A, P]}
springs:
  - {name: s1, type: axial, nodes: [A, G1], stiffness: 1.0e9}
  - {name: s2, type: axial, nodes: [A, G2], stiffness: 1.0e9}
  - {name: s3, type: axial, nodes: [P, G3], stiffness: 1.0e2}
effects: {sway: false}
"""


def test_graded_model_with_a_massless_body_carrying_an_off_centre_mass():
    """Frequencies to 1e-12 relative (the graded path's Jacobi SVD gives each to a few eps
    relative); mass-normalised shapes to 1e-12: the bar's coordinates (ux, uz, ry about
    its centre (0.5, 0, 0), z at offset d moving by uz - d ry) with A at rest in the slow
    mode (uz = -ry / 2) and P moving 1 / sqrt(m) (|ry| = 1 / sqrt(m), L = 1 m), and a pure
    ux = 1 / sqrt(m) in the fast one."""
    model = load("bar.yaml", BAR)
    s = assemble(model)
    r = modes(model, system=s)
    assert r.graded.startswith("element factor")      # the graded eigen-solution
    np.testing.assert_allclose(r.omega, [math.sqrt(10.0), 1.0e4], rtol=1e-12)
    assert r.labels == ("body bar ux", "body bar uz", "body bar ry")
    slow, fast = r.shapes[:, 0], r.shapes[:, 1]
    a = 1 / math.sqrt(10.0)
    assert abs(slow[0]) < 1e-12 and abs(abs(slow[2]) - a) < 1e-12
    assert abs(slow[1] + slow[2] / 2) < 1e-12         # A at rest
    assert abs(abs(fast[0]) - a) < 1e-12 and np.abs(fast[1:]).max() < 1e-12
    c = condense(s)
    assert c.massless_map is not None                 # the general (null-space) path
    assert c.massless == ("body bar ry",)
