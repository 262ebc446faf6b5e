"""Fast value tests that kill mutants of cranefe/analysis/modal.py left by
tests/test_mutation_kills_modal_paths.py and _modal_graded.py (tools/mutation.py modal;
docs/testing.md, "Mutation testing"): the choices `modes` makes and reports (the
solver at the SMALL boundary, the sparse default of 10 modes, the count against the
moving coordinates, the shift and the rigid threshold of the sparse path scaled by the
model, not by 1 kg or 1 N/m), the drive-reduction comparison of a model that asks for
`drive: reduced` itself, the warnings fed by the static tension and the frequencies,
the messages of the errors, and the label of a neutral mode that is not coordinate 0.
Every value from a closed form (uniform chains, the two-mass hoist) or by hand.
"""

import math
import time

import pytest

from cranefe.analysis.modal import drive_reduction, modes
from cranefe.errors import AnalysisError, ModelError
from cranefe.model import load
from test_mutation_kills_modal_paths import (G, RTOL, SPARSE, _two_bars, chain,
                                             chain_reference, fixed_free, hoist)


def test_sparse_rigid_threshold_and_shift_scale_with_a_heavy_soft_chain():
    # 5 masses of 1e6 kg on springs of 1e-3 N/m: every K_ii / M_ii is 1e-9 or 2e-9 s^-2
    # and w_1^2 = 8e-11 s^-2. The shift (-1e-3 of the smallest K_ii / M_ii) and the rigid
    # threshold (|w^2| < 1e-10 of it) scale with the model; one in absolute units
    # (1e-10 s^-2) or by K_ii M_ii (1e-7) would call the elastic modes rigid.
    # Closed form of the fixed-free chain; SPARSE: ARPACK shift-invert, round-off.
    k, m = 1.0e-3, 1.0e6
    r = modes(chain((k,) * 5, (m,) * 5), solver="sparse", count=3)
    assert r.solver == "sparse" and r.rigid.tolist() == [False] * 3
    assert r.omega == pytest.approx(fixed_free(5, k, m)[:3], rel=SPARSE)


@pytest.mark.parametrize("n", [11, 12])
def test_sparse_default_count_is_ten_and_light_masses_move(n):
    # n masses of 0.5 kg (all diagonal masses below 1 kg) on springs of 100 N/m,
    # `--solver sparse` without a count: the ten lowest of the fixed-free chain,
    # solved sparse (10 < n moving coordinates: no "solved densely" warning; n = 11
    # is the edge), no graded report on the sparse path.
    k, m = 100.0, 0.5
    r = modes(chain((k,) * n, (m,) * n), solver="sparse")
    assert r.solver == "sparse" and r.graded == ""
    assert not any("solved densely" in w for w in r.warnings)
    assert r.omega == pytest.approx(fixed_free(n, k, m)[:10], rel=SPARSE)


def test_sparse_count_against_the_moving_coordinates_with_a_massless_node():
    # 4 nodes, the third massless: 3 moving coordinates; count 3 -> dense (ARPACK finds
    # fewer than all), with the warning word for word, all 3 frequencies (50 digits)
    ks, ms = (2.0e4, 3.0e4, 5.0e4, 1.0e4), (2.0, 3.0, 0.0, 4.0)
    r = modes(chain(ks, ms), solver="sparse", count=3)
    assert r.solver == "dense" and len(r.omega) == 3
    assert ("--solver sparse finds fewer than all 3 modes of this model: solved densely"
            in r.warnings)
    assert r.omega == pytest.approx(list(chain_reference(ks, ms)), rel=RTOL)


def test_auto_solver_above_small_with_a_count_is_sparse():
    # auto: dense up to SMALL = 300 coordinates, sparse above when a count is given
    # (docs: "dense when small, or when all modes are wanted"); the two lowest of the
    # uniform fixed-free chain (SPARSE). (n = 300, dense, takes 5 s: left out.)
    n, solver, k, m = 301, "sparse", 1.0e6, 10.0
    r = modes(chain((k,) * n, (m,) * n), count=2)
    assert r.solver == solver and r.to_dict()["solver"] == solver
    assert r.omega == pytest.approx(fixed_free(n, k, m)[:2], rel=SPARSE)


