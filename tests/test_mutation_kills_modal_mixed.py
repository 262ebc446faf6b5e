"""Kill test for cranefe/analysis/damping/modal.py (`_modal_absorption`'s `names +=`:
docs/testing.md, "Mutation testing", damping_modal) on a model with both an absorbing
spring and an absorbing beam, which no other fast test has: the element names must be
the springs' followed by the members', matching the rows of the per-element parts.
"""

import math

import numpy as np

from cranefe.analysis.damping.modal import modal_damping
from cranefe.analysis.modal import modes
from cranefe.model import load
from cranefe.system import assemble

EA_L = 2.1e11 * 1.0e-3 / 4          # the arm's axial stiffness E A / L, N/m

MIXED = f"""cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {{O: [0, 0, 0], T: [4, 0, 0], G: [5, 0, 0]}}
ground: [O, G]
masses: {{T: 100.0}}
members:
  arm: {{type: beam, nodes: [O, T], E: 2.1e11, A: 1.0e-3, Iy: 1.0e-6, rho: 0,
        elements: 2, psi: 0.3}}
springs:
  - {{name: s, type: axial, nodes: [T, G], stiffness: {EA_L!r}, psi: 0.1}}
effects: {{structure: flexible}}
"""


def test_shares_of_a_spring_and_a_beam_in_parallel():
    """A cantilever arm O-T along x (massless, tip mass m = 100 kg) and an axial spring
    T-G along x of the same stiffness k = E A / L = 5.25e7 N/m. The straight arm's
    axial and bending motions are uncoupled (linear, planar), the spring along x does not
    stretch in the bending mode (first order).
    - axial mode: w^2 = 2 k / m, both elements stretched by the tip's amplitude, so their
      shares of H_ii are psi c / sum psi c = 0.3 k / 0.4 k = 3/4 (arm) and 1/4 (spring),
      zeta = (0.4 k / (2 pi m)) / (2 w^2) = 0.4 / (8 pi);
    - bending mode: w^2 = 3 E I / (L^3 m) (the tip of a massless cantilever), only the
      arm deformed: share 1 and zeta = psi / (4 pi) = 0.3 / (4 pi).
    Tolerance 1e-9: round-off of V^T K V relative to the largest w^2 (the axial one,
    2.6e4 times the bending one)."""
    model = load("mixed.yaml", MIXED)
    s = assemble(model)
    md = modal_damping(s, modes(model, system=s))
    w_bend = math.sqrt(3 * 2.1e11 * 1.0e-6 / (4**3 * 100.0))
    w_axial = math.sqrt(2 * EA_L / 100.0)
    assert np.allclose(md.omega, [w_bend, w_axial], rtol=1e-9)
    assert md.element_names == ("member arm", "spring s")
    assert np.allclose(md.zeta, [0.3 / (4 * math.pi), 0.4 / (8 * math.pi)], rtol=1e-9)
    assert np.allclose(md.shares, [[1.0, 0.0], [0.75, 0.25]], rtol=1e-9, atol=1e-9)
