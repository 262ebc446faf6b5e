"""Massless free blocks in operation scenes (a hook block whose mass is neglected;
docs/operations.md "Massless blocks"): the small-motion limit is `cranefe modes` (the
linear core condenses massless nodes), the load on a sling below a block on n falls
oscillates axially at sqrt(k_series / m), the block stays in equilibrium at every
instant, and what is not solved with them is refused."""

import numpy as np
import pytest
import scipy.linalg as sla
from test_operation import mechanism, scene

from cranefe.analysis.operation.integrate import simulate
from cranefe.cli import main
from cranefe.model import load

G = 9.81
BLOCK = """cranefe: 1
name: load on a sling below a massless block on 2 falls
plane: xz
nodes:
  W: [-5, 0, 20]
  S: [0, 0, 20]
  B: [0, 0, 10]
  L: [0, 0, 7]
ground: [W, S]
masses: {L: 1000}
drums:
  hoist: {node: W, radius: 0.5, inertia: 10, rope_reserve: 100}
ropes:
  hoist: {EA: 1.0e7, path: [hoist, S, {node: B, falls: 2}]}
  sling: {EA: 5.0e6, path: [B, L]}
"""
M_LOAD = 1000.0
L_HOIST = 5.0 + 2 * 10.0          # the drum's span and two falls of 10 m
K_SERIES = 1 / (1 / (4 * 1.0e7 / L_HOIST) + 1 / (5.0e6 / 3.0))   # n^2 EA / L, EA / l


def condensed(mech):
    """The engine's tangent at the static state with the massless rows condensed
    (K* = K_xx - K_xy K_yy^-1 K_yx) and the masses: (omega^2, modes, x, M)."""
    ev = mech.evaluate(0.0, mech.q0, np.zeros(mech.n), mech.taut0)
    assert np.abs(ev.F).max() < 1e-9 * M_LOAD * G                 # at rest
    y = mech.qy
    x = np.setdiff1d(np.arange(mech.n), y)
    K = ev.K
    Ks = K[np.ix_(x, x)] - K[np.ix_(x, y)] @ np.linalg.solve(K[np.ix_(y, y)], K[np.ix_(y, x)])
    M = np.diag(mech.M[x])
    lam, phi = sla.eigh(Ks, M)
    return lam, phi, x, M


def test_linearisation_is_the_linear_core_and_the_closed_form(tmp_path):
    """At the static state the engine's tangent, massless rows condensed, has the
    frequencies of `cranefe modes` (which condenses massless nodes; drum held) to 1e-10,
    and these are the closed forms: the axial sqrt(k_series / m) with the hoist's
    n^2 EA / L (2 falls) in series with the sling's EA / l, and the pendulum of the whole
    length sqrt(g / 13) (the block's horizontal equilibrium puts the two spans in
    series: (S/l) of the falls 2 (m g / 2) / 10 and of the sling m g / 3)."""
    from cranefe.analysis.modal import modes
    path = scene(tmp_path, BLOCK, "  duration: 1\n")
    model = load(path)
    mech = mechanism(model)
    assert mech.n == 4 and list(mech.qy) == [2, 3] and list(mech.M[2:]) == [0, 0]
    np.testing.assert_allclose(mech.S0, [M_LOAD * G / 2, M_LOAD * G], rtol=1e-12)
    w = np.sqrt(condensed(mech)[0])
    lin = modes(model.with_effects(drive="held")).omega
    np.testing.assert_allclose(w, lin, rtol=1e-10)
    np.testing.assert_allclose(w, [np.sqrt(G / 13), np.sqrt(K_SERIES / M_LOAD)],
                               rtol=1e-12)


