"""Transient scenes against closed forms (cranefe/cases.py): hoist start under a step
torque, lift-off at constant hauling speed, a slack rope re-tensioned; energy balance;
modal superposition with all modes equals direct integration."""

import numpy as np
import pytest

from cranefe import cases
from cranefe.model import load
from cranefe.analysis.transient.integrate import simulate

G = 9.81


def scene(tmp_path, model_text, analysis, effects="{sway: false}", name="scene.yaml"):
    model = tmp_path / "model.yaml"
    if not model.exists():
        model.write_text(model_text)
    path = tmp_path / name
    path.write_text(f"cranefe: 1\nscene: test\nmodel: {model}\neffects: {effects}\n"
                    f"analysis:\n  type: transient\n{analysis}")
    return load(path)


def test_step_torque_against_the_closed_form(tmp_path):
    text, ex = cases.hoist_step_torque(ratio=1.6)
    h = 5e-4
    r = simulate(scene(tmp_path, text, f"  duration: 1.0\n  time_step: {h}\n  drums:\n"
                                       f"    hoist: {{torque: {ex['torque']}}}\n"))
    t = r.times
    # the trapezoidal rule's period error (w h)^2 / 12 = 5e-6 shifts the phase by
    # 5e-6 w t < 8e-5 rad over the run: forces agree to that times dS / S
    np.testing.assert_allclose(r.rope_force[:, 0], ex["force"](t), rtol=1e-5)
    np.testing.assert_allclose(r.drum_speed[:, 0], ex["drum_speed"](t),
                               atol=1e-5 * np.abs(ex["drum_speed"](t)).max())
    # the peak is interpolated between steps (cubic Hermite): no sampling error left
    assert r.rope_force_max[0] == pytest.approx(ex["peak"], rel=1e-9)
    assert r.rope_force_max_time[0] == pytest.approx(ex["peak_time"], rel=1e-5)
    assert r.dynamic_factor[0] == pytest.approx(ex["peak"] / ex["S0"], rel=1e-9)
    # undamped and linear: the discrete energy balance holds to round-off
    assert r.energy_error < 1e-11
    assert r.energy["work_loads"] > 0 and r.energy["dissipated"] == 0


def test_principal_coordinates_follow_heletiy_eq_8(tmp_path):
    """Seed eq. 7-8 by hand for q = (s, theta), s = z - R theta / n (positional, the rope
    stretch is -n s) and theta (quasi-cyclic): A = T^T diag(m, J) T, C = diag(n^2 k, 0),
    A1 = A11 - A12^2 / A22, F1' = F1 - A12 / A22 F2; s then oscillates about F1'/C1."""
    J, R, m, n, EA = 500.0, 0.25, 5000.0, 2, 2.0e7
    text, ex = cases.hoist_step_torque(ratio=1.6, falls=n, J=J, R=R, m=m, EA=EA)
    k = EA / (30 + 20 * n)
    T = np.array([[1.0, R / n], [0.0, 1.0]])          # (z, theta) = T (s, theta)
    A = T.T @ np.diag([m, J]) @ T
    F = T.T @ np.array([0.0, ex["torque"] - R * ex["S0"]])
    A1 = A[0, 0] - A[0, 1] ** 2 / A[1, 1]
    F1 = F[0] - A[0, 1] / A[1, 1] * F[1]
    C1 = n * n * k
    assert np.sqrt(C1 / A1) == pytest.approx(ex["omega"], rel=1e-12)
    assert -n * k * F1 / C1 == pytest.approx(ex["dS"], rel=1e-12)   # stretch force
    r = simulate(scene(tmp_path, text, "  duration: 0.5\n  time_step: 5e-4\n  method: modal\n"
                                       f"  drums:\n    hoist: {{torque: {ex['torque']}}}\n"))
    assert r.modes == 1
    assert r.rope_force_max[0] == pytest.approx(ex["S0"] - 2 * n * k * F1 / C1, rel=1e-9)