def test_drive_reduction_of_a_model_that_asks_for_drive_reduced():
    # the model itself says drive: reduced (as `cranefe modes` does it: api.py): the
    # comparison must solve the coupled drive, not the model's own effects. Two-mass
    # hoist: w_r^2 / w_c^2 = 1 - m r^2 / (m r^2 + J), r = R / n (as in
    # test_mutation_kills_modal_paths); and the result's document carries it.
    n, R, J, m = 2, 0.25, 500.0, 5000.0
    model = hoist(False, J=J, rotor=0.0, falls=n, drive="reduced")
    reduced = modes(model)
    doc = drive_reduction(model, reduced)
    (mode,) = doc["modes"]
    r = R / n
    assert (1 + mode["relative_error"]) ** 2 == pytest.approx(
        1 - m * r * r / (m * r * r + J), rel=RTOL)
    reduced.drive_reduction = doc
    assert reduced.to_dict()["drive_reduction"] == doc


def test_rope_warnings_from_the_static_tension_and_the_frequencies():
    # 2000 kg on 12 m of rope with EA = 1e4 N, sway on (a static state): static strain
    # m g / EA = 1.96 (beyond 3 %: the stretch warning); vertical w^2 = EA / (12 m) =
    # 0.417 s^-2, a pendulum of g / w^2 = 23.5 m, longer than the model: the slow-mode
    # warning; the sway pendulum w^2 = S / (12 m) = g / 12.
    text = """cranefe: 1
plane: xz
nodes: {S: [0, 0, 30], B: [0, 0, 18]}
ground: [S]
masses: {B: MASS}
ropes:
  r: {EA: EA, path: [S, B]}
effects: {sway: true}
"""
    r = modes(load("soft.yaml", text.replace("MASS", "2000").replace("EA: EA", "EA: 1.0e4")))
    assert r.omega**2 == pytest.approx([1.0e4 / 12.0 / 2000, G / 12.0], rel=RTOL)
    assert any(w.startswith("ropes.r: the static tension 1.962e+04 N") for w in r.warnings)
    assert any(w.startswith("the slowest mode") for w in r.warnings)
    # 50 g on a stiff rope: tension 0.49 N, small but not slack: no slack warning
    r = modes(load("light.yaml", text.replace("MASS", "0.05").replace("EA: EA", "EA: 1.0e7")))
    assert not any("has no tension" in w for w in r.warnings)


def test_messages_name_the_entry_and_the_cause():
    model = chain((1.0e4,), (1.0,))
    with pytest.raises(ModelError) as e:
        modes(model, count=0)
    assert e.value.file == "chain.yaml" and e.value.entry == "count"
    assert e.value.message == "count 0: ask for at least one mode (a whole number >= 1)"
    nothing = load("none.yaml", "cranefe: 1\nplane: xz\nnodes: {A: [0, 0, 0]}\n"
                   "ground: [A]\n")
    with pytest.raises(AnalysisError) as e:
        modes(nothing)
    assert str(e.value) == ("the model has no degrees of freedom for these effects: "
                            "nothing moves")
    m, l = 800.0, 3.0
    with pytest.raises(AnalysisError) as e:
        modes(_two_bars(0.5 * m * G * l, 3.0e5))
    assert str(e.value).endswith(
        "(e.g. a body balanced above its hinge with too weak a spring, a compressed rope "
        "or a member past its buckling load); check the supports, the loads and the "
        "geometry")


