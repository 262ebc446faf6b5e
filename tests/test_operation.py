"""Operation scenes (large motions, docs/operations.md) against exact references:
the linear core at the static state, the conical pendulum of steady slewing, the
variable-length pendulum (Bessel functions), the residual sway of a trapezoidal trolley
move, the axial frequency of a mass on a rope being paid out, energy conservation."""

from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as sla
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from scipy.special import j1, jvp, y1, yvp

from cranefe.cli import main
from cranefe.errors import AnalysisError
from cranefe.model import load
from cranefe.analysis.operation.integrate import simulate
from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse

G = 9.81
HOIST = str(Path(__file__).resolve().parents[1] / "models" / "two_mass_hoist.yaml")

SLEWING = """cranefe: 1
name: slewing test crane
nodes:
  O: [0, 0, 0]
  T: [0, 0, 30]
  K: [R, 0, 30]
  H: [R, 0, Z]
ground: [O]
masses: {H: 1000}
bodies:
  jib: {mass: 5000, com: [10, 0, 30], inertia: [1.0e3, 1.0e5, 1.0e5], nodes: [O, T]}
  trolley: {mass: 500, com: [R, 0, 30], inertia: [10, 10, 10], nodes: [K]}
joints:
  - {name: slew, type: hinge, bodies: [ground, jib], at: O, axis: [0, 0, 1]}
  - {name: travel, type: slider, bodies: [jib, trolley], at: K, axis: [1, 0, 0],
     range: [-2, 20]}
ropes:
  hoist: {EA: EAVAL, path: [K, H]}
"""

WINCH = """cranefe: 1
name: variable-length pendulum
plane: xz
nodes:
  W: [-2, 0, 40]
  S: [0, 0, 40]
  H: [0, 0, Z]
ground: [W, S]
masses: {H: MASS}
drums:
  hoist: {node: W, radius: 0.5, inertia: 10, rope_reserve: 100}
ropes:
  r: {EA: EAVAL, path: [hoist, S, H]}
"""

DOUBLE = """cranefe: 1
name: hook and load on a sling
nodes:
  S: [0, 0, 30]
  H: [0, 0, 20]
  B: [0, 0, 17]
ground: [S]
masses: {H: 200, B: 2000}
ropes:
  hoist: {EA: 1.0e7, path: [S, H]}
  sling: {EA: 5.0e6, path: [H, B]}
"""


def scene(tmp_path, model_text, analysis, effects="{}", name="scene.yaml", **subs):
    for k, v in subs.items():
        model_text = model_text.replace(k, str(v))
    model = tmp_path / f"model_{name}"
    model.write_text(model_text)
    path = tmp_path / name
    path.write_text(f"cranefe: 1\nscene: test\nmodel: {model}\neffects: {effects}\n"
                    f"analysis:\n  type: operation\n{analysis}")
    return path


def mechanism(model):
    return Mechanism(model, parse(model))


# ----------------------------------------------------------------- linear core

@pytest.mark.parametrize("sway", [True, False])
@pytest.mark.parametrize("drum", ["held", "torque"])
def test_linearisation_at_the_static_state_equals_the_linear_core(tmp_path, sway, drum):
    """The tangent K and mass M at the static state give `cranefe modes`' frequencies
    (two-mass hoist; the drum held, or free under a torque equal to its holding torque):
    exact up to round-off, because S = EA ln(L/L0) has the linear core's tangent EA/L."""
    from cranefe.analysis.modal import modes
    eff = "{sway: %s}" % ("true" if sway else "false")
    path = tmp_path / "s.yaml"
    path.write_text(f"cranefe: 1\nscene: t\nmodel: {HOIST}\neffects: {eff}\n"
                    "analysis: {type: operation, duration: 1}\n")
    model = load(path)
    if drum == "torque":
        hold = float(mechanism(model).hold_torque[0])
        path.write_text(f"cranefe: 1\nscene: t\nmodel: {HOIST}\neffects: {eff}\n"
                        "analysis: {type: operation, duration: 1, drives: "
                        f"{{h: {{drum: hoist, torque: {hold!r}}}}}}}\n")
        model = load(path)
    mech = mechanism(model)
    ev = mech.evaluate(0.0, mech.q0, np.zeros(mech.n), mech.taut0)
    assert np.abs(ev.F).max() < 1e-9 * 5200 * G          # at rest
    w = np.sqrt(np.abs(np.sort(sla.eigvals(ev.K, np.diag(mech.M)).real)))
    lin = modes(model if drum == "torque" else model.with_effects(drive="held")).omega
    assert len(w) == len(lin)
    np.testing.assert_allclose(w, lin, rtol=1e-10, atol=1e-7)