def test_lift_off_at_constant_hauling_speed(tmp_path):
    text, ex = cases.hoist_lift_off(drum_speed=2.0)
    r = simulate(scene(tmp_path, text, "  duration: 0.6\n  time_step: 0.002\n"
                                       "  initial: grounded\n  drums:\n    hoist: {speed: 2.0}\n"))
    # the force grows linearly before lift-off, which the trapezoidal rule follows
    # exactly, and the event is located to 1e-9 of the weight
    assert r.lift_off_time == pytest.approx(ex["lift_off_time"], rel=1e-9)
    assert r.dynamic_factor[0] == pytest.approx(ex["dynamic_factor"], rel=1e-8)
    assert r.rope_force_static[0] == pytest.approx(ex["S0"], rel=1e-12)
    assert r.ground_force[0, 0] == pytest.approx(5000 * G, rel=1e-12)
    assert r.ground_force[-1, 0] == 0
    assert [e.split(": ")[1] for e in r.events] == ["B lift-off"]
    # the drive does work (its reaction torque) and the energy balance closes
    assert r.energy["work_drives"] > 0
    assert r.energy_error < 1e-12


def test_lift_off_time_does_not_depend_on_the_step(tmp_path):
    text, ex = cases.hoist_lift_off(drum_speed=2.0)
    for h in (0.05, 0.013):
        r = simulate(scene(tmp_path, text, f"  duration: 0.8\n  time_step: {h}\n  initial: "
                                           "grounded\n  drums:\n    hoist: {speed: 2.0}\n",
                           name=f"s{h}.yaml"))
        assert r.lift_off_time == pytest.approx(ex["lift_off_time"], rel=1e-9)
        # the period lengthens by (w h)^2 / 12, the amplitude is kept: the peak's error
        # is the interpolation's, O((w h)^4)
        assert r.dynamic_factor[0] == pytest.approx(ex["dynamic_factor"],
                                                    rel=(ex["omega"] * h) ** 4)


def test_slack_rope_retensioned_against_the_closed_form(tmp_path):
    text, ex = cases.hoist_slack(hook_speed=0.9)
    r = simulate(scene(tmp_path, text, "  duration: 0.4\n  time_step: 2e-4\n  drums:\n"
                                       f"    hoist: {{speed: {ex['drum_speed']}}}\n"))
    events = [(float(e.split(" s: ")[0]), e.split(" ")[-1]) for e in r.events]
    assert [what for _, what in events] == ["slack", "taut"]
    # event times carry the phase error of the step before them: (w h)^2 / 12 w t
    assert events[0][0] == pytest.approx(ex["slack_time"], rel=1e-5)
    assert events[1][0] == pytest.approx(ex["taut_time"], rel=1e-5)
    assert r.rope_force_max[0] == pytest.approx(ex["peak"], rel=1e-7)
    assert r.energy_error < 1e-11


@pytest.mark.parametrize("h, effects", [(1e-3, "{sway: false}"), (1e-5, "{sway: false}"),
                                        (5e-4, "{sway: false, rope_mass: 4}")])
def test_slack_rope_events_keep_the_energy(tmp_path, h, effects):
    """A free drum paid out by a negative torque faster than the load can follow: the
    rope goes slack, the load falls freely, the rope takes it again; no energy is lost
    at the events at any step (with rope mass: every element is tension-only)."""
    text, ex = cases.hoist_step_torque(mu=1.5)
    duration = 0.6 if h > 1e-4 else 0.08
    table = f"[[0, -{10 * ex['torque']}], [0.05, -{10 * ex['torque']}], [0.06, 0]]"
    r = simulate(scene(tmp_path, text, f"  duration: {duration}\n  time_step: {h}\n"
                                       f"  drums:\n    hoist: {{torque: {table}}}\n",
                       effects=effects))
    kinds = {e.split(" ")[-1] for e in r.events}
    assert "slack" in kinds
    if duration > 0.1:
        assert "taut" in kinds
    assert r.energy_error < 1e-9
    assert np.all(r.rope_force >= 0)


