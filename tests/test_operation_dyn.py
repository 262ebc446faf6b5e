"""Joint coordinates of operation scenes (docs/operations.md, "Joint coordinates"):
torque, force, motor and free drives of hinges and sliders against exact references -
a slewing body under a constant torque, the cart-pendulum (its linear frequency, the
momentum theorem along the rail), a motor's exponential run-up, the holding torque of a
jib, the energy balance."""

from pathlib import Path

import numpy as np
import pytest
from test_operation import mechanism, scene
import scipy.linalg as sla

from cranefe.cli import main
from cranefe.model import load
from cranefe.analysis.operation.integrate import simulate
from cranefe.analysis.operation.scene import parse

G = 9.81

SLEW = """cranefe: 1
name: slewing body
nodes:
  O: [0, 0, 0]
  T: [0, 0, 30]
  E: [20, 0, 30]
ground: [O]
masses: {E: 500}
bodies:
  jib: {mass: 2000, com: [5, 0, 30], inertia: [1.0e3, 1.0e5, 1.0e4], nodes: [O, T, E]}
joints:
  - {name: slew, type: hinge, bodies: [ground, jib], at: O, axis: [0, 0, 1]}
"""

CART = """cranefe: 1
name: cart pendulum
plane: xz
nodes:
  G: [0, 0, 20]
  K: [0, 0, 20]
  H: [0, 0, 10]
ground: []
masses: {H: MLOAD}
bodies:
  trolley: {mass: MCART, com: [0, 0, 20.5], inertia: 50, nodes: [G, K]}
joints:
  - {name: travel, type: slider, bodies: [ground, trolley], at: G, axis: [1, 0, 0],
     range: [-50, 50]}
ropes:
  hoist: {EA: EAVAL, path: [K, H]}
"""


