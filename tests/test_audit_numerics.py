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