@pytest.mark.parametrize("effects, analysis", [
    ("{sway: false}", "drums:\n    hoist: {torque: [[0, 0], [0.2, 15000], [1.0, 15000]]}"),
    ("{sway: true, damping: modal}", "drums:\n    hoist: {torque: 12000}"),
    ("{sway: false, rope_mass: 4, damping: modal}", "drums:\n    hoist: {torque: 12000}"),
    ("{sway: false, rope_mass: 3}", "drums:\n    hoist: {speed: 2.0, ramp: 0.3}"),
    ("{sway: false, rope_mass: 3}",
     "drums:\n    hoist: {motor: {stall_torque: 500, synchronous_speed: 150}}"),
])
def test_modal_superposition_with_all_modes_equals_direct(tmp_path, effects, analysis):
    text, _ = cases.hoist_step_torque(mu=1.5)
    common = f"  duration: 0.8\n  time_step: 0.002\n  {analysis}\n"
    d = simulate(scene(tmp_path, text, common, effects, "d.yaml"))
    m = simulate(scene(tmp_path, text, common + "  method: modal\n  modes: 1000\n", effects,
                       "m.yaml"))
    # the same trapezoidal rule on equations that differ by an orthogonal change of
    # coordinates: equal to round-off
    np.testing.assert_allclose(m.rope_force, d.rope_force, rtol=1e-9)
    np.testing.assert_allclose(m.drum_speed, d.drum_speed, rtol=1e-9,
                               atol=1e-10 * np.abs(d.drum_speed).max())
    np.testing.assert_allclose(m.drum_torque, d.drum_torque, rtol=1e-8)
    assert m.rope_force_max == pytest.approx(d.rope_force_max, rel=1e-9)
    assert d.energy_error < 1e-10 and m.energy_error < 1e-10


def test_modal_equals_direct_with_massless_nodes_and_several_ropes(tmp_path):
    """Luffing tower crane: a massless tackle block (static condensation inside the
    modal solution), a braked luffing drum, four ropes."""
    path = tmp_path / "s.yaml"
    base = "cranefe: 1\nscene: t\nmodel: {m}\neffects: {{sway: true}}\nanalysis:\n" \
           "  type: transient\n  duration: 0.5\n  time_step: 0.005\n" \
           "  drums:\n    hoist: {{torque: 9000}}\n"
    import os
    model = os.path.join(os.path.dirname(__file__), "..", "models", "luffing_tower_crane.yaml")
    path.write_text(base.format(m=os.path.abspath(model)))
    d = simulate(load(path))
    path.write_text(base.format(m=os.path.abspath(model)) + "  method: modal\n  modes: 99\n")
    m = simulate(load(path))
    assert d.dofs > m.modes
    np.testing.assert_allclose(m.rope_force, d.rope_force, rtol=1e-8)
    assert d.energy_error < 1e-10


def test_static_correction_of_a_prescribed_drum(tmp_path):
    """A prescribed drum angle loads the held structure through -K_fp theta(t): the
    quasi-static following motion is no combination of a few modes, so without the
    static correction (mode acceleration) the truncated solution is far off; with it two
    modes give the peak to 1e-3 (rope with 8 elements per fall, 25 coordinates)."""
    text, _ = cases.hoist_step_torque(mu=1.5)
    eff = "{sway: false, rope_mass: 8}"
    common = "  duration: 0.6\n  time_step: 0.001\n  drums:\n    hoist: {speed: 2.0, ramp: 0.2}\n"
    ref = simulate(scene(tmp_path, text, common, eff, "ref.yaml")).rope_force_max[0]
    err = {}
    for corr in ("true", "false"):
        r = simulate(scene(tmp_path, text, common + f"  method: modal\n  modes: 2\n"
                                                    f"  static_correction: {corr}\n",
                           eff, f"c{corr}.yaml"))
        err[corr] = abs(r.rope_force_max[0] / ref - 1)
    assert err["true"] < 1e-3
    assert err["false"] > 1.0
    assert any("static_correction" in w for w in r.warnings)


