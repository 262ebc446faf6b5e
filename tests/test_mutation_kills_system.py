"""Kill tests for cranefe/system.py (tools/mutation.py system; docs/testing.md, "Mutation
testing"): the tension stiffness of a beam with a released end, and the effects and
reuse that `assemble` passes on.

Before these tests, `geometric_stiffness` could drop the end releases of beams under
axial force (the geometric stiffness then acts on the node's rotation instead of the
element's condensed one), and `assemble` could drop the effects it was given (using the
model's own) or the reuse store, with every fast test passing.
"""

import dataclasses

import numpy as np
import pytest

from cranefe.analysis.modal import modes
from cranefe.assembly.reuse import Reuse
from cranefe.model import load
from cranefe.system import assemble

G = 9.81

COLUMN = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 0], T: [0, 0, 10], S: [5, 0, 10]}
ground: [O, S]
masses: {T: 1000}
members:
  col: {type: beam, nodes: [O, T], E: 2.1e11, A: 1.0e-2, Iy: 2.0e-4, rho: 0,
        releases: {O: [ry]}}
springs:
  - {type: axial, nodes: [T, S], stiffness: 5.0e4}
effects: {structure: flexible, sway: true}
"""


def test_pinned_column_under_its_load_is_an_inverted_pendulum_on_a_spring():
    """A massless column pinned at its base O (the element's rotation released there),
    carrying m = 1000 kg at its top T, held sideways by a horizontal spring k = 5e4 N/m.
    Pinned at the base and free of moment at the top, the column turns rigidly under a
    side force (no bending), so the side stiffness is the spring's and the P-delta of the
    compression N = -m g over the rigid rotation: int N v'^2 = N delta^2 / L, i.e.
    w^2 = (k - m g / L) / m = 49.019 s^-2; axially w^2 = EA / (L m) = 2.1e5 s^-2. The
    cubic shape functions hold the linear field exactly: tolerance 1e-12. Without the
    release transform on the geometric stiffness, it would act on the ground's fixed
    rotation instead: w^2 = (k + 0.2 N / L ... ) / m, off by 0.2 % of k here."""
    k, m, L = 5.0e4, 1000.0, 10.0
    r = modes(load("c.yaml", COLUMN))
    np.testing.assert_allclose(r.omega**2, [(k - m * G / L) / m, 2.1e11 * 1.0e-2 / L / m],
                               rtol=1e-12)


TAGLINE = """cranefe: 1
plane: xz
nodes: {A: [-6, 0, 8], L: [0, 0, 0], B: [4, 0, -3]}
ground: [A, B]
masses: {L: 1000}
ropes:
  hoist: {EA: 1.0e7, psi: 0.2, path: [A, L], mass_per_length: 20}
  tag: {EA: 1.0e5, psi: 0.4, path: [L, B], mass_per_length: 5}
"""


PENDULUM = """cranefe: 1
plane: xz
nodes: {A: [0, 0, 8], L: [0, 0, 0], B: [3, 0, 0]}
ground: [A, B]
masses: {L: 1000}
ropes:
  hoist: {EA: 1.0e7, path: [A, L]}
springs:
  - {type: axial, nodes: [L, B], stiffness: 2.0e3}
"""


@pytest.mark.parametrize("base, changes", [
    (TAGLINE, {"rope_mass": 2, "rope_mass_matrix": "lumped"}),
    (TAGLINE, {"rope_mass": 3, "sway": False}),
    (PENDULUM, {"rope_elasticity": False}),
])
def test_assemble_uses_the_effects_it_is_given(base, changes):
    """assemble(model, effects) equals assembling the model whose own effects are those
    (the scene and the CLI pass effects that differ from the model file's): K, M and f
    to 1e-12 relative; and the same through a Reuse store (twice: a miss and a hit)."""
    model = load("t.yaml", base)
    eff = dataclasses.replace(model.effects, **changes)
    text = base + "effects: {" + ", ".join(
        f"{k}: {str(v).lower() if isinstance(v, bool) else v}" for k, v in changes.items()) + "}\n"
    own = assemble(load("t.yaml", text))
    assert own.effects == eff
    reuse = Reuse()
    for s in (assemble(model, eff), assemble(model, eff, reuse), assemble(model, eff, reuse)):
        assert s.dofs.labels == own.dofs.labels
        for a, b in ((s.K, own.K), (s.M, own.M)):
            np.testing.assert_allclose(a.toarray(), b.toarray(), rtol=0,
                                       atol=1e-12 * abs(b).max())
        np.testing.assert_allclose(s.f, own.f, rtol=0, atol=1e-12 * np.abs(own.f).max())
        assert (s.static is None) == (not eff.sway)
    assert reuse.hits["dofs"] >= 1
