"""Every study runs (quick sizes) and writes the files it names."""

import csv
import os

import pytest

from cranefe.cli import main
from cranefe.studies import NAMES

SLOW = {"rendering", "performance"}     # whole processes and renders: run by hand


@pytest.mark.parametrize("name", sorted(set(NAMES) - SLOW - {"accuracy"}))
def test_study_quick(name, tmp_path, capsys):
    assert main(["study", name, "--quick", "--out", str(tmp_path)]) == 0
    written = capsys.readouterr().out.split()
    assert written and all(os.path.getsize(p) > 0 for p in written)
    for p in written:
        if p.endswith(".csv"):
            with open(p) as fh:
                assert len(list(csv.DictReader(fh))) >= 1


def test_accuracy_runs_every_accuracy_study(tmp_path, capsys):
    from cranefe.studies.accuracy import ACCURACY
    (tmp_path / "results").mkdir()
    (tmp_path / "docs").mkdir()
    assert main(["study", "accuracy", "--quick", "--out", str(tmp_path / "results")]) == 0
    out = capsys.readouterr().out
    assert "validation.csv" in out and (tmp_path / "docs" / "validation.md").exists()
    # each accuracy study present wrote its table
    tables = {"ropes": "rope_convergence.csv", "drive": "drive_reduction.csv",
              "eigensolvers": "eigensolvers.csv"}
    for name in ACCURACY:
        if name in tables:
            assert (tmp_path / "results" / tables[name]).exists()