@pytest.mark.parametrize("dq, duration, tol, bound", [
    ((0.0, -0.001), 0.5, 1e-10, 2e-4),   # axial: 2.4 periods (measured 9.4e-5)
    ((0.01, 0.0), 8.0, 1e-9, 1e-5),      # pendulum: 1.1 periods (measured 2.4e-6)
])
def test_small_release_oscillates_at_the_modes_frequencies(tmp_path, dq, duration, tol,
                                                           bound):
    """The load released 1 mm down or 1 cm sideways (the block put into equilibrium by
    the engine, its velocity from the implicit function): the load follows the linear
    modal solution q0 + sum phi phi^T M dq cos(w t) of the condensed system to `bound` of
    the release (the trapezoidal rule's phase error (w h)^2 / 12 per radian and the
    second-order terms of the release, ~1e-5), and the axial zero crossings give
    sqrt(k_series / m) to 1e-5 (measured 3.6e-6)."""
    path = scene(tmp_path, BLOCK, f"  duration: {duration}\n  tolerance: {tol}\n"
                 "  output_step: 0.002\n")
    model = load(path)
    mech = mechanism(model)
    q = mech.q0.copy()
    q[:2] += dq
    res = simulate(model, initial={"q": q, "v": np.zeros(mech.n)})
    lam, phi, x, M = condensed(mech)
    ref = mech.q0[x] + (np.cos(np.outer(res.times, np.sqrt(lam))) *
                        (phi.T @ M @ np.array(dq))) @ phi.T
    got = res.mass_position[:, 0, [0, 2]]
    k = int(np.argmax(np.abs(dq)))
    assert np.abs(got - ref)[:, k].max() < bound * abs(dq[k])
    if k == 1:
        u, t = got[:, 1] - mech.q0[1], res.times
        i = np.flatnonzero((u[:-1] < 0) & (u[1:] >= 0))
        tc = t[i] - u[i] * (t[i + 1] - t[i]) / (u[i + 1] - u[i])
        w = 2 * np.pi * (len(tc) - 1) / (tc[-1] - tc[0])
        assert abs(w / np.sqrt(K_SERIES / M_LOAD) - 1) < 1e-5
    assert res.energy_error < 1e-8


def test_block_in_equilibrium_while_hoisting(tmp_path):
    """The drum hauls in 2 m of rope on a trapezoid (sway on): the massless block is in
    equilibrium at every output time, 2 S_hoist = S_sling (its two falls against the
    sling; to 1e-6 of the force: the samples between steps are Hermite interpolants of
    each force), the load rises by half the rope (2 falls) up to the axial ringing the
    stop leaves (undamped: at most 2 m a / k_series, a = 0.25 m/s^2 the load's
    deceleration; measured 4.8e-4 m), and the energy balance closes to 1e-6."""
    path = scene(tmp_path, BLOCK, "  duration: 6\n  tolerance: 1.0e-7\n  drives:\n"
                 "    hoist: {drum: hoist, profile: {type: trapezoid, distance: 4.0, "
                 "v_max: 1.0, a_max: 1.0, start: 0.5}}\n")
    res = simulate(load(path))
    S = res.rope_force
    np.testing.assert_allclose(2 * S[:, 0], S[:, 1], rtol=1e-6)
    z = res.mass_position[:, 0, 2]
    assert abs(z[-1] - z[0] - 0.5 * 4.0 * 0.5) < 2 * M_LOAD * 0.25 / K_SERIES
    assert res.energy_error < 1e-6
    assert "B" in res.sway_names          # the block's angle is reported too


def test_what_massless_blocks_do_not_cover_is_refused(tmp_path, capsys):
    """Damping (a dashpot makes the block's velocity a differential unknown) and
    inextensible ropes with a massless block: exit 2 naming the effect."""
    for eff, entry in (("{damping: exact}", "effects.damping"),
                       ("{rope_elasticity: false}", "effects.rope_elasticity")):
        path = scene(tmp_path, BLOCK, "  duration: 1\n", effects=eff,
                     name=f"{entry}.yaml")
        assert main(["simulate", str(path)]) == 2
        err = capsys.readouterr().err
        assert entry in err and "massless" in err, err


def test_a_block_whose_ropes_go_slack_stops_with_a_message(tmp_path, capsys):
    """The drum hauls in at 4 m/s of rope and stops within 0.05 s: the load (2 m/s up)
    decelerates slower than the stop and the block's ropes go slack. A massless block
    held by nothing has no position: the run stops with exit 1 naming the block and
    the time (audit: before, a LinAlgError traceback and no output), the CSV and JSON
    of what was computed kept."""
    import json
    path = scene(tmp_path, BLOCK, "  duration: 4\n  drives:\n    hoist: {drum: hoist, "
                 "profile: {type: table, speed: [[0, 0], [1.0, 4.0], [2.0, 4.0], "
                 "[2.05, 0]]}}\n")
    csv = tmp_path / "out.csv"
    assert main(["simulate", str(path), "--json", "--csv", str(csv)]) == 1
    cap = capsys.readouterr()
    assert "massless block(s) B" in cap.err and "t = 2.0" in cap.err, cap.err
    assert "Traceback" not in cap.err
    doc = json.loads(cap.out)
    assert doc["status"] == 1 and 2.0 < doc["duration_s"] < 2.2
    assert csv.exists() and len(csv.read_text().splitlines()) > 100
