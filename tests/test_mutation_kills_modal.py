"""Value tests that kill mutants of cranefe/analysis/damping/modal.py that
tests/test_values.py and tests/test_damping.py left alive (tools/mutation.py
damping_modal; docs/testing.md, "Mutation testing"): no beam carried an absorption, and
the per-element shares of H_ii were never checked by value.
"""

import math

import numpy as np

from cranefe.analysis.damping.modal import modal_damping
from cranefe.analysis.modal import modes
from cranefe.model import load
from cranefe.system import assemble

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

PAIR = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {G: [0, 0, 0], N0: [1, 0, 0], G2: [2, 0, 0]}
ground: [G, G2]
masses: {N0: 10}
springs:
  - {name: a, type: axial, nodes: [G, N0], stiffness: 1000, psi: 0.2}
  - {name: b, type: axial, nodes: [N0, G2], stiffness: 3000, psi: 0.1}
effects: {sway: false}
"""


def test_uniform_beam_absorption_gives_psi_over_4_pi_in_every_mode():
    """Every element with the same psi: K_psi = psi K, so H = psi V^T K V / (2 pi) =
    psi diag(w^2) / (2 pi) for mass-normalised modes: zeta_i = H_ii / (2 w_i^2) =
    psi / (4 pi) = 0.3 / (4 pi) in every mode, no coupling, the whole share in the
    member. Tolerance 1e-9: off-diagonal round-off of V^T K V relative to w_max^2."""
    model = load("beam.yaml", BEAM)
    s = assemble(model)
    md = modal_damping(s, modes(model, system=s))
    assert len(md.zeta) >= 2
    assert np.allclose(md.zeta, 0.3 / (4 * math.pi), rtol=1e-9)
    assert np.all(md.coupling < 1e-9)
    assert md.element_names == ("member arm",)
    assert np.allclose(md.shares, 1.0, rtol=1e-12)


def test_shares_of_two_springs_on_one_mass():
    """One mass m = 10 kg between springs k_a = 1000 (psi 0.2) and k_b = 3000 (psi 0.1):
    w^2 = 4000 / m, both springs stretch by the mode's amplitude, so the share of each in
    H_ii is c psi / sum c psi = 200 / 500 and 300 / 500, and zeta = (500 / (2 pi m)) /
    (2 w^2) = 1 / (32 pi)."""
    model = load("pair.yaml", PAIR)
    s = assemble(model)
    md = modal_damping(s, modes(model, system=s))
    assert np.allclose(md.omega, [math.sqrt(400.0)], rtol=1e-12)
    assert np.allclose(md.zeta, [1.0 / (32.0 * math.pi)], rtol=1e-12)
    assert md.element_names == ("spring a", "spring b")
    assert np.allclose(md.shares, [[0.4, 0.6]], rtol=1e-12)