@pytest.mark.parametrize("dq, duration, tol", [
    ((0.01, 0.0), 8.0, 1e-11),        # pendulum: one period
    ((0.0, -0.001), 1.0, 1e-12),      # hoisting mode: 2.4 periods
])
def test_small_release_oscillates_at_the_modes_frequencies(tmp_path, dq, duration, tol):
    """A small release from the static state (two-mass hoist with sway, drum held):
    the released coordinate follows the linear modal solution q0 + sum phi_i phi_i^T M dq cos(w_i t), whose
    frequencies are `cranefe modes`' (to 1e-10): to 1e-4 of the release (the trapezoidal
    rule's phase error (w h)^2 / 12 per radian accumulates over the run: tolerance
    1e-11-1e-12 keeps it below; the nonlinearity of a 1 cm / 1 mm release is ~1e-5)."""
    from cranefe.analysis.modal import modes
    path = tmp_path / "s.yaml"
    path.write_text(f"cranefe: 1\nscene: t\nmodel: {HOIST}\n"
                    f"analysis: {{type: operation, duration: {duration}, tolerance: {tol}, "
                    "output_step: 0.02}\n")
    model = load(path)
    mech = mechanism(model)
    lin = modes(model.with_effects(drive="held"))
    dq = np.array(dq)
    res = simulate(model, initial={"q": mech.q0 + dq, "v": np.zeros(2)})
    M = np.diag(mech.M)
    ev = mech.evaluate(0.0, mech.q0, np.zeros(2), mech.taut0)
    lam, phi = sla.eigh(ev.K, M)
    np.testing.assert_allclose(np.sqrt(lam), lin.omega, rtol=1e-10)
    ref = mech.q0 + (np.cos(np.outer(res.times, np.sqrt(lam))) * (phi.T @ M @ dq)) @ phi.T
    got = res.mass_position[:, 0, [0, 2]]
    k = int(np.argmax(np.abs(dq)))                  # the released coordinate
    err = np.abs(got - ref)[:, k].max() / np.abs(dq[k])
    assert err < 1e-4, err
    # the other one moves by the second-order coupling only: the swing lifts the hook
    # by x^2 / (2 l) on its arc (l = 16 m), up to twice that with the undamped axial
    # response; the axial motion does not move it sideways
    assert np.abs(got - ref)[:, 1 - k].max() < 1.1 * dq[0] ** 2 / 16 + 1e-12


def test_torque_start_matches_the_linear_transient(tmp_path):
    """A hoist start by a torque 0.3 % above the holding torque (sway off): the rope
    force of the operation engine equals `cranefe simulate` of the same transient scene
    to 2e-3 of its dynamic swing (12 N) over 1 s. What differs: the engine's rope
    stiffens as it shortens (EA/L at the current length), a second-order term
    EA (dL / L)^2 / 2 ~ 1e-2 N for the 2 mm hauled in (with 1 % excess torque 0.13 N, 3e-3
    of the swing: there the linear core's fixed geometry departs), and the engine's
    step error at tolerance 1e-12 (~5e-4 of the swing)."""
    from cranefe.analysis.transient.integrate import simulate as transient
    path = tmp_path / "s.yaml"
    path.write_text(f"cranefe: 1\nscene: t\nmodel: {HOIST}\neffects: {{sway: false}}\n"
                    "analysis: {type: operation, duration: 1}\n")
    hold = float(mechanism(load(path)).hold_torque[0])
    tq = 1.003 * hold
    path.write_text(f"cranefe: 1\nscene: t\nmodel: {HOIST}\neffects: {{sway: false}}\n"
                    "analysis: {type: operation, duration: 1, tolerance: 1.0e-12, "
                    f"output_step: 0.01, drives: {{h: {{drum: hoist, torque: {tq!r}}}}}}}\n")
    op = simulate(load(path))
    tpath = tmp_path / "t.yaml"
    tpath.write_text(f"cranefe: 1\nscene: t\nmodel: {HOIST}\neffects: {{sway: false}}\n"
                     "analysis: {type: transient, duration: 1, time_step: 1.0e-4, "
                     f"output_step: 0.01, drums: {{hoist: {{torque: {tq!r}}}}}}}\n")
    tr = transient(load(tpath))
    Fo, Ft = op.rope_force[:, 0], tr.rope_force[:, 0]
    assert len(Fo) == len(Ft)
    swing = Ft.max() - Ft.min()
    assert np.abs(Fo - Ft).max() < 2e-3 * swing, np.abs(Fo - Ft).max() / swing


# ----------------------------------------------------------------- exact references