def test_slewing_body_under_a_constant_torque(tmp_path):
    """A body turning about a fixed vertical axis under a constant torque M: its inertia
    about the axis J = Izz + m (cx^2 + cy^2) + sum m_i r_i^2 (body and the point mass
    fixed on it), angle M t^2 / (2 J) at any angle (here 33 deg). The trapezoidal rule
    integrates a constant acceleration exactly, so only round-off remains (1e-12); the
    kinetic energy equals the drive's work M phi (energy error at round-off)."""
    path = scene(tmp_path, SLEW, "  duration: 10\n  drives:\n    s: {hinge: slew, "
                 "torque: 3000}\n")
    res = simulate(load(path))
    J = 1.0e4 + 2000 * 5**2 + 500 * 20**2
    t = res.times
    np.testing.assert_allclose(res.drive_position[:, 0], 3000 * t**2 / (2 * J),
                               rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(res.drive_speed[:, 0], 3000 * t / J, rtol=1e-12,
                               atol=1e-14)
    phi = res.drive_position[-1, 0]
    # the point mass at E turns with the body: (20 cos phi, 20 sin phi, 30)
    np.testing.assert_allclose(res.mass_position[-1, 0], [20 * np.cos(phi),
                                                          20 * np.sin(phi), 30], atol=1e-10)
    assert res.energy["kinetic_final"] == pytest.approx(3000 * phi, rel=1e-12)
    assert res.energy_error < 1e-12
    assert res.coordinates == ("joint s",)


@pytest.mark.parametrize("mload, mcart", [(2000, 1000), (500, 4000)])
def test_cart_pendulum_linear_frequency(tmp_path, mload, mcart):
    """Trolley (mass M) on a slider with a load m on a rope of length l, the trolley
    free (force 0): linearised at rest the pendulum mode has w^2 = (S / l)(1/m + 1/M)
    = g/l (1 + m/M) (S = m g; the cart recoils), the rope's axial mode decouples; the
    translation of the whole is the zero mode. Exact up to round-off (1e-10)."""
    path = scene(tmp_path, CART, "  duration: 1\n  drives:\n    c: {slider: travel, "
                 "force: 0}\n", MLOAD=mload, MCART=mcart,
                 EAVAL=1.0e10)
    mech = mechanism(load(path))
    ev = mech.evaluate(0.0, mech.q0, np.zeros(mech.n), mech.taut0)
    assert np.abs(ev.F).max() < 1e-9 * mload * G
    w = np.sort(np.sqrt(np.abs(sla.eigvals(ev.K, np.diag(mech.M)).real)))
    assert w[0] < 1e-6
    assert w[1] == pytest.approx(np.sqrt(G / 10 * (1 + mload / mcart)), rel=1e-10)
    assert w[2] == pytest.approx(np.sqrt(1.0e10 / 10 / mload), rel=1e-10)


def test_cart_pendulum_swing_keeps_momentum_and_the_linear_period(tmp_path):
    """Released with the load 0.01 rad aside and no force on the trolley: the momentum
    along the rail M s' + m x' stays zero (only internal forces act along it: conserved
    to the Newton tolerance, asserted 1e-9 of the peak m x'), the centre of mass stays
    put, and the swing's period (zero crossings of the relative displacement over
    2 periods) is the linear 2 pi / sqrt(g/l (1 + m/M)) to 1e-4 (nonlinear amplitude
    effect ~theta0^2/16 = 6e-6; the rope's stretch (m g / EA = 2e-4) is already in the
    model's geometry and varies by ~theta0^2 of it; the trapezoidal rule's phase error
    (w h)^2/12 at tolerance 1e-9 ~1e-6). Measured: the period 6.3e-5 from the linear
    one (5.7e-5 with EA 1e8: the swing's own amplitude effect, larger than the simple
    pendulum's theta0^2/16 with the cart recoiling), the centre of mass 2e-12 of
    10 theta0, the momentum 1.7e-3 (np.gradient's error on the load's speed at 2 ms
    output steps), energy 1.4e-10. The rope's EA is 1e7 (stretch 2e-3 m, its axial mode
    at 22 rad/s, well apart from the swing's 1.7 rad/s): with EA 1e8 its 0.06 s axial
    period set 5515 steps instead of 1749."""
    path = scene(tmp_path, CART, "  duration: 8\n  tolerance: 1.0e-9\n"
                 "  output_step: 0.002\n  drives:\n    c: {slider: travel, force: 0}\n",
                 MLOAD=2000, MCART=1000, EAVAL=1.0e7)
    model = load(path)
    mech = mechanism(model)
    th0 = 0.01
    q = mech.q0.copy()
    q[0], q[1] = 10 * np.sin(th0), 20 - 10 * np.cos(th0)
    res = simulate(model, initial={"q": q, "v": np.zeros(3)})
    xs, vs = res.drive_position[:, 0], res.drive_speed[:, 0]
    xl = res.mass_position[:, 0, 0]
    t = res.times
    vl = np.gradient(xl, t)
    xcm = (1000 * xs + 2000 * xl) / 3000
    assert np.abs(xcm - xcm[0]).max() < 1e-9 * 10 * th0
    # momentum from the exact speeds: the trolley's drive speed, the load's from x_cm
    assert np.abs(1000 * vs + 2000 * vl).max() < 2e-3 * 2000 * np.abs(vl).max()
    rel = xl - xs
    k = np.flatnonzero(np.sign(rel[1:]) != np.sign(rel[:-1]))
    tz = t[k] - rel[k] * (t[k + 1] - t[k]) / (rel[k + 1] - rel[k])
    period = 2 * (tz[-1] - tz[0]) / (len(tz) - 1)
    w = np.sqrt(G / 10 * 3)
    assert period == pytest.approx(2 * np.pi / w, rel=1e-4)
    assert res.energy_error < 1e-6


def test_cart_under_a_constant_force_momentum_theorem_and_energy(tmp_path):
    """A constant force F on the trolley with the load swinging behind: the centre of
    mass of trolley and load accelerates at F / (M + m) exactly (the rope's forces are
    internal), to the Newton tolerance (1e-9 of the travel asserted); the energy balance
    closes (work F s = kinetic + potential + elastic change, error < 1e-8 at tolerance
    1e-9: measured 1.7e-10; the bound was 1e-7), and the work booked is F times the
    trolley's travel. 4 s (the swing's period is 3.7 s: its first peak, twice the
    steady angle, at 1.8 s) instead of 12 s and the rope's EA 1e7 instead of 1e8 (its
    axial mode at 22 rad/s, not the 0.06 s period that set the steps): 1062 steps
    instead of 6676; the centre of mass measured 3e-13 of the travel."""
    F = 1000.0
    path = scene(tmp_path, CART, "  duration: 4\n  tolerance: 1.0e-9\n"
                 "  output_step: 0.01\n  drives:\n    c: {slider: travel, force: 1000}\n",
                 MLOAD=2000, MCART=1000, EAVAL=1.0e7)
    res = simulate(load(path))
    t = res.times
    xcm = (1000 * res.drive_position[:, 0] + 2000 * res.mass_position[:, 0, 0]) / 3000
    travel = F * t[-1]**2 / 6000
    np.testing.assert_allclose(xcm, F * t**2 / 6000, atol=1e-9 * travel)
    assert res.energy_error < 1e-8
    assert res.energy["work_drives"] == pytest.approx(F * res.drive_position[-1, 0],
                                                      rel=1e-6)
    assert res.to_dict()["drives"]["c"]["force_max_N"] == pytest.approx(F)
    # the load swings back behind the accelerating trolley: tan(theta) -> F / ((M+m) g)
    assert res.sway_max_deg[0] > np.degrees(np.arctan(F / (3000 * G)))


def test_slider_motor_runs_up_exponentially(tmp_path):
    """A trolley alone driven by a linear motor characteristic M = M_s (1 - n / n_s)
    through a gear i (n = i s'), rotor inertia J_r: (m + J_r i^2) s'' = i M_s (1 - i s'
    / n_s), so s' = v_inf (1 - exp(-t / tau)), v_inf = n_s / i, tau = (m + J_r i^2) n_s /
    (i^2 M_s). The trapezoidal rule's error on a linear decay is (h / tau)^2 / 12 per
    unit time: 1e-5 of v_inf asserted at tolerance 1e-8."""
    text = CART.replace("masses: {H: MLOAD}\n", "").replace(
        "ropes:\n  hoist: {EA: EAVAL, path: [K, H]}\n", "").replace(
        "  H: [0, 0, 10]\n", "")
    path = scene(tmp_path, text, "  duration: 6\n  tolerance: 1.0e-8\n  drives:\n"
                 "    c: {slider: travel, motor: {stall_torque: 40, synchronous_speed: "
                 "150}, gear_ratio: 50, rotor_inertia: 0.2}\n", MCART=1000, EAVAL=1)
    res = simulate(load(path))
    m = 1000 + 0.2 * 50**2
    v_inf, tau = 150 / 50, m * 150 / (50**2 * 40)
    t = res.times
    np.testing.assert_allclose(res.drive_speed[:, 0], v_inf * (1 - np.exp(-t / tau)),
                               atol=1e-5 * v_inf)
    s = v_inf * (t - tau * (1 - np.exp(-t / tau)))
    np.testing.assert_allclose(res.drive_position[:, 0], s, atol=1e-5 * s[-1])
    # the work is the trapezoidal sum of the motor's power: O(h^2) off the exact integral
    assert res.energy_error < 1e-5


LUFF = """cranefe: 1
name: jib on a hinge
plane: xz
nodes:
  A: [0, 0, 2]
  E: [20, 0, 2]
ground: []
bodies:
  jib: {mass: 3000, com: [8, 0, 2.5], inertia: 1.0e5, nodes: [A, E]}
joints:
  - {name: luff, type: hinge, bodies: [ground, jib], at: A, axis: [0, 1, 0]}
"""


def test_holding_torque_of_a_jib_and_its_free_fall(tmp_path):
    """A jib on a horizontal hinge (axis +y, com 8 m out and 0.5 m up): a turn phi about
    +y moves the com to z_c = -8 sin phi + 0.5 cos phi (lowers it), gravity's moment
    about +y is +8 m g, so the holding torque is -8 m g; a torque drive equal to it
    holds the jib at rest
    (|F| < 1e-9 m g); released (torque 0) the jib is a physical pendulum,
    J phi'' = m g (8 cos phi + 0.5 sin phi), whose energy J phi'^2 / 2 = -m g dz_c
    (J = I + m (8^2 + 0.5^2)) holds on the run to 2e-5 (output samples are cubic Hermite
    interpolants inside the steps; the step error at tolerance 1e-9)."""
    path = scene(tmp_path, LUFF, "  duration: 1\n  drives:\n    l: {hinge: luff, "
                 "torque: 0}\n")
    mech = mechanism(load(path))
    hold = float(mech.joint_hold[0])
    # R about +y by phi: x -> x cos + z sin, z -> -x sin + z cos: the com (8, 0.5)
    # relative to A goes down for phi > 0: gravity's moment about +y is +m g 8
    assert hold == pytest.approx(-3000 * G * 8, rel=1e-12)
    path = scene(tmp_path, LUFF, "  duration: 1\n  drives:\n    l: {hinge: luff, "
                 f"torque: {hold!r}}}\n")
    mech = mechanism(load(path))
    ev = mech.evaluate(0.0, mech.q0, np.zeros(mech.n), mech.taut0)
    assert np.abs(ev.F).max() < 1e-9 * 3000 * G
    path = scene(tmp_path, LUFF, "  duration: 1.5\n  tolerance: 1.0e-9\n  drives:\n"
                 "    l: {hinge: luff, torque: 0}\n")
    res = simulate(load(path))
    phi = res.drive_position[:, 0]
    J = 1.0e5 + 3000 * (8**2 + 0.5**2)
    # energy: J phi'^2 / 2 = m g (z_c(0) - z_c(phi)), z_c - 2 = -8 sin phi + 0.5 cos phi
    dz = (-8 * np.sin(phi) + 0.5 * np.cos(phi)) - 0.5
    np.testing.assert_allclose(0.5 * J * res.drive_speed[:, 0]**2, -3000 * G * dz,
                               rtol=2e-5, atol=1e-9 * 3000 * G)
    assert phi[-1] > 0.5
    # the trapezoidal rule does not keep a nonlinear pendulum's energy exactly: the error
    # shrinks as the steps (~tolerance^(1/3)) squared, ~4.6x per decade of tolerance
    assert res.energy_error < 2e-6
    fine = simulate(load(scene(tmp_path, LUFF, "  duration: 1.5\n  tolerance: 1.0e-10\n"
                               "  drives:\n    l: {hinge: luff, torque: 0}\n")))
    assert fine.energy_error < res.energy_error / 3


def test_bad_joint_drives(tmp_path, capsys):
    """A force on a hinge, free on a drum, a gear on a profile drive, a free joint no
    rope holds: exit 2 naming the scene file and the entry. (A joint coordinate with a
    moving joint below it and sway off with a load guided by such a body are solved:
    tests/test_operation_joint_chain.py.)"""
    cases = [
        (SLEW, "{hinge: slew, force: 5}", "analysis.drives.d.force"),
        (SLEW, "{hinge: slew, profile: {type: table, speed: [[0, 0.1]]}, gear_ratio: 3}",
         "analysis.drives.d.gear_ratio"),
        (SLEW, "{hinge: slew, torque: 5, ramp: -1}", "analysis.drives.d.ramp"),
        (SLEW, "{linear: nope, profile: {type: table, speed: [[0, 0.1]]}}",
         "analysis.drives.d.linear"),
        (CYLINDER, "{linear: cyl, force: 5}", "analysis.drives.d.force"),
    ]
    for text, drive, entry in cases:
        path = scene(tmp_path, text, f"  duration: 5\n  drives:\n    d: {drive}\n")
        assert main(["simulate", str(path)]) == 2
        err = capsys.readouterr().err
        assert entry in err and "scene.yaml" in err, err
    # a free jib that no rope holds: not a static state
    path = scene(tmp_path, LUFF, "  duration: 5\n  drives:\n    d: {hinge: luff, "
                 "free: true}\n")
    assert main(["simulate", str(path)]) == 2
    err = capsys.readouterr().err
    assert "analysis.drives.d" in err and "not a static equilibrium" in err, err


# ----------------------------------------------------------------- luffing by rope

LUFFING = str(Path(__file__).resolve().parents[1] / "models" / "operations" /
              "luffing_crane.yaml")
F_PIN, C_HEAD, CH_HEAD, WL = (np.array([1.0, 42.0 * 0 + 30.0]), np.array([-0.5, 42.0]),
                              np.array([0.0, 41.0]), np.array([-2.0, 1.5]))
B0 = np.array([22.2132034, 51.2132034])
COM0 = np.array([10.8994949, 39.8994949])
M_BOOM, M_HOOK = 4500.0, 6000.0


def _turn(x, phi):
    """A point of the boom turned by phi about +y through the foot F (x, z):
    x' = x cos + z sin, z' = -x sin + z cos (relative to F)."""
    r = x - F_PIN
    return F_PIN + np.array([r[0] * np.cos(phi) + r[1] * np.sin(phi),
                             -r[0] * np.sin(phi) + r[1] * np.cos(phi)])


def _moment(r, f):
    """y component of r x f in the xz plane: r_z f_x - r_x f_z."""
    return r[1] * f[0] - r[0] * f[1]


def _luffing_tension(phi, hoist=True):
    """Moment balance of the boom about its foot F at angle phi: the weight at the com,
    the hoist rope at the tip (S_h = m g / 2 towards the tower-head sheave CH and 2 S_h
    down to the hook), and 6 falls of the luffing rope towards the tower head C."""
    B, com = _turn(B0, phi), _turn(COM0, phi)
    Sh = M_HOOK * G / 2 if hoist else 0.0
    u_h = (CH_HEAD - B) / np.linalg.norm(CH_HEAD - B)
    m = _moment(com - F_PIN, [0, -M_BOOM * G]) + _moment(B - F_PIN, Sh * u_h) + \
        _moment(B - F_PIN, [0, -2 * Sh])
    u_l = (C_HEAD - B) / np.linalg.norm(C_HEAD - B)
    return -m / (6 * _moment(B - F_PIN, u_l))


def _luffing_length(phi):
    return np.linalg.norm(C_HEAD - WL) + 6 * np.linalg.norm(C_HEAD - _turn(B0, phi)) + 3.0


def _luff_scene(tmp_path, drives, effects="{}", extra="", psi=None, hoist=True):
    text = Path(LUFFING).read_text()
    if not hoist:                       # the boom on its luffing rope alone
        i = text.index("  hoist_rope:")
        text = text[:i].replace("masses:\n  HOOK: 6000\n", "")
    if psi is not None:
        text = text.replace("psi: 0.20", f"psi: {psi}")
    (tmp_path / "luffing_crane.yaml").write_text(text)
    path = tmp_path / "luff.yaml"
    path.write_text(f"cranefe: 1\nscene: t\nmodel: luffing_crane.yaml\neffects: {effects}\n"
                    f"analysis:\n  type: operation\n{extra}  drives:\n{drives}")
    return path


def test_luffing_rope_tension_is_the_moment_balance(tmp_path):
    """The static state with the boom free on its hinge: the luffing rope's tension is
    the hand moment balance about the foot (22 kN per fall at 45 deg), the hoist rope's
    m g / 2, and every generalised force vanishes there (the boom hangs at rest)."""
    path = _luff_scene(tmp_path, "    boom: {hinge: luffing, free: true}\n",
                       extra="  duration: 1\n")
    mech = mechanism(load(path))
    np.testing.assert_allclose(mech.S0, [_luffing_tension(0.0), M_HOOK * G / 2],
                               rtol=1e-8)
    ev = mech.evaluate(0.0, mech.q0, np.zeros(mech.n), mech.taut0)
    assert np.abs(ev.F).max() < 1e-9 * M_HOOK * G


def test_luffing_small_oscillations_equal_the_linear_core(tmp_path):
    """Linearised at the static state (luffing and hoist drums held) the engine's tangent
    and mass give `cranefe modes`' frequencies of the same model: the load's pendulum,
    the boom rocking on its elastic luffing tackle (with the hoist rope's share), the
    load bouncing on its falls. Both are exact linearisations of the same mechanics
    (Hencky ropes with tangent EA/L, the boom's gravity load stiffness, the ropes'
    tension stiffness at the boom's turning tip): equal to 1e-9. (With sway off the
    linear core drops every tension and gravity load stiffness, the engine only the
    load's swing: the boom's large-motion mechanics stay exact, so they differ.)"""
    from cranefe.analysis.modal import modes
    path = _luff_scene(tmp_path, "    boom: {hinge: luffing, free: true}\n",
                       extra="  duration: 1\n")
    model = load(path)
    mech = mechanism(model)
    ev = mech.evaluate(0.0, mech.q0, np.zeros(mech.n), mech.taut0)
    w = np.sort(np.sqrt(np.abs(sla.eigvals(ev.K, np.diag(mech.M)).real)))
    lin = np.sort(modes(model.with_effects(drive="held")).omega)
    assert len(w) == len(lin) == 3
    np.testing.assert_allclose(w, lin, rtol=1e-9)


def test_luffing_by_rope_settles_at_the_moment_balance_angle(tmp_path):
    """The luffing drum pays out 2 m of rope (10 rad at 0.2 m) and the boom, free on its
    hinge, sinks to the angle phi where the moment balance holds with the elastic rope:
    6 S(phi) arm(phi) = moments of weight and hoist rope, S(phi) = EA ln(L(phi) / L0),
    L0 = L0_ref + 2 m / lambda_ref (found by Brent's method). The boom alone on its
    tackle (no hook: a swinging load is undamped) with strong rope damping (psi = 2)
    settles in 25 s: to 1e-7 rad."""
    from scipy.optimize import brentq
    path = _luff_scene(tmp_path, "    boom: {hinge: luffing, free: true}\n"
                       "    luff: {drum: luffing, profile: {type: trapezoid, distance: -10,"
                       " v_max: 2, a_max: 2}}\n", effects="{damping: exact}",
                       extra="  duration: 25\n  tolerance: 1.0e-9\n", psi=2.0, hoist=False)
    res = simulate(load(path))
    EA = 3.0e7
    S0 = _luffing_tension(0.0, hoist=False)
    lam = np.exp(S0 / EA)
    L0 = _luffing_length(0.0) / lam + 0.2 * 10 / lam
    phi = brentq(lambda p: EA * np.log(_luffing_length(p) / L0) -
                 _luffing_tension(p, hoist=False), -0.2, 0.2)
    assert phi > 0.02                          # the boom went down by 1.63 deg
    assert res.drive_position[-1, 0] == pytest.approx(phi, abs=1e-7)
    assert res.energy_error < 1e-6


def test_luffing_boom_released_keeps_its_energy(tmp_path):
    """No drives, no damping: the boom released 1e-4 rad from its static angle rocks on
    the luffing rope (1.4 and 4.4 Hz with the hoist rope) with the load swinging; the
    energy (boom's kinetic and potential, the load's, the ropes' elastic) is kept to the
    integrator's accuracy: < 1e-8 of the largest term at tolerances 1e-8 and 1e-9 over
    2 s (measured 1e-10 and 2e-10: at this level the balance is set by the Newton
    tolerance and round-off, not by the step, so it does not fall further)."""
    errs = []
    for tol in (1e-8, 1e-9):
        path = _luff_scene(tmp_path, "    boom: {hinge: luffing, free: true}\n",
                           extra=f"  duration: 2\n  tolerance: {tol}\n")
        model = load(path)
        mech = mechanism(model)
        q = mech.q0.copy()
        q[mech.nc] += 1e-4 * mech.jc[0]["rho"]
        res = simulate(model, initial={"q": q, "v": np.zeros(mech.n)})
        assert res.energy["kinetic_final"] > 1.0          # it moves
        errs.append(res.energy_error)
    assert max(errs) < 1e-8


BY_ROPE = Path(LUFFING).parent / "luffing_crane_by_rope.yaml"


@pytest.fixture(scope="module")
def by_rope():
    """The 40 s run of luffing_crane_by_rope.yaml (5.5 s), made once for the example's
    test and the animation's."""
    model = load(str(BY_ROPE))
    return model, simulate(model)


def _by_rope_cut(tmp_path, seconds):
    """The example's scene text with its duration cut to `seconds`, in tmp_path."""
    text = BY_ROPE.read_text()
    assert text.count("  duration: 40\n") == 1
    short = tmp_path / "luffing_crane_by_rope.yaml"
    short.write_text(text.replace("  duration: 40\n", f"  duration: {seconds}\n").replace(
        "model: luffing_crane.yaml", f"model: {Path(LUFFING)}"))
    return short


def test_luffing_by_rope_example(tmp_path, capsys, by_rope):
    """models/operations/luffing_crane_by_rope.yaml: the boom raised by its luffing rope
    from 45 deg to the angle where the rope hauled in (15 m) fits the tackle's geometry,
    L(phi) = L(0) - 15 m (to the rope's stretch change, ~1e-3 of the angle); the load
    swings; the energy balance closes (measured: the angle 1.35e-3 from phi_geo at 40 s,
    1.7e-3 at 20 s while the boom still swings, hence the full 40 s; energy 3.8e-8).
    The command line runs the same scene text cut to 2 s (the full 40 s a second time
    cost 10 s of the test's 16 s) and its JSON document's steps, peak rope forces, energy error and drives equal
    those of the 2 s run's to_dict()."""
    import json
    from scipy.optimize import brentq
    res = by_rope[1]
    phi_geo = brentq(lambda p: _luffing_length(p) - (_luffing_length(0.0) - 15.0), -0.5, 0)
    assert res.drive_position[-1, 0] == pytest.approx(phi_geo, rel=2e-3)
    assert res.sway_max_deg[0] > 0.5
    assert res.energy_error < 1e-5
    short = _by_rope_cut(tmp_path, 2)
    capsys.readouterr()
    assert main(["simulate", str(short), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    ref = simulate(load(str(short))).to_dict()
    assert doc["duration_s"] == 2.0 == ref["duration_s"]
    for key in ("steps", "rope_force_max_N", "energy_error", "drives"):
        assert doc[key] == ref[key], key


def test_csv_body_columns_follow_a_joint_coordinate(tmp_path, capsys):
    """The boom of luffing_crane_by_rope.yaml is a joint coordinate (free hinge): the
    CSV's body_boom columns turn with it (audit: they stayed at the reference pose).
    Planar: its rotation vector is the hinge's turn, |ry| = |boom.position| (to the
    CSV's digits), and its com moves on a circle about the hinge, so the chord from
    the start over 2 |sin(phi / 2)| is one radius at every row. The example's first 12 s
    (the boom turned by up to 0.147 rad, asserted > 0.1; the whole 40 s cost 9 s)."""
    import csv
    path = _by_rope_cut(tmp_path, 12)
    out = tmp_path / "boom.csv"
    assert main(["simulate", str(path), "--csv", str(out)]) == 0
    rows = list(csv.DictReader(out.open()))
    phi = np.array([float(r["boom.position"]) for r in rows])
    ry = np.array([float(r["body_boom.ry_rad"]) for r in rows])
    com = np.array([[float(r[f"body_boom.{a}_m"]) for a in "xyz"] for r in rows])
    assert abs(phi).max() > 0.1
    np.testing.assert_allclose(np.abs(ry), np.abs(phi), atol=1e-6)
    moved = np.abs(phi) > 0.02
    radius = np.linalg.norm(com[moved] - com[0], axis=1) / (2 * np.abs(np.sin(phi[moved] / 2)))
    assert radius.max() - radius.min() < 1e-4 * radius.mean()


# ----------------------------------------------------------------- luffing by a linear drive

CYLINDER = """cranefe: 1
name: boom luffed by a cylinder
plane: xz
nodes:
  O: [0, 0, 0]
  A: [4, 0, 0]
  C: [3, 0, 4]
  B: [8, 0, 8]
  H: [8, 0, 0]
ground: [O, A]
masses: {H: 1000}
bodies:
  boom: {mass: 2000, com: [4, 0, 4], inertia: 2.0e4, nodes: [O, C, B]}
joints:
  - {name: foot, type: hinge, bodies: [ground, boom], at: O, axis: [0, 1, 0]}
linear_drives:
  cyl: {nodes: [A, C], pinion_radius: 0.1, gear_ratio: 10}
ropes:
  hoist: {EA: 1.0e6, path: [B, H]}
"""


def test_cylinder_luffing_follows_the_law_of_cosines(tmp_path):
    """A boom hinged at O, a cylinder from A (ground) to C (boom) lengthened by 1 m on a
    trapezoid: the angle at O between OA and OC obeys d^2 = a^2 + c^2 - 2 a c cos(gamma),
    so the boom turns by gamma(t) - gamma_ref (the tip B turned about O): the engine's
    kinematic nodes to 1e-10 m; their velocities and accelerations equal the central
    differences of the positions (to the differences' own error, 1e-6); the load
    swings below the tip and the energy balance closes (< 1e-6: measured 1.4e-7 at
    tolerance 1e-7, 3.2e-8 at 1e-8). 7.5 s (the move ends at 7 s) at tolerance 1e-7
    instead of 9 s at 1e-8: 888 steps instead of 2206."""
    path = scene(tmp_path, CYLINDER, "  duration: 7.5\n  tolerance: 1.0e-7\n  drives:\n"
                 "    c: {linear: cyl, profile: {type: trapezoid, distance: 1.0, v_max: 0.2,"
                 " a_max: 0.1}}\n")
    model = load(path)
    mech = mechanism(model)
    a, c = 4.0, 5.0
    gamma_ref = np.arctan2(4, 3)
    d_ref = np.hypot(1, 4)
    motion = mech.spec.drives[0].motion
    idx = model.node_index
    for t in (0.0, 1.3, 3.7, 6.1, 9.7):             # away from the kinks 2, 5, 7 s
        d = d_ref + motion(t)[0]
        gamma = np.arccos((a * a + c * c - d * d) / (2 * a * c))
        turn = gamma - gamma_ref                      # OC turns away from OA: up, about -y
        X, V, A, _ = mech.kinematics(t)
        B = np.array([8 * np.cos(turn) - 8 * np.sin(turn), 0,
                      8 * np.sin(turn) + 8 * np.cos(turn)])
        np.testing.assert_allclose(X[idx["B"]], B, atol=1e-10)
        assert np.linalg.norm(X[idx["C"]] - X[idx["A"]]) == pytest.approx(d, abs=1e-10)
        h = 1e-4
        Xp, Xm = mech.kinematics(t + h)[0], mech.kinematics(t - h)[0] if t > 0 else None
        if Xm is not None:
            np.testing.assert_allclose(V, (Xp - Xm) / (2 * h), atol=1e-6)
            np.testing.assert_allclose(A, (Xp - 2 * X + Xm) / h**2, atol=1e-5)
    res = simulate(model)
    assert res.drive_position[-1, 0] == pytest.approx(1.0, abs=1e-12)
    assert res.sway_max_deg[0] > 0.1
    assert res.energy_error < 1e-6


def test_portal_crane_luffed_by_its_rack_equals_the_luffing_kinematics(tmp_path):
    """The portal crane's four-bar level-luffing linkage (models/portal_crane_luffing.yaml)
    moved by its rack (linear drive A-C) lengthened 0.6 m (the boom down by ~9 deg):
    at every time the boom angle
    alpha of the engine makes the rack's length d_ref + s(t) (to 1e-10 m), and the
    counterweight W on its rocker sits where the luffing analysis' kinematics
    (`Linkage.state`) puts it at that alpha, alpha found independently by Brent's method
    on the rack length (1e-9 m). 4.5 s (the move ends at 4 s) instead of 6 s: each step
    solves the linkage, 0.75 of the steps."""
    from scipy.optimize import brentq
    from cranefe.analysis.luffing.kinematics import Linkage
    portal = Path(__file__).resolve().parents[1] / "models" / "portal_crane_luffing.yaml"
    path = tmp_path / "s.yaml"
    path.write_text(f"cranefe: 1\nscene: t\nmodel: {portal}\nanalysis:\n  type: operation\n"
                    "  duration: 4.5\n  output_step: 0.25\n  drives:\n    luff: {linear: luffing,"
                    " profile: {type: trapezoid, distance: 0.6, v_max: 0.2, a_max: 0.2}}\n")
    model = load(str(path))
    res = simulate(model)
    link = Linkage(model, "boom", "O", "B")
    idx = model.node_index
    A, C = idx["A"], idx["C"]
    d_ref = np.linalg.norm(model.coords[C] - model.coords[A])
    boom = [b.name for b in model.bodies].index("boom")

    def length(alpha):
        st = link.state([alpha])
        XC = link._point(st.q, boom, C)[0][0]
        return np.linalg.norm(XC - model.coords[A][[0, 2]])

    motion = parse(model).drives[0].motion
    k = res.mass_names.index("W")
    rocker = [b.name for b in model.bodies].index("rocker")
    for i in range(0, len(res.times), 3):
        t = res.times[i]
        target = d_ref + motion(t)[0]
        alpha = brentq(lambda x: length(x) - target, link.alpha_ref - 0.35,
                       link.alpha_ref + 0.1, xtol=1e-14)
        st = link.state([alpha])
        W = link._point(st.q, rocker, idx["W"])[0][0]
        np.testing.assert_allclose(res.mass_position[i, k][[0, 2]], W, atol=1e-9)
    assert res.drive_position[-1, 0] == pytest.approx(0.6, abs=1e-12)


RADIAL = """cranefe: 1
name: trolley free on a slewing jib
nodes:
  O: [0, 0, 0]
  T: [0, 0, 30]
  K: [10, 0, 30]
ground: [O]
bodies:
  jib: {mass: 5000, com: [10, 0, 30], inertia: [1.0e3, 1.0e5, 1.0e5], nodes: [O, T]}
  trolley: {mass: 500, com: [10, 0, 30.5], inertia: [10, 20, 30], nodes: [K]}
joints:
  - {name: slew, type: hinge, bodies: [ground, jib], at: O, axis: [0, 0, 1]}
  - {name: travel, type: slider, bodies: [jib, trolley], at: K, axis: [1, 0, 0],
     range: [-2, 40]}
"""


def test_free_trolley_on_a_slewing_jib_runs_out_by_the_centrifugal_force(tmp_path):
    """The jib slews at a prescribed constant w from t = 0 and the trolley is free on its
    slider (force 0): in the turning frame r'' = w^2 r (the Coriolis force is taken by
    the slider), so from rest at r0 = 10 m, r = r0 cosh(w t) - the carried acceleration
    of a prescribed parent in Kane's term. To 1e-6 of the run-out at tolerance 1e-10
    (the trapezoidal rule's error on an exponential (w h)^2/12 per unit w t); the
    energy balance, with the work of the prescribed slewing on the trolley
    int (x'' - g) . v_p dm, closes to 1e-6."""
    w = 0.3
    path = scene(tmp_path, RADIAL, "  duration: 5\n  tolerance: 1.0e-10\n  drives:\n"
                 f"    s: {{hinge: slew, profile: {{type: table, speed: [[0, {w}]]}}}}\n"
                 "    t: {slider: travel, force: 0}\n")
    res = simulate(load(path))
    k = res.drive_names.index("t")
    t = res.times
    run = 10 * (np.cosh(w * t) - 1)
    np.testing.assert_allclose(res.drive_position[:, k], run, atol=1e-6 * run[-1])
    np.testing.assert_allclose(res.drive_speed[:, k], 10 * w * np.sinh(w * t),
                               atol=1e-6 * 10 * w * np.sinh(w * t[-1]))
    assert res.energy_error < 1e-6


def test_slewing_torque_ramp(tmp_path):
    """A torque ramped up over r = 2 s (ramp: 2) then constant: J phi'' = M t / r, so
    phi = M t^3 / (6 J r) up to r and M / J (r^2/6 + r (t - r)/2 + (t - r)^2/2) after
    (a step ends at the ramp's kink). The trapezoidal rule is exact for a constant
    acceleration, not for a growing one: each step errs by h^2/12 (a1 - a0) (the error
    control keeps it below tolerance x size, 2e-8 m of arc at the 20 m radius here) and
    the errors add up over the ramp's steps: 1e-5 of the final angle asserted
    (measured 1.1e-6)."""
    path = scene(tmp_path, SLEW, "  duration: 6\n  tolerance: 1.0e-9\n  drives:\n"
                 "    s: {hinge: slew, torque: 3000, ramp: 2}\n")
    res = simulate(load(path))
    J = 1.0e4 + 2000 * 5**2 + 500 * 20**2
    t, r, M = res.times, 2.0, 3000.0
    phi = np.where(t < r, M * t**3 / (6 * J * r),
                   M / J * (r**2 / 6 + r * (t - r) / 2 + (t - r)**2 / 2))
    np.testing.assert_allclose(res.drive_position[:, 0], phi, atol=1e-5 * phi[-1])
    assert res.drive_torque[-1, 0] == pytest.approx(M)


def test_trolley_pushed_past_its_range_stops_the_run(tmp_path, capsys):
    """A constant force pushes the trolley (range [-1, 2] m) past its end (the centre of
    mass F t^2 / (2 (M + m)) reaches 2 m at 3.5 s, the trolley a little earlier): the
    engine has no end stops, so the run stops there with AnalysisError naming the time
    and the joint (exit 1), the results up to then kept (CSV written)."""
    text = CART.replace("range: [-50, 50]", "range: [-1, 2]")
    path = scene(tmp_path, text, "  duration: 10\n  drives:\n    c: {slider: travel, "
                 "force: 1000}\n", MLOAD=2000, MCART=1000, EAVAL=1.0e8)
    csv = tmp_path / "run.csv"
    assert main(["simulate", str(path), "--csv", str(csv)]) == 1
    err = capsys.readouterr().err
    assert "past the end of its range" in err and "travel" in err, err
    rows = csv.read_text().splitlines()
    t_end = float(rows[-1].split(",")[0])
    assert 2.0 < t_end < 6.0


def test_animation_frames_follow_a_joint_coordinate(by_rope):
    """The animation's positions (outputs/movie.py) of luffing_crane_by_rope.yaml: the
    boom's tip node B turns with the free hinge the run computed (audit: the frames
    drew the boom at its reference pose), on its circle about the hinge: its chord
    from the start is 2 r |sin(phi / 2)| with r its distance from the boom's com's
    circle centre, checked as the ratio of B's chord to the com's (both on one rigid
    body turning about one axis: r_B / r_com at every frame). The run: the module's
    by_rope fixture."""
    from cranefe.outputs.movie import operation_positions
    model, res = by_rope
    idx, P = operation_positions(model, res, frames=6)
    b, nn = model.node_index["B"], len(model.node_names)
    com = nn + [x.name for x in model.bodies].index("boom")
    chord_b = np.linalg.norm(P[1:, b] - P[0, b], axis=1)
    chord_c = np.linalg.norm(P[1:, com] - P[0, com], axis=1)
    assert chord_b.min() > 0.5
    ratio = chord_b / chord_c
    assert ratio.max() - ratio.min() < 1e-9 * ratio.mean()
