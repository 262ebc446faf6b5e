"""The validation study's peer comparisons (cranefe/studies/validation.py): the spatial
spreader with sway on against Exudyn, and missing peers kept in the table."""

import csv

import numpy as np
import pytest

from cranefe.model import load
from cranefe.analysis.modal import modes
from cranefe.statics import solve_static
from cranefe.studies import validation


def test_spatial_spreader_with_sway_against_exudyn():
    """A rigid spreader (full inertia tensor) on six inclined ropes with a hook load
    below an off-centre point, sway on: every one of the 9 frequencies involves the
    ropes' tension stiffness (S/l)(I - e e^T) and the body's load stiffness H (the rope
    pulls at offsets from the centre of mass, docs/theory.md section 5). Exudyn builds
    the same system from the file with its own kinematics (Tait-Bryan rotations, spring
    connectors pre-tensioned to the same static state) and linearises it itself.

    Tolerance 1e-10: both solve the same 9 x 9 linear eigenproblem in double precision
    (frequencies 1.4 to 57 rad/s; measured agreement 4e-15); the tensions come from the
    determinate equilibrium in both (measured 1e-15)."""
    pytest.importorskip("exudyn")
    text = validation.spreader_text()
    model = load("spreader.yaml", text)
    r = modes(model)
    w, S = validation.exudyn_omega(text)
    assert r.dofs == 9 and len(w) == 9
    np.testing.assert_allclose(r.omega, w, rtol=1e-10)
    # the two pendulum modes of the hook: sqrt(g / 5 m) = 1.4007 rad/s, lowered by
    # 0.2 % and split by the spreader's own small sway (1.3976, 1.3981)
    np.testing.assert_allclose(r.omega[:2], np.sqrt(9.81 / 5.0), rtol=3e-3)
    st = solve_static(model)
    cranefe_S = {model.ropes[k].name: st.rope_tension()[k, 1] for k in range(len(model.ropes))}
    assert cranefe_S == pytest.approx(S, rel=1e-10)
    assert min(S.values()) > 4000                        # every rope taut


def test_missing_peers_keep_their_rows(tmp_path, monkeypatch):
    """Without OpenSeesPy and Exudyn the table shows both comparisons as missing (once
    the OpenSeesPy row was silently dropped while docs/validation.md still showed it)."""
    for name in ("hoist_cases", "pendulum_cases", "chain_cases", "rope_cases",
                 "structure_cases"):
        monkeypatch.setattr(validation, name, lambda: iter(()))
    monkeypatch.setattr(validation, "_version", lambda dist: None)
    (tmp_path / "results").mkdir()
    (tmp_path / "docs").mkdir()
    validation.run(str(tmp_path / "results"), quick=True)
    with open(tmp_path / "results" / "validation.csv") as fh:
        rows = {r["case"]: r["max_relative_error"] for r in csv.DictReader(fh)}
    floor = rows.pop("lattice tower crane, 3000 DOFs, vs independent numpy assembly")
    assert floor == "< 1e-11" or float(floor) < 1e-10     # always there: numpy only
    assert rows == {
        "lattice tower crane, 3000 DOFs, vs OpenSeesPy": "missing (OpenSeesPy not installed)",
        "spreader on six ropes with a hook load, spatial, sway on (9 DOFs), vs Exudyn":
            "missing (Exudyn not installed)"}
    md = (tmp_path / "docs" / "validation.md").read_text()
    assert "| lattice tower crane, 3000 DOFs, vs OpenSeesPy | peer program | 10 frequencies " \
           "| missing (OpenSeesPy not installed) |" in md
    assert "vs Exudyn | peer program" in md and "missing (Exudyn not installed)" in md