def test_steady_slewing_is_the_conical_pendulum(tmp_path):
    """Slewing at a constant w with the load on its steady orbit: the radius stays
    r + l sin(theta) with tan(theta) = w^2 (r + l sin(theta)) / g, l the rope stretched
    by S = m g / cos(theta) (S = EA ln(l/L0)), over one revolution to 5e-7 of l and the
    angle to 2e-5 deg (the integrator's error accumulated over 4 700 steps at tolerance
    1e-10: 1.6e-7 of l measured)."""
    r, l0, m, EA, w = 10.0, 10.0, 1000.0, 1.0e8, 0.4
    path = scene(tmp_path, SLEWING, f"  duration: {2 * np.pi / w}\n  tolerance: 1.0e-10\n"
                 f"  drives:\n    slewing: {{hinge: slew, profile: {{type: table, speed: "
                 f"[[0, {w}]]}}}}\n", R=r, Z=30 - l0, EAVAL=EA)
    model = load(path)
    mech = mechanism(model)
    L0 = mech.L0_ref[0]

    def theta_of(l):
        return brentq(lambda th: np.tan(th) - w * w * (r + l * np.sin(th)) / G, 0, 1.5)

    def length(l):          # the stretch under the orbit's tension
        return L0 * np.exp(m * G / np.cos(theta_of(l)) / EA) - l

    l = brentq(length, 0.9 * l0, 1.1 * l0)
    th = theta_of(l)
    rho = r + l * np.sin(th)
    x0 = np.array([rho, 0.0, 30 - l * np.cos(th)])
    v0 = np.array([0.0, w * rho, 0.0])
    res = simulate(model, initial={"q": x0, "v": v0})
    P = res.mass_position[:, 0]
    radius = np.hypot(P[:, 0], P[:, 1])
    assert np.abs(radius - rho).max() < 5e-7 * l
    assert np.abs(P[:, 2] - x0[2]).max() < 5e-7 * l
    np.testing.assert_allclose(res.sway_deg[:, 0], np.degrees(th), atol=2e-5)
    # the load turns with the jib: at t the angle of the load is w t
    ang = np.unwrap(np.arctan2(P[:, 1], P[:, 0]))
    np.testing.assert_allclose(ang, w * res.times, atol=1e-6)


def variable_pendulum(t, l0, v, th0):
    """Linear sway of a pendulum whose length changes at a constant rate v (v > 0
    lowering, v < 0 hoisting) from th(0) = th0, th'(0) = 0 (docs/operations.md):
    (l^2 th')' + g l th = 0 gives th = [C1 J1(z) + C2 Y1(z)] / sqrt(l),
    z = 2 sqrt(g l) / |v|, dz/dt = sign(v) sqrt(g / l)."""
    def basis(l):
        z = 2 * np.sqrt(G * l) / abs(v)
        dz = np.sign(v) * np.sqrt(G / l)
        f = np.array([j1(z), y1(z)]) / np.sqrt(l)
        df = np.array([jvp(1, z), yvp(1, z)]) * dz / np.sqrt(l) \
            - np.array([j1(z), y1(z)]) * v / (2 * l ** 1.5)
        return f, df
    f, df = basis(l0)
    C = np.linalg.solve(np.array([f, df]), [th0, 0.0])
    return np.array([basis(l0 + v * tt)[0] @ C for tt in np.atleast_1d(t)])


def test_bessel_reference_solves_the_variable_length_pendulum():
    """The closed form against the ODE l th'' + 2 l' th' + g th = 0 integrated to 1e-12."""
    for v in (0.5, -0.5):
        l0 = 10.0 if v > 0 else 20.0
        sol = solve_ivp(lambda t, y, v=v, l0=l0: [y[1], -(2 * v * y[1] + G * y[0])
                                                  / (l0 + v * t)],
                        (0, 20), [0.01, 0.0], rtol=1e-12, atol=1e-15, dense_output=True)
        t = np.linspace(0, 20, 41)
        np.testing.assert_allclose(variable_pendulum(t, l0, v, 0.01), sol.sol(t)[0],
                                   atol=1e-11)


@pytest.mark.parametrize("v", [0.5, -0.5])
def test_hoisting_and_lowering_with_sway_follow_the_bessel_solution(tmp_path, v):
    """Lowering (10 -> 20 m) or hoisting (20 -> 10 m) at 0.5 m/s with a 0.01 rad sway on
    a stiff rope (EA/m g = 1e4): the sway angle follows the linear closed form to
    1e-3 of the initial amplitude (the nonlinearity theta0^2/16 ~ 1e-5; the rope's
    stretch ~1e-4 of l; measured 3.9e-5 and 2.2e-4, with EA ten times higher 3.7e-5
    and 2.1e-4 in three times the steps)."""
    l0 = 10.0 if v > 0 else 20.0
    th0, R = 0.01, 0.5
    path = scene(tmp_path, WINCH, f"  duration: 20\n  tolerance: 1.0e-9\n  output_step: 0.05\n"
                 f"  drives:\n    hoist: {{drum: hoist, profile: {{type: table, speed: "
                 f"[[0, {-v / R}]]}}}}\n", Z=40 - l0, MASS=1000, EAVAL=1.0e8)
    model = load(path)
    mech = mechanism(model)
    e = np.array([np.sin(th0), -np.cos(th0)])        # x, z along the rope, downwards
    res = simulate(model, initial={"q": np.array([0.0, 40.0]) + l0 * e, "v": v * e})
    P = res.mass_position[:, 0]
    th = np.arctan2(P[:, 0], 40.0 - P[:, 2])
    ref = variable_pendulum(res.times, l0, v, th0)
    assert np.abs(th - ref).max() < 1e-3 * th0, np.abs(th - ref).max() / th0
    assert mech.n == 2


