"""Numerical findings of the outside audit (issue 15): zero-frequency mechanisms are
rigid modes, light members under heavy loads are in equilibrium, bodies may have zero
rotary inertia, and a mode count must be at least one."""

import warnings
from dataclasses import replace

import numpy as np
import pytest

from cranefe.analysis.damping import damping
from cranefe.analysis.modal import modes
from cranefe.errors import ModelError
from cranefe.model import load


# --- a mechanism that is not a free drum is a rigid mode --------------------------------

def test_inextensible_hoist_mechanism_is_rigid():
    # with inextensible ropes the luffing crane's hoist (drum + hook along the rope) is a
    # mechanism: K sees it only through round-off of the constraint map (w^2 ~ 4e-33),
    # so the pattern's null space misses it. It must be rigid: no NaN damping rows, no
    # numpy warnings (before: zeta NaN, log decrement inf, RuntimeWarnings)
    m = load("models/luffing_tower_crane.yaml")
    m = replace(m, effects=replace(m.effects, rope_elasticity=False))
    r = modes(m)
    assert r.rigid[0] and not r.rigid[1:].any() and r.omega[0] == 0
    assert "drum hoist" in r.quasi_cyclic
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        d = damping(m)
    assert d.rigid[0] and np.all(np.isfinite(d.zeta)) and np.all(d.zeta[1:] > 0)
    assert not any("no element has" in w for w in d.warnings)


def test_rigid_detection_keeps_soft_modes_of_graded_chains():
    # the other way round: a 1e-3 N/m spring beside a 1e12 one is soft, not free
    from test_graded import chain
    r = modes(load("c.yaml", chain([1.1e12, 1e-3, 1.3e12], [1.0, 3.0, 2.0])))
    assert not r.rigid.any() and r.omega.min() > 0


# --- count ------------------------------------------------------------------------------

@pytest.mark.parametrize("count", [0, -1, 1.5])
def test_modes_count_below_one_refused(count):
    with pytest.raises(ModelError, match="count"):
        modes(load("models/two_mass_hoist.yaml"), count=count)


def test_modes_count_one():
    assert len(modes(load("models/two_mass_hoist.yaml"), count=1).omega) == 1


# --- equilibrium relative to the forces a node carries ----------------------------------

LIGHT = """cranefe: 1
plane: xz
nodes: {{O: [0, 0, 0], A: [0.3, 0, 4], B: [0.1, 0, 8], C: [3, 0, 10], T: [6, 0, 12]}}
ground: [O]
masses: {{T: 20000}}
members:
  mast: {{type: {kind}, nodes: [O, A, B, C, T], E: 2.1e11, G: 8.1e10, A: 1.0e-2,
         Iy: 2.0e-4, Iz: 2.0e-4, J: 4.0e-4, rho: 1.0, orientation: [0, 1, 0]}}
{extra}effects: {{structure: flexible}}
"""


def test_light_beam_under_heavy_load_is_in_equilibrium():
    # a bent column of density 1 kg/m^3 carrying 2e5 N: its nodes weigh ~0.2 N but
    # carry 2e5 N, and balance to ~1e-7 N of round-off (before: refused as "not in
    # static equilibrium ... its ropes and springs")
    r = modes(load("light.yaml", LIGHT.format(kind="beam", extra="")))
    assert r.omega.min() > 0


def test_light_truss_under_heavy_load_is_in_equilibrium():
    # a triangulated planar truss of density 1 kg/m^3 carrying 2e5 N at T (truss forces
    # were already in the scale; a guard beside the beam case)
    text = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 0], P: [4, 0, 0.2], A: [1, 0, 3.1], T: [5.3, 0, 2.9]}
ground: [O, P]
masses: {T: 20000}
members:
  chord: {type: truss, nodes: [O, A, T], E: 2.1e11, A: 1.0e-2, rho: 1.0}
  web: {type: truss, nodes: [A, P, T], E: 2.1e11, A: 1.0e-2, rho: 1.0}
effects: {structure: flexible}
"""
    r = modes(load("truss.yaml", text))
    assert r.omega.min() > 0


def test_unbalanced_member_node_message_names_members_not_ropes():
    # a load on one inclined truss: the truss cannot balance its weight sideways
    text = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 0], H: [3, 0, 4]}
ground: [O]
masses: {H: 100}
members:
  bar: {type: truss, nodes: [O, H], E: 2.1e11, A: 1.0e-3, rho: 7850}
effects: {structure: flexible}
"""
    with pytest.raises(ModelError, match="its members cannot balance") as e:
        modes(load("bar.yaml", text))
    assert "ropes" not in str(e.value) and e.value.entry == "nodes.H"