def test_timings_are_durations_within_the_call():
    # solve and total are durations (differences of perf_counter), within the call
    t0 = time.perf_counter()
    r = modes(chain((1.0e4,) * 3, (1.0,) * 3))
    wall = time.perf_counter() - t0
    t = r.to_dict()["timings_s"]
    assert 0 <= t["solve"] <= t["total"] <= wall


def test_neutral_mode_labelled_by_its_own_coordinate():
    # bar a stable (3e5 N m/rad), bar b neutral (k = m g l exactly, its terms cancel to
    # round-off): the rigid mode is b's angle, coordinate 1, not coordinate 0; the
    # other w^2 = (3e5 - m g l) / (Ic + m l^2) by hand
    m, l, Ic = 800.0, 3.0, 900.0
    r = modes(_two_bars(3.0e5, m * G * l))
    assert r.rigid.tolist() == [True, False] and r.quasi_cyclic == ("body b ry",)
    assert r.omega[1] ** 2 == pytest.approx((3.0e5 - m * G * l) / (Ic + m * l * l),
                                            rel=RTOL)
    assert math.isfinite(r.period_s[1])


FREE = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {G: [0, 0, 0], A: [1, 0, 0], B: [2, 0, 0], C: [3, 0, 0], N: [20, 0, 0],
        P: [25, 0, 0]}
ground: [G]
supports: {A: [uz], B: [uz], C: [uz]}
masses: {A: 2.0, B: 2.0, C: 2.0}
bodies:
  f: {mass: 5.0, com: [20, 0, 0], inertia: 1.0, nodes: [N]}
  g: {mass: 3.0, com: [25, 0, 0], inertia: 1.0, nodes: [P]}
joints:
  - {type: slider, bodies: [ground, f], at: N, axis: [1, 0, 0]}
  - {type: slider, bodies: [ground, g], at: P, axis: [1, 0, 0]}
springs:
  - {name: a, type: axial, nodes: [G, A], stiffness: 100.0}
  - {name: b, type: axial, nodes: [A, B], stiffness: 100.0}
  - {name: c, type: axial, nodes: [B, C], stiffness: 100.0}
"""

FREE3 = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {N: [0, 0, 0], P: [5, 0, 0], Q: [10, 0, 0]}
bodies:
  f: {mass: 5.0, com: [0, 0, 0], inertia: 1.0, nodes: [N]}
  g: {mass: 3.0, com: [5, 0, 0], inertia: 1.0, nodes: [P]}
  h: {mass: 2.0, com: [10, 0, 0], inertia: 1.0, nodes: [Q]}
joints:
  - {type: slider, bodies: [ground, f], at: N, axis: [1, 0, 0]}
  - {type: slider, bodies: [ground, g], at: P, axis: [1, 0, 0]}
  - {type: slider, bodies: [ground, h], at: Q, axis: [1, 0, 0]}
"""


def test_sparse_with_coordinates_that_no_element_holds():
    # Two bodies on sliders that nothing holds (K_ii = 0: rigid, 0 Hz) beside a
    # fixed-free chain of 3 masses 2 kg on 100 N/m springs along x. The sparse shift
    # comes from the positive K_ii / M_ii only (a zero one would make K - sigma M
    # singular): 2 rigid modes, then the chain's lowest (closed form, SPARSE).
    r = modes(load("free.yaml", FREE), solver="sparse", count=3)
    assert r.solver == "sparse" and r.rigid.tolist() == [True, True, False]
    assert r.omega[:2].tolist() == [0.0, 0.0]
    assert r.omega[2] == pytest.approx(fixed_free(3, 100.0, 2.0)[0], rel=SPARSE)
    # without the chain nothing is held at all: every K_ii = 0, the shift falls back
    # to -1e-3 s^-2; two of the three bodies' rigid modes
    r = modes(load("free3.yaml", FREE3), solver="sparse", count=2)
    assert r.solver == "sparse" and r.rigid.tolist() == [True, True]
    assert r.omega.tolist() == [0.0, 0.0]
    # dense: every coordinate rigid, nothing left to solve after the condensation
    r = modes(load("free3.yaml", FREE3))
    assert r.solver == "dense" and r.rigid.tolist() == [True] * 3
    assert r.omega.tolist() == [0.0] * 3 and r.shapes.shape == (3, 3)
    assert r.graded == ""                        # nothing graded to solve