@pytest.mark.parametrize("a, tol, step_tol", [(0.05, 2e-3, 1e-9), (0.5, 2e-2, 1e-8)])
def test_residual_sway_after_a_trapezoidal_trolley_move(tmp_path, a, tol, step_tol):
    """Trolley moved 10 m at v_max 1 m/s (accelerating at a; at 0.05 m/s^2 the profile
    is triangular, T_c = 0): the residual sway of a simple pendulum is (4 a / g) |sin(w T_a / 2) sin(w (T_a + T_c) / 2)| (linear, rigid
    support, w = sqrt(g/l)); the engine's nonlinear residual agrees to 0.2 % at a small
    amplitude and 2 % at a large one (the nonlinear deviation, measured, is in
    docs/operations.md; the small residual is a difference of two swings, so its step
    tolerance is tighter). EA = 1e8 N: the rope stretches 0.01 mm per kN, and the
    steps follow its axial oscillation less (a third of the steps of 1e9 N; the
    residual is the same to 4e-7 of itself)."""
    l = 10.0
    vp = min(1.0, np.sqrt(10.0 * a))        # triangular if the distance is short
    T_a = vp / a
    T_c = 10.0 / vp - T_a
    wn = np.sqrt(G / l)
    period = 2 * np.pi / wn
    dur = 2 * T_a + T_c + 1.2 * period
    path = scene(tmp_path, SLEWING, f"  duration: {dur}\n  tolerance: {step_tol}\n"
                 f"  output_step: 0.01\n"
                 f"  drives:\n    trolley: {{slider: travel, profile: {{type: trapezoid, "
                 f"distance: 10, v_max: 1.0, a_max: {a}}}}}\n", R=5.0, Z=30 - l,
                 EAVAL=1.0e8)
    res = simulate(load(path))
    lin = np.degrees(4 * a / G * abs(np.sin(wn * T_a / 2) * np.sin(wn * (T_a + T_c) / 2)))
    got = res.sway_residual_deg[0]
    assert abs(got - lin) < tol * lin, (got, lin)
    assert abs(res.motion_end - (2 * T_a + T_c)) < 1e-12


def test_axial_frequency_follows_the_rope_length(tmp_path):
    """A mass on one fall paid out at 0.5 m/s from rest (the start excites the axial
    oscillation): each local period between zero crossings of S - m g equals
    2 pi / sqrt(EA / (L m)) at that time's stretched length L (10 -> 20 m of rope), to
    1e-3 (the slow change of L per period, (L'/(L w))^2 ~ 1e-4; the step's phase error
    at tolerance 1e-7)."""
    m, EA, R = 1000.0, 2.0e6, 0.5
    path = scene(tmp_path, WINCH, f"  duration: 20\n  tolerance: 1.0e-7\n"
                 f"  output_step: 0.005\n  drives:\n    hoist: {{drum: hoist, profile: "
                 f"{{type: table, speed: [[0, {-0.5 / R}]]}}}}\n", Z=32, MASS=m,
                 EAVAL=EA, effects="{sway: false}")
    res = simulate(load(path))
    t, S = res.times, res.rope_force[:, 0] - m * G
    k = np.flatnonzero(np.sign(S[1:]) != np.sign(S[:-1]))
    tz = t[k] - S[k] * (t[k + 1] - t[k]) / (S[k + 1] - S[k])
    z = res.mass_position[:, 0, 2]
    L = 2.0 + (40.0 - z)                                  # |W S| + |S H|
    errs = []
    for i in range(2, len(tz) - 2, 7):
        Tm = tz[i + 2] - tz[i]
        Lm = np.interp(0.5 * (tz[i] + tz[i + 2]), t, L)
        errs.append(Tm / (2 * np.pi / np.sqrt(EA / (Lm * m))) - 1)
    assert len(errs) > 10
    assert np.abs(errs).max() < 1e-3, np.abs(errs).max()
    assert L[-1] > 19.9


