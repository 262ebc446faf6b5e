"""The tables quoted in docs/accuracy.md agree with the CSVs in results/ that their study
commands write (issue 20: every figure in docs/ is what the current code measures).

A quoted number agrees when it is the CSV value rounded to the digits quoted: their
difference is at most half a unit of the last quoted digit (plus 1e-12 relative for the
binary representation). Regenerating a CSV without updating the page fails here."""

import csv
import os
import re

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOC = os.path.join(ROOT, "docs", "accuracy.md")


def results(name):
    with open(os.path.join(ROOT, "results", name)) as fh:
        return list(csv.DictReader(fh))


def table(heading):
    """Rows (lists of cell texts) of the first markdown table after `heading`."""
    text = open(DOC).read()
    start = text.index(heading)
    lines = text[start:].splitlines()
    rows, seen = [], False
    for line in lines[1:]:
        if line.startswith("|"):
            seen = True
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if not set("".join(cells)) <= set("-: "):
                rows.append(cells)
        elif seen:
            break
    return rows[1:]                                   # without the header


def agrees(quoted, value):
    """`quoted` (e.g. '4.7e-5', '-1.2e-3', '0.24 s', '2 933') is `value` rounded."""
    text = quoted.replace(" s", "").replace(" ", "").replace("%", "")
    mant, _, exp = text.lower().partition("e")
    decimals = len(mant.split(".")[1]) if "." in mant else 0
    unit = 10.0 ** (-decimals + (int(exp) if exp else 0))
    return abs(float(text) - value) <= 0.5 * unit + 1e-12 * abs(value)


def test_rope_table_is_the_csv():
    rows = results("rope_convergence.csv")
    err = {(r["case"], r["mass"], int(r["N"])): float(r["error_mode1"]) for r in rows}
    quoted = table("## Rope elements per fall")
    assert [int(r[0]) for r in quoted] == [4, 8, 16, 32]
    for N, heavy, chain, span in quoted:
        for case, cell in (("heavy_rope_end_mass", heavy), ("hanging_chain", chain),
                           ("tensioned_span", span)):
            consistent, lumped = (c.strip() for c in cell.split("/"))
            assert agrees(consistent, err[case, "consistent", int(N)]), (case, N, cell)
            assert agrees(lumped, err[case, "lumped", int(N)]), (case, N, cell)


def test_eigensolver_table_is_the_csv():
    rows = {int(r["dofs"]): r for r in results("eigensolvers.csv")}
    quoted = table("## Dense and sparse eigensolvers")
    assert quoted
    for size, dense, sparse in quoted:
        r = rows[int(size.replace(" ", ""))]
        for cell, kind in ((dense, "dense"), (sparse, "sparse")):
            if cell == "-":
                assert r[f"{kind}_error"] == "nan"
                continue
            error, seconds = (c.strip() for c in cell.split(","))
            assert agrees(error, float(r[f"{kind}_error"])), (size, kind, cell)
            assert agrees(seconds, float(r[f"{kind}_s"])), (size, kind, cell)


def test_damping_table_is_the_csv():
    rows = results("damping_cost.csv")
    quoted = table("## Damping: decoupled estimate against exact")
    assert quoted
    for case, dofs, coupling, viscous, hysteretic, whole, step in quoted:
        r = next(x for x in rows if x["case"] == case.replace(" ", "_")
                 and x["dofs"] == dofs.replace(" ", ""))
        for cell, key in ((coupling, "max_coupling"), (viscous, "max_error_viscous"),
                          (hysteretic, "max_error_hysteretic"),
                          (whole, "ratio_exact_modal"), (step, "ratio_damping_step")):
            assert agrees(cell, float(r[key])), (case, dofs, key, cell)


@pytest.mark.parametrize("quoted, value, ok", [
    ("4.7e-5", 4.69083e-05, True), ("4.8e-5", 4.69083e-05, False),
    ("0.24 s", 0.250159, False), ("0.25 s", 0.250159, True), ("2 933", 2933.0, True),
    ("-1.2e-3", -0.00115157, True), ("12", 12.4, True), ("12", 12.6, False)])