def test_drive_reduction_of_a_sparse_result_pairs_every_mode():
    # The two-mass hoist (drive: reduced in the model) beside a separate fixed-free
    # chain of 12 masses of 10 kg on 1e5 N/m springs along x (13 moving coordinates).
    # Sparse, 11 modes: the coupled model (one more coordinate, the drum: a rigid mode)
    # must be asked for 12 so that all 11 elastic modes pair: the chain's modes do not
    # see the drum (relative error 0 to round-off), the hoist's m r^2 / (m r^2 + J).
    n, R, J, m = 2, 0.25, 500.0, 5000.0
    chain_nodes = ", ".join(f"C{i}: [{100 + i}, 0, 0]" for i in range(12))
    springs = "\n".join(f"  - {{name: c{i}, type: axial, nodes: [{a}, C{i}], "
                        "stiffness: 1.0e5}"
                        for i, a in enumerate(["Z"] + [f"C{i}" for i in range(11)]))
    model = load("hoist_chain.yaml", f"""cranefe: 1
plane: xz
nodes: {{D: [0, 0, 0], S: [0, 0, 30], B: [0, 0, 10], Z: [99, 0, 0], {chain_nodes}}}
ground: [D, S, Z]
supports: {{{", ".join(f"C{i}: [uz]" for i in range(12))}}}
masses: {{B: {m}, {", ".join(f"C{i}: 10.0" for i in range(12))}}}
drums:
  hoist: {{node: D, radius: {R}, inertia: {J}, brake: false}}
ropes:
  hoist: {{EA: 2.0e7, path: [hoist, S, {{node: B, falls: {n}}}]}}
springs:
{springs}
effects: {{sway: false, drive: reduced}}
""")
    reduced = modes(model, solver="sparse", count=11)
    assert reduced.solver == "sparse" and len(reduced.omega) == 11
    doc = drive_reduction(model, reduced)
    assert len(doc["modes"]) == 11
    err = sorted(abs(d["relative_error"]) for d in doc["modes"])
    r = R / n
    assert max(err[:10]) < 1e-9                     # the chain: ARPACK round-off
    assert (1 - err[10]) ** 2 == pytest.approx(1 - m * r * r / (m * r * r + J), rel=1e-9)


@pytest.mark.parametrize("m, l", [(733.0, 3.0), (99.9, 2.7)])
def test_sparse_neutral_mode_with_a_negative_round_off(m, l):
    # bar a neutral (k = m g l exactly), bar b stable, sparse count 1: the neutral mode's
    # element terms cancel to a w^2 of about -1e-37 (these m, l) or -7e-16 s^-2: zero to
    # round-off, a rigid mode, not an instability
    r = modes(_two_bars(m * G * l, 3.0e5, m=m, l=l), solver="sparse", count=1)
    assert r.rigid.tolist() == [True] and r.omega.tolist() == [0.0]


def test_auto_solver_dense_up_to_dense_max_inclusive(monkeypatch):
    # auto with no count: dense up to DENSE_MAX coordinates inclusive (docs: "dense when
    # all modes are wanted", up to that size); the limits set low so that a 4-mass chain
    # sits exactly on DENSE_MAX: all 4 modes, densely, without a warning
    import cranefe.analysis.modal as modal
    monkeypatch.setattr(modal, "SMALL", 2)
    monkeypatch.setattr(modal, "DENSE_MAX", 4)
    n, k, m = 4, 1.0e6, 10.0
    r = modes(chain((k,) * n, (m,) * n))
    assert r.solver == "dense" and not r.warnings
    assert r.omega == pytest.approx(fixed_free(n, k, m), rel=RTOL)