def test_energy_is_conserved_without_damping_and_drives(tmp_path):
    """The hook-and-load double pendulum released from a large 3D offset (17 deg and
    29 deg, ropes at their static lengths): the energy balance closes to the
    integrator's error, which shrinks as the tolerance is tightened."""
    errs = []
    for tol in (1e-5, 1e-7):
        path = scene(tmp_path, DOUBLE, f"  duration: 4\n  tolerance: {tol}\n",
                     name=f"d{tol}.yaml")
        model = load(path)
        mech = mechanism(model)
        l1, l2 = mech.L_ref                 # released on the ropes' static lengths
        e1 = np.array([np.sin(0.3) * np.cos(0.4), np.sin(0.3) * np.sin(0.4), -np.cos(0.3)])
        e2 = np.array([np.sin(0.5) * np.cos(-0.2), np.sin(0.5) * np.sin(-0.2), -np.cos(0.5)])
        H = np.array([0, 0, 30.0]) + l1 * e1
        q = np.concatenate([H, H + l2 * e2])
        res = simulate(model, initial={"q": q, "v": np.zeros(6)})
        assert res.energy["work_drives"] == 0 and res.energy["dissipated"] == 0
        errs.append(res.energy_error)
        assert res.sway_max_deg[1] > 20
    assert errs[0] < 2e-3 and errs[1] < 1e-4, errs
    assert errs[1] < errs[0] / 10


def test_energy_balance_with_drives_damping_and_slack(tmp_path):
    """Paying out too fast makes the rope go slack and snap taut again: the slack and
    taut events are located, and the balance of kinetic, gravity and elastic energy
    against the drive's work and the dashpots' dissipation closes to 1e-5."""
    path = scene(tmp_path, WINCH, "  duration: 2\n  tolerance: 1.0e-9\n  drives:\n"
                 "    hoist: {drum: hoist, profile: {type: table, speed: [[0, 0], [0.05, -8], "
                 "[0.5, -8], [0.55, 0]]}}\n", Z=30, MASS=1000, EAVAL="1.0e7, psi: 0.2",
                 effects="{sway: false, damping: exact}")
    model = load(path)
    res = simulate(model)
    kinds = [w for _, w in res.events if w.startswith("rope")]
    assert "rope r slack" in kinds and "rope r taut" in kinds
    assert res.energy["dissipated"] > 0
    assert res.energy_error < 1e-5, res.energy_error
    assert res.dynamic_factor[0] > 1.5


# ----------------------------------------------------------------- bad input, blow-up

@pytest.mark.parametrize("drive, entry", [
    ("{slider: travel, profile: {type: trapezoid, distance: 25, v_max: 1, a_max: 0.5}}",
     "analysis.drives.d.profile"),
    ("{hinge: travel, profile: {type: trapezoid, distance: 1, v_max: 1, a_max: 0.5}}",
     "analysis.drives.d.hinge"),
    ("{slider: slew, profile: {type: trapezoid, distance: 1, v_max: 1, a_max: 0.5}}",
     "analysis.drives.d.slider"),
    ("{hinge: slew, profile: {type: table, speed_deg: [[0, 0], [2, 1], [1, 0]]}}",
     "analysis.drives.d.profile.speed_deg"),
    ("{hinge: slew, profile: {type: trapezoid, distance: 1, v_max: -1, a_max: 0.5}}",
     "analysis.drives.d.profile.v_max"),
    ("{hinge: slew, profile: {type: trapezoid, distance: 1, v_max: 1}}",
     "analysis.drives.d.profile"),
    ("{hinge: slew, profile: {type: jump, distance: 1}}", "analysis.drives.d.profile.type"),
    ("{hinge: nope, profile: {type: trapezoid, distance: 1, v_max: 1, a_max: 1}}",
     "analysis.drives.d.hinge"),
    ("{slider: travel, torque: 5}", "analysis.drives.d.torque"),
    ("{hinge: slew, free: false}", "analysis.drives.d.free"),
])
def test_bad_drives_name_file_and_entry(tmp_path, capsys, drive, entry):
    path = scene(tmp_path, SLEWING, f"  duration: 60\n  drives:\n    d: {drive}\n", R=10,
                 Z=20, EAVAL=1e9)
    assert main(["simulate", str(path)]) == 2
    err = capsys.readouterr().err
    assert f"{path}: {entry}:" in err, err


def test_paying_out_more_rope_than_the_drum_holds(tmp_path, capsys):
    path = scene(tmp_path, WINCH, "  duration: 100\n  drives:\n    h: {drum: hoist, "
                 "profile: {type: trapezoid, distance: -300, v_max: 4, a_max: 1}}\n",
                 Z=30, MASS=1000, EAVAL=1e8)
    assert main(["simulate", str(path)]) == 2
    err = capsys.readouterr().err
    assert "analysis.drives.h.profile" in err and "rope_reserve 100" in err


def test_hauling_the_hook_into_its_sheave(tmp_path, capsys):
    path = scene(tmp_path, WINCH, "  duration: 100\n  drives:\n    h: {drum: hoist, "
                 "profile: {type: trapezoid, distance: 30, v_max: 4, a_max: 1}}\n",
                 Z=30, MASS=1000, EAVAL=1e8)
    assert main(["simulate", str(path)]) == 2
    assert "pulled into its sheaves" in capsys.readouterr().err