@pytest.mark.parametrize("motor, slip", [
    ("{stall_torque: 15000, synchronous_speed: 10}", None),
    ("{breakdown_torque: 20000, breakdown_slip: 0.3, synchronous_speed: 10}", 0.3),
])
def test_motor_runs_up_to_its_steady_speed(tmp_path, motor, slip):
    """Damped run to steady state: motor torque = holding torque R S0 at the drum (the
    case's drum has no gearbox: gear ratio 1)."""
    text, ex = cases.hoist_step_torque(J=10.0)
    text = text.replace("hoist: {EA:", "hoist: {psi: 1.0, EA:")      # damps the rope
    model = scene(tmp_path, text, f"  duration: 6.0\n  time_step: 0.004\n  drums:\n"
                                  f"    hoist: {{motor: {motor}}}\n",
                  effects="{sway: false, damping: modal}")
    r = simulate(model)
    gear = model.drums[0].gear_ratio
    hold = 0.25 * ex["S0"]                         # N m at the drum
    Mm = hold / gear                               # at the motor
    if slip is None:
        n = 10 * (1 - Mm / 15000)
    else:                                          # Kloss: the stable (small) slip root
        a = Mm / (2 * 20000 * slip)                # s / (s^2 + sk^2) = a
        s = (1 - np.sqrt(1 - 4 * a * a * slip * slip)) / (2 * a)
        n = 10 * (1 - s)
    # what is left of the start's oscillation after 6 s: exp(-zeta w t) ~ 1e-3 of it
    assert r.drum_speed[-1, 0] == pytest.approx(n / gear, rel=3e-4)
    assert r.drum_torque[-1, 0] == pytest.approx(hold, rel=3e-3)


def test_scenes_at_rest_stay_at_rest(tmp_path):
    """Both initial states are equilibria: with nothing driven nothing moves (the
    grounded tensions are statically admissible, the brakes hold)."""
    import os
    root = os.path.join(os.path.dirname(__file__), "..", "models")
    for name in ("luffing_tower_crane.yaml", "hammerhead_tower_crane.yaml"):
        for init in ("static", "grounded"):
            path = tmp_path / f"{name}.{init}.yaml"
            path.write_text(f"cranefe: 1\nmodel: {os.path.abspath(os.path.join(root, name))}"
                            f"\neffects: {{sway: false}}\nanalysis:\n  type: transient\n"
                            f"  duration: 0.2\n  time_step: 0.01\n  initial: {init}\n")
            r = simulate(load(path))
            assert np.abs(r.q).max() < 1e-12, (name, init)
            assert np.isnan(r.lift_off_time)


def test_automatic_time_step(tmp_path):
    text, ex = cases.hoist_step_torque()
    r = simulate(scene(tmp_path, text, f"  duration: 2.0\n  drums:\n    hoist: "
                                       f"{{torque: {ex['torque']}}}\n"))
    # a twentieth of the shortest period
    assert r.time_step == pytest.approx(2 * np.pi / ex["omega"] / 20, rel=0.02)
    assert r.highest_frequency_hz == pytest.approx(ex["omega"] / (2 * np.pi), rel=1e-9)
    text, _ = cases.hoist_step_torque(mu=1.5)
    tmp_path = tmp_path / "b"
    tmp_path.mkdir()
    r = simulate(scene(tmp_path, text, "  duration: 0.5\n  max_steps: 400\n  drums:\n"
                                       f"    hoist: {{torque: {ex['torque']}}}\n",
                       effects="{sway: false, rope_mass: 8}", name="b.yaml"))
    assert r.steps == 400 and "capped" in r.warnings[0]


@pytest.mark.parametrize("sway", ["true", "false"])
def test_exact_damping_at_the_frequency_that_strains_the_rope(tmp_path, sway):
    # damping: exact makes each element a dashpot b = psi c / (2 pi w) at the frequency
    # of the mode that most strains it. With sway the lowest mode is the pendulum, which
    # does not stretch the rope; at its frequency the hoisting mode got 20 x its damping.
    # One absorbing rope: B = (b / c) K, so the hoisting mode has zeta = psi / (4 pi) and
    # the step-torque peak is S0 + dS (1 + exp(-zeta pi / sqrt(1 - zeta^2))).
    text, ex = cases.hoist_step_torque(ratio=1.6)
    psi = 0.3
    text = text.replace("path: [hoist", f"psi: {psi}, path: [hoist")
    r = simulate(scene(tmp_path, text, f"  duration: 0.5\n  time_step: 2e-4\n  drums:\n"
                                       f"    hoist: {{torque: {ex['torque']}}}\n",
                       effects=f"{{sway: {sway}, damping: exact}}"))
    zeta = psi / (4 * np.pi)
    peak = ex["S0"] + ex["dS"] * (1 + np.exp(-zeta * np.pi / np.sqrt(1 - zeta**2)))
    # trapezoidal rule: phase and amplitude errors of order (w h)^2 / 12 ~ 1e-6
    assert r.rope_force_max[0] == pytest.approx(peak, rel=1e-5)