# --- zero rotary inertia: massless rotations condensed ----------------------------------

G = 9.81

PENDULUM = """cranefe: 1
plane: xz
nodes: {{P: [0, 0, 10], Q: [0, 0, 4]}}
ground: [P]
{masses}bodies:
  link: {body}
joints:
  - {{type: hinge, bodies: [ground, link], at: P, axis: [0, 1, 0]}}
"""


@pytest.mark.parametrize("masses, body", [
    ("masses: {Q: 300}\n", "{mass: 0, inertia: 0, nodes: [P, Q]}"),     # massless link
    ("", "{mass: 300, com: Q, inertia: 0, nodes: [P, Q]}"),            # point-like body
])
def test_point_mass_on_a_rigid_link_is_a_pendulum(masses, body):
    # w = sqrt(g / l), l = 6 m: the rotary inertia about the hinge is m l^2 exactly
    r = modes(load("p.yaml", PENDULUM.format(masses=masses, body=body)))
    np.testing.assert_allclose(r.omega, [np.sqrt(G / 6.0)], rtol=1e-12)


TWO_ROPES = """cranefe: 1
plane: xz
nodes: {{S1: [-1, 0, 10], S2: [2, 0, 10], A: [-1, 0, 4], B: [2, 0, 4]}}
ground: [S1, S2]
{masses}bodies:
  link: {body}
ropes:
  r1: {{EA: 1.0e6, path: [S1, A]}}
  r2: {{EA: 2.0e6, path: [S2, B]}}
effects: {{sway: false}}
"""


def test_massless_link_carrying_a_point_mass_off_its_centre():
    # the link's massless motion is a rotation about B (where the mass is), a combination
    # of its coordinates at the centre: condensed, the mass hangs on rope r2 alone,
    # w^2 = k2 / m; the horizontal motion is free (sway off). Before: a spurious
    # 5.8e8 Hz mode from the singular inertia.
    r = modes(load("t.yaml", TWO_ROPES.format(masses="masses: {B: 300}\n",
                                              body="{mass: 0, inertia: 0, nodes: [A, B]}")))
    assert r.rigid.tolist() == [True, False] and len(r.massless) == 1
    np.testing.assert_allclose(r.omega[1], np.sqrt(2.0e6 / 6.0 / 300), rtol=1e-12)


def test_body_without_rotary_inertia_between_two_ropes():
    # a body of mass m at the middle of A-B with inertia 0: its rotation is massless and
    # adjusts statically, so the ropes act as 4 k1 k2 / (k1 + k2) on its vertical motion
    text = TWO_ROPES.format(masses="", body="{mass: 300, com: [0.5, 0, 4], inertia: 0, "
                            "nodes: [A, B]}")
    r = modes(load("t.yaml", text))
    k1, k2 = 1.0e6 / 6, 2.0e6 / 6
    np.testing.assert_allclose(r.omega[~r.rigid], [np.sqrt(4 * k1 * k2 / (k1 + k2) / 300)],
                               rtol=1e-12)


def test_unrestrained_massless_rotation_is_a_model_error():
    # one rope at the centre of mass: nothing resists the rotation, nothing has inertia
    text = """cranefe: 1
plane: xz
nodes: {S: [0, 0, 10], A: [0, 0, 4], B: [2, 0, 4]}
ground: [S]
bodies:
  beam: {mass: 300, com: A, inertia: 0, nodes: [A, B]}
ropes:
  r: {EA: 1.0e6, path: [S, A]}
"""
    with pytest.raises(ModelError, match="massless and unrestrained"):
        modes(load("u.yaml", text))


def test_inextensible_ropes_with_psi_are_named_not_missing():
    # the hoist rope has psi 0.2 but is a constraint here: the warning says so rather
    # than "no element has psi" (the audit's false warning)
    m = load("models/two_mass_hoist.yaml")
    d = damping(replace(m, effects=replace(m.effects, rope_elasticity=False)))
    assert any("rope hoist_rope: psi > 0 but inextensible" in w for w in d.warnings)
    assert not any("no element has" in w for w in d.warnings)