def test_a_slider_without_range_is_refused(tmp_path, capsys):
    text = SLEWING.replace(",\n     range: [-2, 20]", "")
    path = scene(tmp_path, text, "  duration: 10\n  drives:\n    d: {slider: travel, "
                 "profile: {type: trapezoid, distance: 1, v_max: 1, a_max: 1}}\n", R=10,
                 Z=20, EAVAL=1e9)
    assert main(["simulate", str(path)]) == 2
    assert "add range: [min, max]" in capsys.readouterr().err


def test_a_run_that_blows_up_keeps_what_it_computed(tmp_path, capsys):
    """Ten times the holding torque hauls the hook into the head sheave: the run stops
    with AnalysisError naming the time (exit 1) and keeps the history up to there.
    (EA = 1e7 N: the same two-blocking at 0.34 s in a third of the steps of 1e8 N.)"""
    path = scene(tmp_path, WINCH, "  duration: 20\n  output_step: 0.01\n  drives:\n"
                 "    h: {drum: hoist, torque: 50000}\n", Z=35, MASS=1000, EAVAL=1e7)
    with pytest.raises(AnalysisError) as exc:
        simulate(load(path))
    res = exc.value.result
    assert "t = " in str(exc.value) and res.status == 1
    assert 0 < res.times[-1] < 20
    assert res.mass_position[-1, 0, 2] > 39
    csv = tmp_path / "out.csv"
    assert main(["simulate", str(path), "--csv", str(csv)]) == 1
    assert csv.exists()
    assert "analysis failed" in capsys.readouterr().err


# ----------------------------------------------------------------- examples, CLI

def example(tmp_path, name, duration):
    """A bundled example scene with a shorter duration (the model file next to it)."""
    import pathlib
    src = pathlib.Path(__file__).parent.parent / "models" / "operations"
    text = (src / name).read_text()
    lines = [f"  duration: {duration}" if ln.startswith("  duration:") else ln
             for ln in text.splitlines()]
    for f in src.glob("*.yaml"):
        (tmp_path / f.name).write_text(f.read_text())
    (tmp_path / name).write_text("\n".join(lines) + "\n")
    return tmp_path / name


def test_tower_crane_working_cycle_example(tmp_path, capsys):
    """The first 25 s of the working cycle (the hoist's start and stop, the trolley's
    start): the JSON contract of issue 16, and the hoist rope's dynamic factor of the
    S-curve start, pinned (1.1209, computed by this engine; hand check: the 4-fall
    hook-and-load on 163 m of rope (2.9 Hz) under a 1.5 s jerk ramp to 1.33 m/s^2 of
    rope, a quasi-static 1 + a/g = 1.034 of hook acceleration plus the sling's and the
    axial ringing)."""
    import json
    path = example(tmp_path, "tower_crane_cycle.yaml", 25)
    csv = tmp_path / "cycle.csv"
    assert main(["simulate", str(path), "--json", "--csv", str(csv), "--plots",
                 str(tmp_path / "plots")]) == 0
    doc = json.loads(capsys.readouterr().out)
    for key in ("duration_s", "rope_force_max_N", "dynamic_factor", "sway", "energy_error",
                "events", "timings_s", "warnings"):
        assert key in doc
    assert set(doc["sway"]) == {"HOOK", "LOAD"}
    assert set(doc["sway"]["HOOK"]) == {"max_deg", "residual_deg"}
    assert doc["dynamic_factor"]["hoist_rope"] == pytest.approx(1.1209, abs=2e-3)
    assert doc["energy_error"] < 1e-4
    head = csv.read_text().splitlines()[0].split(",")
    assert head[:4] == ["t_s", "HOOK.x_m", "HOOK.y_m", "HOOK.z_m"]
    for col in ("hoist_rope.force_N", "sling.force_N", "hoist.position", "hoist.speed",
                "trolley.position", "trolley.speed", "slewing.position", "slewing.speed"):
        assert col in head
    assert (tmp_path / "plots" / "operation.png").exists()