def test_agrees_reads_the_quoted_digits(quoted, value, ok):
    assert agrees(quoted, value) is ok


def quoted_after(phrase):
    """The number right after `phrase` in docs/accuracy.md (e.g. 'within ' -> '3.0e-4')."""
    text = " ".join(open(DOC).read().split())
    m = re.search(re.escape(phrase) + r"\s*\(?(-?[0-9][0-9.]*(?:e-?[0-9]+)?)", text)
    assert m, phrase
    return m.group(1)


def test_prose_figures_are_the_csvs():
    # rope orders: "Fitted order 2.00 in every case" (first mode)
    orders = [float(r["order_mode1"]) for r in results("rope_convergence_orders.csv")]
    assert all(agrees(quoted_after("Fitted order"), o) for o in orders)
    # transients: the direct runs' largest error up to 2e-2 s, the fine steps' errors,
    # modal superposition with 2 modes and from 8 modes (static correction)
    rows = [r for r in results("transient_cost.csv") if r["case"] == "hoist_start"]
    direct = {float(r["time_step_s"]): float(r["error"]) for r in rows
              if r["method"] == "direct"}
    assert agrees(quoted_after("fall) is within"), max(e for h, e in direct.items() if h <= 0.02))
    assert agrees(quoted_after("2e-2 s (not monotonically: where the peak falls between "
                               "steps matters), and within"),
                  max(e for h, e in direct.items() if h <= 2e-4))
    modal = {int(r["modes"]): float(r["error"]) for r in rows
             if r["method"] == "modal" and r["static_correction"] == "true"}
    assert agrees(quoted_after("the rigid mode and the hoisting mode"), modal[2])
    fine = float(quoted_after("reaches the fine step's error"))
    assert all(agrees(str(fine), e) for k, e in modal.items() if k >= 8)
    # luffing: quadrature m = 16 and Chebyshev collocation n = 10
    luff = {r["method"]: r for r in results("luffing_cost.csv")}
    assert agrees(quoted_after("quadrature ("), float(luff["quadrature m=16"]["error_rad"]))
    assert agrees(quoted_after("Chebyshev collocation n = 10 gives"),
                  float(luff["collocation, Chebyshev n=10"]["error_rad"]))


def test_validation_page_is_the_csv():
    """docs/validation.md and results/validation.csv come from one run of `cranefe study
    validation`: the same rows, peers that were missing included."""
    rows = results("validation.csv")
    md = [line for line in open(os.path.join(ROOT, "docs", "validation.md"))
          if line.startswith("| ") and not line.startswith("| case |")]
    assert [[c.strip() for c in line.strip().strip("|").split("|")] for line in md] == \
        [[r["case"], r["kind"], r["reference"], r["max_relative_error"]] for r in rows]
    assert any("vs OpenSeesPy" in r["case"] for r in rows)         # present or missing
    assert any("vs Exudyn" in r["case"] for r in rows)


def test_operation_tables_are_the_csvs():
    """docs/operations.md ("Accuracy and cost", "Comparison with Exudyn") and the
    operation engine's table in docs/accuracy.md are what `cranefe study operations`
    renders from results/operation_cost.csv, operation_cost_orders.csv and
    operation_peers.csv (it rewrites the blocks between its markers); every bundled
    operation scene is in them, and Exudyn's rows, present or missing."""
    from cranefe.studies import operations as op
    cost, orders = results("operation_cost.csv"), results("operation_cost_orders.csv")
    peers = results("operation_peers.csv")
    page = open(os.path.join(ROOT, "docs", "operations.md")).read()
    assert op.block(page, "cost") == op.cost_markdown(cost, orders).strip("\n")
    assert op.block(page, "peers") == op.peers_markdown(peers).strip("\n")
    assert op.block(open(DOC).read(), "engine") == op.accuracy_markdown(cost).strip("\n")
    assert {r["scene"] for r in cost} == {r["scene"] for r in peers} == set(op.SCENES)
    assert {r["scene"] for r in peers if r["program"].startswith("Exudyn")} == set(op.SCENES)
    assert {r["scene"] for r in cost if r["method"] == "scipy Radau"}     # the cross-check
