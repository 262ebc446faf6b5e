"""Kill test for cranefe/condense.py (tools/mutation.py condense; docs/testing.md,
"Mutation testing"): `recover[b] = None` (the massless coordinates' part of every mode
shape made NaN) passed the preset's fast tests."""

import math

import numpy as np
import pytest

from cranefe.analysis.modal import modes
from cranefe.model import load
from cranefe.system import assemble

SERIES = """cranefe: 1
name: massless block in series
plane: xz
nodes: {S: [0, 0, 20], D: [0, 0, 12], B: [0, 0, 5]}
ground: [S]
masses: {B: 2000}
ropes:
  r1: {EA: 1.0e7, path: [S, {node: D, falls: 2}]}
  r2: {EA: 2.0e7, path: [D, {node: B, falls: 3}]}
effects: {sway: false}
"""


@pytest.mark.parametrize("m", [2000.0, 0.5])
def test_massless_block_moves_by_static_condensation(m):
    """Block D is massless between r1 (2 falls, L = 16 m: k1 = 2^2 EA1 / 16 = 2.5e6 N/m)
    and r2 (3 falls, L = 21 m: k2 = 3^2 EA2 / 21). Its equation k1 y = k2 (x - y) gives
    y = k2 / (k1 + k2) x; the mode is w^2 = k1 k2 / (k1 + k2) / m with x = 1/sqrt(m)
    (mass-normalised). Tolerance 1e-12: a 2 x 2 solve. A mass below 1 kg is a mass
    (`massless_split` with `d > 1` for `d > 0` survived the fast tests)."""
    model = load("series.yaml", SERIES.replace("B: 2000", f"B: {m}"))
    s = assemble(model)
    md = modes(model, system=s)
    k1, k2 = 4 * 1.0e7 / 16, 9 * 2.0e7 / 21
    assert s.dofs.labels == ("node D z", "node B z")
    assert np.allclose(md.omega, [math.sqrt(k1 * k2 / (k1 + k2) / m)], rtol=1e-12)
    x, y = md.shapes[1, 0], md.shapes[0, 0]
    assert math.isclose(abs(x), 1 / math.sqrt(m), rel_tol=1e-12)
    assert math.isclose(y / x, k2 / (k1 + k2), rel_tol=1e-12)


ROTATION = """cranefe: 1
plane: xz
nodes: {S: [0, 0, 10], A: [0, 0, 4], B: [2, 0, 4]}
ground: [S]
bodies:
  beam: {mass: 300, com: A, inertia: 0, nodes: [A, B]}
ropes:
  r: {EA: 1.0e6, path: [S, A]}
"""


def test_massless_mechanism_error_names_file_entry_and_coordinate():
    """Bad input names file + entry + fix (common contract): one rope at the centre of
    mass of a body without rotary inertia leaves its rotation with neither stiffness nor
    inertia. The message's file, entry and text were mutated freely in the condense run
    (`model.file` -> None, `entry_of(...)` dropped, the text altered) without a failure."""
    from cranefe.errors import ModelError
    with pytest.raises(ModelError) as err:
        modes(load("u.yaml", ROTATION))
    e = err.value
    assert (e.file, e.entry) == ("u.yaml", "bodies.beam")
    assert e.message == (
        "massless and unrestrained: body beam ry can move with no stiffness and no "
        "inertia; attach a rope or spring in that direction, give it mass, or add it to "
        "ground")


def test_nothing_with_inertia_names_the_file():
    from cranefe.condense import condense
    from cranefe.errors import ModelError
    text = SERIES.replace("masses: {B: 2000}\n", "")
    with pytest.raises(ModelError) as err:
        condense(assemble(load("n.yaml", text)))
    assert err.value.file == "n.yaml"
    assert err.value.message == ("nothing that moves has inertia, so there is nothing to "
                                 "vibrate; give a node a mass (masses:) or a body a mass")