def test_overhead_crane_emergency_stop_example(tmp_path):
    """The trolley's emergency stop (0.63 m/s in 0.4 s, 6 m pendulum): the residual
    sway against the linear closed form, to 3 % (the nonlinear and elastic deviation at
    a 3.5 deg swing). Linear: theta'' + w^2 theta = -x''(t) / l with x'' piecewise
    constant; a jump da_k of the acceleration at t_k adds -(da_k / g)(1 - cos w(t - t_k)),
    so once the trolley rests (sum da_k = 0) theta = sum (da_k / g) cos w(t - t_k): the
    amplitude is |sum (da_k / g) exp(-i w t_k)|."""
    path = example(tmp_path, "overhead_crane_estop.yaml", 14)
    res = simulate(load(path))
    mech = mechanism(load(path))
    l = np.linalg.norm(mech.model.coords[mech.hang[0]] - mech.model.coords[mech.free[0]])
    wn = np.sqrt(G / l)
    jumps = [(0.0, 0.315), (2.0, -0.315), (6.0, -1.575), (6.4, 1.575)]   # da at t_k
    amp = abs(sum(da / G * np.exp(-1j * wn * tk) for tk, da in jumps))
    assert res.sway_residual_deg[0] == pytest.approx(np.degrees(amp), rel=3e-2)
    assert res.events[-1][1] == "drive trolley stops"


def test_engine_agrees_with_scipy_radau(tmp_path):
    """The first 5 s of the overhead crane's move (the swing's peak force at 3.6 s)
    integrated by scipy's Radau (the same equations in first-order form, analytic
    Jacobian, rtol 1e-8): the engine's peak rope force at tolerance 1e-9 agrees to 1e-3
    of its dynamic rise over the static force (two independent integrators; Radau's peak
    is sampled every 2 ms of its dense output; measured 2.4e-4)."""
    import dataclasses

    from cranefe.analysis.operation.reference import radau
    model = load(example(tmp_path, "overhead_crane_estop.yaml", 5))
    model = dataclasses.replace(model, analysis={**model.analysis, "tolerance": 1e-9})
    res = simulate(model)
    peak, static, *_ = radau(model, rtol=1e-8, atol=1e-10)
    rise = peak[0] - static[0]
    assert rise > 100
    assert abs(res.rope_force_max[0] - peak[0]) < 1e-3 * rise


# ----------------------------------------------------------------- profiles, kinematics

@pytest.mark.parametrize("kind", ["trapezoid", "s_curve"])
@pytest.mark.parametrize("distance", [15.0, -15.0, 0.2])
def test_motion_profiles_reach_the_distance_within_their_limits(kind, distance):
    """Each profile ends at rest at its distance, never beyond v_max, a_max (and j_max);
    a short move lowers the peak speed (triangular / no cruise); speed and acceleration
    are the derivatives of the position (central differences to 1e-6)."""
    from cranefe.analysis.operation import profiles
    v, a, j = 1.0, 0.5, 1.0
    m = profiles.trapezoid(distance, v, a, 2.0) if kind == "trapezoid" else \
        profiles.s_curve(distance, v, a, j, 2.0)
    t = np.linspace(0, m.t[-1] + 5, 4001)
    s, sv, sa = np.array([m(x) for x in t]).T
    assert s[-1] == pytest.approx(distance, abs=1e-12)
    assert abs(sv[-1]) < 1e-12 and sa[-1] == 0 and s[0] == 0
    assert np.abs(sv).max() <= v * (1 + 1e-12) and np.abs(sa).max() <= a * (1 + 1e-12)
    if kind == "s_curve":
        assert np.abs(np.diff(sa)).max() / (t[1] - t[0]) <= j * (1 + 1e-9)
    dt = 1e-5
    for x in (2.3, m.t[-1] / 2 + 1.01, m.t[-1] - 0.3):
        p0, p1 = m(x - dt)[0], m(x + dt)[0]
        assert (p1 - p0) / (2 * dt) == pytest.approx(m(x)[1], abs=1e-6)
    if abs(distance) < 1:
        assert np.abs(sv).max() < v
    assert m.moves() == [(2.0, float(m.t[-1]))]


def test_two_moves_of_one_drum_and_their_events(tmp_path):
    from cranefe.analysis.operation import profiles
    up = profiles.trapezoid(10, 2, 1, 0.0)
    down = profiles.trapezoid(-10, 2, 1, 20.0)
    m = profiles.combine([up, down])
    assert m(15)[0] == pytest.approx(10) and m(40)[0] == pytest.approx(0, abs=1e-12)
    assert m(21)[1] == pytest.approx(-1)
    assert m.moves() == [(0.0, 7.0), (20.0, 27.0)]


LUFFING = """cranefe: 1
name: luffing boom
plane: xz
nodes:
  O: [0, 0, 0]
  T: [20, 0, 20]
  H: [20, 0, 8]
ground: [O]
masses: {T: 300, H: 2000}
bodies:
  boom: {mass: 4000, com: [10, 0, 10], inertia: 1.0e5, nodes: [O, T]}
joints:
  - {name: luffing, type: hinge, bodies: [ground, boom], at: O, range_deg: [-30, 30]}
ropes:
  hoist: {EA: 1.0e9, path: [T, H]}
"""


