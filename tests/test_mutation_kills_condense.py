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