def test_luffing_by_a_hinge_moves_the_boom_tip_on_its_circle(tmp_path):
    """A boom luffed down by 20 deg about its foot (planar, hinge axis +y): the tip (a
    point mass on the boom, reported among the masses) is at the exact rotation of its
    reference position at every output time (1e-12 m); the load ends hanging below it
    swinging; luffing past the hinge's range_deg is refused. (The move takes 12 s; 2 s
    more of the swing suffice.)"""
    path = scene(tmp_path, LUFFING, "  duration: 14\n  output_step: 0.5\n  drives:\n"
                 "    luff: {hinge: luffing, profile: {type: trapezoid, distance_deg: 20, "
                 "v_max_deg: 2, a_max_deg: 1}}\n")
    res = simulate(load(path))
    k = res.mass_names.index("T")
    from cranefe.analysis.operation import profiles
    mot = profiles.trapezoid(np.radians(20), np.radians(2), np.radians(1))
    for i, t in enumerate(res.times):
        phi = mot(t)[0]             # about +y: x' = x cos + z sin, z' = -x sin + z cos
        ref = [20 * np.cos(phi) + 20 * np.sin(phi), 0, -20 * np.sin(phi) + 20 * np.cos(phi)]
        np.testing.assert_allclose(res.mass_position[i, k], ref, atol=1e-12)
    assert res.sway_max_deg[0] > 0.1
    bad = scene(tmp_path, LUFFING, "  duration: 30\n  drives:\n    luff: {hinge: luffing, "
                "profile: {type: trapezoid, distance_deg: 40, v_max_deg: 2, a_max_deg: 1}}\n",
                name="bad.yaml")
    assert main(["simulate", str(bad)]) == 2


def test_without_sway_the_load_follows_its_trolley(tmp_path):
    """sway: false: one coordinate (the height); the load stays exactly below the
    trolley while it runs 10 m and the slewing turns the jib by 30 deg, and the energy
    balance (the guidance's work on the load's horizontal motion included) closes."""
    path = scene(tmp_path, SLEWING, "  duration: 30\n  output_step: 0.1\n  drives:\n"
                 "    trolley: {slider: travel, profile: {type: trapezoid, distance: 10, "
                 "v_max: 1.0, a_max: 0.5}}\n"
                 "    slew: {hinge: slew, profile: {type: s_curve, distance_deg: 30, "
                 "v_max_deg: 3, a_max_deg: 1, j_max_deg: 1, start: 5}}\n",
                 effects="{sway: false}", R=10, Z=20, EAVAL=1e9)
    res = simulate(load(path))
    assert res.coordinates == ("H.height",)
    P = res.mass_position[:, 0]
    phi = np.arctan2(P[:, 1], P[:, 0])
    assert np.hypot(P[-1, 0], P[-1, 1]) == pytest.approx(20.0, abs=1e-9)
    assert phi[-1] == pytest.approx(np.radians(30), abs=1e-9)
    assert np.abs(res.sway_deg).max() < 1e-9
    assert res.energy_error < 1e-6


def test_kinematics_of_the_hot_path_equal_the_kernels():
    """The engine's per-call kinematics (joint data made at setup, the last state reused
    while the drives rest) against the motion kernels composed afresh along the tree, at
    times before, during and after the moves of the tower-crane cycle, revisited out of
    order. The same formulas: equal to rounding (1e-12 of the 60 m size)."""
    from cranefe import elements as kernels
    import pathlib
    from cranefe.model.model import GROUND
    model = load(pathlib.Path(__file__).parent.parent / "models" / "operations"
                 / "tower_crane_cycle.yaml")
    mech = Mechanism(model, parse(model))
    m = model
    for t in (0.0, 0.5, 3.0, 3.0, 12.7, 40.0, 55.5, 0.5, 80.0, 109.0, 109.0, 12.7):
        ref = {GROUND: kernels.IDENTITY_MOTION}
        for b in mech.order:
            p, k = mech.parent[b]
            j, d = m.joints[k], mech.driven_joints.get(k)
            if d is None:
                ref[b] = ref[p]
                continue
            s, ds, dds = (x * (1.0 if j.bodies[1] == b else -1.0) for x in d.motion(t))
            jm = (kernels.hinge_motion(j.axis, m.coords[j.at], s, ds, dds)
                  if j.type == "hinge" else kernels.slider_motion(j.axis, s, ds, dds))
            ref[b] = kernels.compose(ref[p], jm)
        X, V, A, _ = mech.kinematics(t)
        for bi, b in enumerate(model.bodies):
            idx = mech.kin[mech.carrier[mech.kin] == bi]
            R, dR, ddR, p, dp, ddp = ref[bi]
            for got, want in ((X, m.coords[idx] @ R.T + p), (V, m.coords[idx] @ dR.T + dp),
                              (A, m.coords[idx] @ ddR.T + ddp)):
                np.testing.assert_allclose(got[idx], want, rtol=0, atol=1e-12 * 60)
    assert any(mech.driven_joints)                   # the cycle moves bodies
