"""Kill tests for cranefe/analysis/loads/analysis.py (tools/mutation.py loads_analysis;
docs/mutation.md, its section): the configurations the first kill tests
(tests/test_mutation_kills_loads_analysis.py) build no model for, each small and its
values derived by hand:

- `only=["phi5"]` (every drive's phi5) and `only=[the hoist drum]` on a model with a
  slider move;
- every run's warnings kept, in run order (a hoist start that warns before a release
  that warns otherwise);
- the model's and the scene's names in the result and its document;
- a rope with no static force listed first (a tag line) beside a hoist rope whose static
  force is below 1 N (a 0.1 kg load);
- phi5 of a luffing hinge away from the origin with the jib inclined (the tangent of the
  tip's circle not horizontal), and of a slew through 60 deg about an axis away from
  the origin (the tangent turning with the jib);
- phi1 of an arm carrying a 0.5 kg point mass, a 0.5 kg body and a massless body.
"""

import functools
import itertools

import numpy as np
import pytest
from test_mutation_kills_loads_analysis import CART  # the cart with a hoist drum

import cranefe

G = 9.81


# ----------------------------------------------------------- only= with a joint move


def test_only_phi5_runs_every_drive_and_the_hoist_drum_its_own(tmp_path):
    """only = [phi5] on a crane with a slider move: phi5 of the hoist start and of the
    travel move, nothing else; only = [hoist]: the start alone (no move). The travel:
    a trapezoid (jerk time 0) whose ramp is one pendulum period 2 pi / w (w = sqrt(g /
    l), l = 10 m) leaves no swing: the horizontal force on the load peaks at 2 m a in
    the linear limit (docs/loads.md; tolerance 1e-3 as the slider test of
    test_mutation_kills_loads_analysis.py: the exact pendulum at 0.5 deg, second
    differences of positions stored every 0.01 s; measured there 1e-4). after_lift_off
    0.1 s: the hoist start (in both calls; its stiff rope's 7469 steps took 8 s of the
    first call's 10.5 s) ends 0.1 s after its 1 s ramp instead of 3 s (2054 steps; its
    phi5, 1.0577, the same to 5e-9: the peak is in the ramp); the travel move keeps its
    23.2 s."""
    (tmp_path / "cart.yaml").write_text(CART)
    w = np.sqrt(G / 10.0)
    ramp = float(2 * np.pi / w)
    path = tmp_path / "s.yaml"
    path.write_text("cranefe: 1\nscene: t\nmodel: cart.yaml\nanalysis:\n  type: loads\n"
                    "  hoist: {speed: 0.2}\n  tolerance: 1.0e-9\n  after_lift_off: 0.1\n"
                    "  drives:\n"
                    f"    travel: {{v_max: 0.5, ramp: {ramp!r}, jerk_time: 0, "
                    "distance: 6.0}\n")
    r = cranefe.loads(str(path), only=["phi5"])
    assert set(r.factors) == {"phi5"} and set(r.factors["phi5"]) == {"hoist", "travel"}
    assert [t.name for t in r.simulations] == ["hoist start", "travel move"]
    p = r.factors["phi5"]["travel"]
    assert p["value"] == pytest.approx(2.0, rel=1e-3)
    assert p["acceleration"] == pytest.approx(0.5 / ramp, rel=1e-12)
    r = cranefe.loads(str(path), only=["hoist"])
    assert set(r.factors) == {"phi5"} and set(r.factors["phi5"]) == {"hoist"}
    assert [t.name for t in r.simulations] == ["hoist start"]


# ------------------------------------------------------------------ warnings, names

ANCHORED = """cranefe: 1
name: a load held down by a rope to the ground
plane: xz
nodes: {D: [0, 0, 0], S: [0, 0, 30], H: [0, 0, 10], A: [0, 0, 5]}
ground: [D, S, A]
masses: {H: 5000.0}
drums:
  hoist: {node: D, radius: 0.25, inertia: 500.0, brake: false}
ropes:
  hoist_rope: {EA: 3.15e6, path: [hoist, S, {node: H, falls: 2}]}
  anchor: {EA: 1.0e5, path: [H, A]}
"""

SCENE = """cranefe: 1
scene: {scene}
model: {model}
analysis:
  type: loads
  hoist: {{drum: hoist, load: H, speed: 0.5, creep: 0.125, ramp: 1.0, jerk_time: 0}}
  release: {{fraction: 0.25, time: 0}}
  after_lift_off: 0.6
  time_step: 0.01
"""


def test_every_runs_warnings_are_kept(tmp_path):
    """A 5 t load on 2 falls of the hoist rope (k1 = EA / 70 m = 45 000 N/m, 4 k1 at H)
    and on a rope down to the ground (k2 = 1e5 / 5 m = 20 000 N/m): at rest H sinks by
    m g / (4 k1 + k2) = 0.24525 m, which pushes the lower rope by k2 x that = 4905 N
    (compression). The hoist start (direct integration) warns that 1 rope element starts
    slack; the release (modal, the last run) does not, but its lower rope's force falls
    to -k2 (m' g + 2 dm g) / (4 k1 + k2) = -6131 N (m' = 3750 kg, dm = 1250 kg released
    at once: twice the static step), below zero: its own warning. The result keeps both,
    in run order (the modal run's `modes:` note is left out)."""
    (tmp_path / "m.yaml").write_text(ANCHORED)
    path = tmp_path / "s.yaml"
    path.write_text(SCENE.format(scene="anchored", model="m.yaml"))
    r = cranefe.loads(str(path), only=["hoist", "phi3"])
    assert [t.name for t in r.simulations] == ["hoist start", "release"]
    k1, k2 = 3.15e6 / 70, 1.0e5 / 5
    low = -k2 * (3750 * G + 2 * 1250 * G) / (4 * k1 + k2)
    assert f"{low:.4g}" == "-6131"
    assert r.warnings == (
        "1 rope element(s) start in compression, i.e. slack",
        (f"a rope's force fell to {low:.4g} N: it would go slack, which modal "
         "superposition (linear) does not follow; use method: direct"))
    assert r.to_dict()["warnings"] == list(r.warnings)


LIGHT = """cranefe: 1
name: a light load with a tag line
plane: xz
nodes: {D: [0, 0, 0], S: [0, 0, 30], H: [0, 0, 10], W: [5, 0, 10]}
ground: [D, S, W]
masses: {H: 0.1}
drums:
  hoist: {node: D, radius: 0.25, inertia: 0.01, brake: false}
ropes:
  tag: {EA: 1.0, path: [W, H]}
  hoist_rope: {EA: 63.0, path: [hoist, S, {node: H, falls: 2}]}
"""


def test_a_light_load_and_a_rope_with_no_static_force(tmp_path):
    """A 0.1 kg load on 2 falls (k = EA / 70 m = 0.9 N/m: w^2 = n^2 k / m = 36, the
    single mass of test_mutation_kills_loads_analysis.py scaled down), so the hoist
    rope's static force is m g / 2 = 0.49 N; a horizontal tag line listed first carries
    nothing (0 N at rest, and nothing to first order in the vertical lift). The factors
    are the hoist rope's: phi2 = 1 + v w / g at full speed (HD1), phi5 = 2 for a step of
    hook acceleration, phi3 = 1 - 2 dm/m for a sudden release (tolerance 1e-4: the
    trapezoidal rule at w h = 0.06, as there). The result names the model, the scene
    and its file."""
    (tmp_path / "m.yaml").write_text(LIGHT)
    path = tmp_path / "s.yaml"
    path.write_text(SCENE.format(scene="light load", model="m.yaml"))
    r = cranefe.loads(str(path), only=["phi2", "hoist", "phi3"])
    assert [t.name for t in r.simulations] == ["lift-off 0.5 m/s", "hoist start",
                                                "release"]
    f = r.factors
    assert f["phi2"]["value"] == pytest.approx(1 + 0.5 * 6.0 / G, rel=1e-4)
    assert f["phi2"]["rope"] == f["phi2"]["curve"][0]["rope"] == "hoist_rope"
    assert f["phi5"]["hoist"]["value"] == pytest.approx(2.0, rel=1e-4)
    assert f["phi5"]["hoist"]["rope"] == "hoist_rope"
    # braking mirrors the start: S0 (1 - 2 a / g) = 0.44 N, low but not slack
    assert f["phi5"]["hoist"]["braking"]["lowest_force_N"] == pytest.approx(
        0.1 * G / 2 * (1 - 2 * 0.5 / G), rel=1e-4)
    assert f["phi5"]["hoist"]["braking"]["slack"] is False
    assert f["phi5"]["hoist"]["rigid_body_force_N"] == pytest.approx(
        0.1 * G / 2 * 0.5 / G, rel=1e-12)
    assert f["phi3"]["value"] == pytest.approx(1 - 2 * 0.25, abs=1e-4)
    assert f["phi3"]["rope"] == "hoist_rope"
    assert r.warnings == ()
    assert r.model_name == "a light load with a tag line" and r.scene == "light load"
    assert r.file == str(path)
    doc = r.to_dict()
    assert doc["model"] == "a light load with a tag line" and doc["scene"] == "light load"
    assert r.table().startswith("light load: dynamic factors")


# ----------------------------------------------------- phi5 of an inclined luffing jib

C = np.array([2.0, 0.0, 3.0])                    # the hinge, away from the origin
JIB, THETA0, ROPE = 20.0, np.radians(60.0), 10.0
TIP = C + JIB * np.array([np.cos(THETA0), 0.0, np.sin(THETA0)])
LUFF = f"""cranefe: 1
name: a jib inclined at 60 deg luffing on a hinge at (2, 0, 3)
nodes:
  O:   {C.tolist()}
  TIP: {TIP.tolist()}
  D:   [1.0, 0.0, 3.5]
  S:   {((C + TIP) / 2).tolist()}
  L:   {(TIP - [0.0, 0.0, ROPE]).tolist()}
ground: [O]
masses:
  L: 2000
bodies:
  jib: {{mass: 3000, com: {((C + TIP) / 2).tolist()}, inertia: [1.0e3, 1.0e5, 1.0e5],
        nodes: [TIP, D, S]}}
joints:
  - {{name: luffing, type: hinge, bodies: [ground, jib], at: O, axis: [0, 1, 0]}}
springs:
  - {{name: luffing_gear, type: rotational, bodies: [ground, jib], at: O,
     axis: [0, 1, 0], stiffness: 1.0e9}}
drums:
  hoist: {{node: D, radius: 0.2, inertia: 5.0, brake: false, rope_reserve: 20.0,
          motor: {{rotor_inertia: 0.05, gear_ratio: 30}}}}
ropes:
  hoist_rope: {{EA: 5.0e7, path: [hoist, S, TIP, L]}}
  tie: {{EA: 1.0e6, path: [D, {{node: S, falls: 2}}]}}
"""


def luffing_reference(omega, ramp, distance, duration):
    """Peak horizontal force / m on the load (m/s^2) under the tip of the jib luffed by
    the trapezoid angle p(t) (angular acceleration alpha = omega / ramp over `ramp`,
    `distance` rad in all, about +y: the tip at angle THETA0 - p above the horizontal):
    x_tip = C_x + JIB cos(THETA0 - p), z_tip = C_z + JIB sin(THETA0 - p) exactly; the
    load a pendulum of length ROPE in the linear limit with the tip's vertical
    acceleration added to g: u'' = (g + z_tip'') (x_tip - u) / ROPE, from rest below the
    tip. DOP853 to 1e-11 piece by piece between the profile's corners."""
    from scipy.integrate import solve_ivp
    alpha = omega / ramp
    t_cruise = distance / omega - ramp              # the trapezoid: ramp, cruise, ramp
    corners = [0.0, ramp, ramp + t_cruise, 2 * ramp + t_cruise, duration]

    def angle(t):                                   # (p, p', p'')
        if t <= corners[1]:
            return 0.5 * alpha * t * t, alpha * t, alpha
        if t <= corners[2]:
            s = t - ramp
            return 0.5 * alpha * ramp ** 2 + omega * s, omega, 0.0
        if t <= corners[3]:
            s = t - corners[2]
            return distance - 0.5 * alpha * (ramp - s) ** 2, omega - alpha * s, -alpha
        return distance, 0.0, 0.0

    def tip(t):                                     # x, z'' and x'' of the tip
        p, dp, ddp = angle(t)
        th = THETA0 - p
        x = C[0] + JIB * np.cos(th)
        ddx = JIB * (np.sin(th) * ddp - np.cos(th) * dp ** 2)
        ddz = JIB * (-np.cos(th) * ddp - np.sin(th) * dp ** 2)
        return x, ddz, ddx

    def rhs(t, y):
        x, ddz, _ = tip(t)
        return [y[1], (G + ddz) * (x - y[0]) / ROPE]

    y0, peak = [TIP[0], 0.0], 0.0
    for a, b in itertools.pairwise(corners):
        sol = solve_ivp(rhs, (a, b), y0, method="DOP853", rtol=1e-11, atol=1e-12,
                        dense_output=True)
        t = np.linspace(a, b, max(2, int((b - a) * 1000)))
        u = sol.sol(t)[0]
        acc = np.array([(G + tip(s)[1]) * (tip(s)[0] - v) / ROPE for s, v in zip(t, u)])
        peak = max(peak, np.abs(acc).max())
        y0 = sol.y[:, -1]
    return peak


@functools.cache
def luff_case():
    """The luffing move: 0.5 deg/s reached over one pendulum period, 5 deg; the run
    lasts the move and 0.75 period (runs.joint_move: the tip 10 m above the load)."""
    ramp = float(2 * np.pi / np.sqrt(G / ROPE))
    duration = 5.0 / 0.5 + ramp + 0.75 * ramp
    return ramp, duration, luffing_reference(np.radians(0.5), ramp, np.radians(5.0),
                                             duration)


def test_phi5_of_an_inclined_luffing_jib_away_from_the_origin(tmp_path):
    """The hinge at (2, 0, 3), the jib at 60 deg, the rope over a sheave S halfway up
    the jib before the tip (the load hangs from the tip, the last span's other end, not
    from S), and a tie of 2 falls between two points of the jib listed after it (no
    span of it reaches the load): the tip's circle has a vertical
    tangent part (JIB cos 60 = 10 m per rad) beside the horizontal one (the lever JIB
    sin 60 = 17.32 m, the tip's height above the hinge: docs/loads.md); phi5 is the
    load's horizontal force over m x lever x the angular acceleration. A trapezoid of
    one pendulum period leaves no swing (2 in the linear limit); the reference follows
    the tip's exact circle (the lever shrinks as the jib lowers, 0.4 % at the peak) and
    the vertical acceleration's change of g. Tolerance 2e-3: the exact pendulum at
    0.3 deg of swing, the rope's static stretch (2 cm of 10 m: w by 1e-3, the peak by
    ~1e-4), the rope's axial mode (~22 rad/s) set ringing by the step of the tip's
    vertical acceleration (1.4e-3 g) and modulating the rope force, second differences
    of positions stored every 0.01 s; measured 5e-4. The mutants seen here change the
    lever by a third or more."""
    (tmp_path / "luff.yaml").write_text(LUFF)
    ramp, duration, peak = luff_case()
    path = tmp_path / "s.yaml"
    path.write_text("cranefe: 1\nscene: t\nmodel: luff.yaml\nanalysis:\n  type: loads\n"
                    "  hoist: {speed: 0.2}\n  tolerance: 1.0e-9\n  drives:\n"
                    f"    luffing: {{v_max_deg: 0.5, ramp: {ramp!r}, jerk_time: 0, "
                    "distance_deg: 5.0}\n")
    r = cranefe.loads(str(path), only=["luffing"])
    p = r.factors["phi5"]["luffing"]
    lever = JIB * np.sin(THETA0)
    alpha = np.radians(0.5) / ramp
    assert p["kind"] == "hinge"
    assert p["acceleration"] == pytest.approx(lever * alpha, rel=1e-9)
    assert p["rigid_body_force_N"] == pytest.approx(2000 * lever * alpha, rel=1e-9)
    assert r.simulations[0].duration == pytest.approx(duration, rel=1e-12)
    assert p["value"] == pytest.approx(peak / (lever * alpha), rel=2e-3)
    assert p["peak_force_N"] == pytest.approx(2000 * peak, rel=2e-3)


# ------------------------------------------------ phi5 of a slew through a large angle

HUB = np.array([3.0, -2.0, 0.0])                # the slewing hinge, away from the origin
RADIUS, HEIGHT = 10.0, 15.0                     # the tip from the hinge
TOP = HUB + [RADIUS, 0.0, HEIGHT]
SLEW = f"""cranefe: 1
name: a jib slewing about a vertical axis through (3, -2, 0)
nodes:
  O:   {HUB.tolist()}
  TIP: {TOP.tolist()}
  D:   {(HUB + [0.5, 0.0, 1.0]).tolist()}
  L:   {(TOP - [0.0, 0.0, ROPE]).tolist()}
ground: [O]
masses:
  L: 2000
bodies:
  jib: {{mass: 3000, com: {((HUB + TOP) / 2).tolist()}, inertia: [1.0e5, 1.0e5, 1.0e5],
        nodes: [TIP, D]}}
joints:
  - {{name: slewing, type: hinge, bodies: [ground, jib], at: O, axis: [0, 0, 1]}}
springs:
  - {{name: slewing_gear, type: rotational, bodies: [ground, jib], at: O,
     axis: [0, 0, 1], stiffness: 1.0e9}}
drums:
  hoist: {{node: D, radius: 0.2, inertia: 5.0, brake: false, rope_reserve: 20.0,
          motor: {{rotor_inertia: 0.05, gear_ratio: 30}}}}
ropes:
  hoist_rope: {{EA: 5.0e7, path: [hoist, TIP, L]}}
"""


def slewing_reference(omega, ramp, distance, duration):
    """(peak, time) of |F . e| / m (m/s^2): F the load's inertia force, e = (-sin p,
    cos p, 0) the horizontal tangent of the tip's circle at the slewing angle p(t) (the
    trapezoid: alpha = omega / ramp over `ramp`, `distance` rad in all, about +z). The
    tip P = HUB + (RADIUS cos p, RADIUS sin p, HEIGHT); the load a spherical pendulum of
    length ROPE hanging from it, r = x - P: r'' = g - P'' - r (r . (g - P'') + |r'|^2) /
    ROPE^2 (the rope force along r, its size from the constraint's second derivative),
    from rest below the tip. DOP853 to 1e-11 piece by piece between the profile's
    corners (the constraint drifts by < 1e-8 m)."""
    from scipy.integrate import solve_ivp
    alpha = omega / ramp
    t_cruise = distance / omega - ramp
    corners = [0.0, ramp, ramp + t_cruise, 2 * ramp + t_cruise, duration]
    gv = np.array([0.0, 0.0, -G])

    def angle(t):                                   # (p, p', p'')
        if t <= corners[1]:
            return 0.5 * alpha * t * t, alpha * t, alpha
        if t <= corners[2]:
            return 0.5 * alpha * ramp ** 2 + omega * (t - ramp), omega, 0.0
        if t <= corners[3]:
            s = t - corners[2]
            return distance - 0.5 * alpha * (ramp - s) ** 2, omega - alpha * s, -alpha
        return distance, 0.0, 0.0

    def tip_acc(t):                                 # P'' and p
        p, dp, ddp = angle(t)
        c, s = np.cos(p), np.sin(p)
        return RADIUS * np.array([-s * ddp - c * dp ** 2, c * ddp - s * dp ** 2, 0.0]), p

    def load_acc(t, y):                             # the load's x'' = P'' + r''
        r, v = y[:3], y[3:]
        P2, p = tip_acc(t)
        q = gv - P2
        return P2 + q - r * (r @ q + v @ v) / ROPE ** 2, p

    def rhs(t, y):
        return np.r_[y[3:], load_acc(t, y)[0] - tip_acc(t)[0]]

    y0, best = np.r_[0.0, 0.0, -ROPE, 0.0, 0.0, 0.0], (0.0, 0.0)
    for a, b in itertools.pairwise(corners):
        sol = solve_ivp(rhs, (a, b), y0, method="DOP853", rtol=1e-11, atol=1e-12,
                        dense_output=True)
        ts = np.linspace(a, b, max(2, int((b - a) * 1000)))
        for t, y in zip(ts, sol.sol(ts).T):
            acc, p = load_acc(t, y)
            f = abs(acc @ [-np.sin(p), np.cos(p), 0.0])
            if f > best[0]:
                best = (f, t)
        y0 = sol.y[:, -1]
    return best


@functools.cache
def slew_case():
    """The slew: a trapezoid of half a pendulum period (w = sqrt(g / ROPE)) whose
    braking starts 1.5 periods after the start (the two pulses' swings add), through
    60 deg; the run lasts the move and 0.75 period (runs.joint_move)."""
    w = np.sqrt(G / ROPE)
    period = 2 * np.pi / w
    ramp, distance = period / 2, np.radians(60.0)
    omega = distance / (1.5 * period)
    duration = distance / omega + ramp + 0.75 * period
    return float(omega), float(ramp), distance, slewing_reference(omega, ramp, distance,
                                                                  duration)


def test_phi5_of_a_slew_through_a_large_angle(tmp_path):
    """A jib slewing 60 deg about a vertical axis away from the origin, the load 10 m
    below its tip at radius 10 m: phi5 is the load's force along the horizontal tangent
    of the tip's circle at the current angle over m x radius x the angular acceleration
    (docs/loads.md). The braking's swing adds to the start's (3.0 m a, 3.5 s after the
    stop, at 60 deg: a tangent rotated or bent by a wrong rotation of the tip's radius
    misses it by half). Reference: the spherical pendulum (centrifugal and Coriolis
    forces of the 6 deg/s slew included; the engine's load path agrees with it to 1e-4 m).
    Tolerance 1e-2: the elastic rope's axial mode (~23 rad/s, absent from the rigid
    reference) rings after the stop's steps of acceleration on the tilted rope and adds
    up to 1.5 % of m a to the force (0.5 % at the peak, measured); the mutants this
    catches change the value by 20 % or more."""
    (tmp_path / "slew.yaml").write_text(SLEW)
    omega, ramp, distance, (peak, when) = slew_case()
    path = tmp_path / "s.yaml"
    path.write_text("cranefe: 1\nscene: t\nmodel: slew.yaml\nanalysis:\n  type: loads\n"
                    "  hoist: {speed: 0.2}\n  tolerance: 1.0e-9\n  drives:\n"
                    f"    slewing: {{v_max_deg: {float(np.degrees(omega))!r}, ramp: {ramp!r}, "
                    "jerk_time: 0, distance_deg: 60.0}\n")
    r = cranefe.loads(str(path), only=["slewing"])
    p = r.factors["phi5"]["slewing"]
    alpha = omega / ramp
    assert p["kind"] == "hinge"
    assert p["acceleration"] == pytest.approx(RADIUS * alpha, rel=1e-9)
    assert when > distance / omega + ramp                   # after the stop
    assert p["value"] == pytest.approx(peak / (RADIUS * alpha), rel=1e-2)
    assert p["peak_time_s"] == pytest.approx(when, abs=0.05)


# --------------------------------------------------- phi1: light and massless parts

ARM = """cranefe: 1
name: an elastic arm with light parts on it
plane: xz
nodes:
  O: [0.0, 0.0, 0.0]
  T: [10.0, 0.0, 0.0]
  D: [10.0, 0.0, -20.0]
  H: [10.0, 0.0, -10.0]
  C: [0.5, 0.0, 0.0]
  E: [12.0, 0.0, 0.0]
ground: [O, D]
masses: {H: 2000, T: 500, C: 200, E: 0.5}
bodies:
  arm: {mass: 1000, com: [5.0, 0.0, 0.0], inertia: [1.0e3, 1.0e3, 1.0e3], nodes: [T, C, E]}
  lamp: {mass: 0.5, com: [11.0, 0.0, 0.0], inertia: [0.01, 0.01, 0.01]}
  frame: {mass: 0.0, com: [13.0, 0.0, 0.0], inertia: [0.01, 0.01, 0.01]}
joints:
  - {name: pivot, type: hinge, bodies: [ground, arm], at: O, axis: [0, 1, 0]}
  - {name: lamp_fixed, type: fixed, bodies: [arm, lamp], at: T}
  - {name: frame_fixed, type: fixed, bodies: [arm, frame], at: T}
springs:
  - {name: arm_spring, type: rotational, bodies: [ground, arm], at: O, axis: [0, 1, 0],
     stiffness: 1.0e7}
drums:
  hoist: {node: D, radius: 0.25, inertia: 5.0, brake: false}
ropes:
  hoist_rope: {EA: 2.16e6, path: [hoist, T, H]}
"""


def test_phi1_counts_light_parts_and_leaves_out_massless_ones(tmp_path):
    """The elastic arm of test_mutation_kills_loads_analysis.py with a 0.5 kg point mass
    E at x = 12 m, a 0.5 kg body (a lamp) at x = 11 m and a massless frame at x = 13 m,
    both fixed to the arm: every crane mass is listed, however light (the lamp and E),
    a part without mass is not (the frame). All ride on one rigid arm turning about O,
    so each one's vertical acceleration is x / 10 of the tip's at every instant: its
    upper - 1 and 1 - lower are x / 10 of the tip's (to rounding: 1e-9), and the worst
    mass is the farthest listed, E."""
    (tmp_path / "arm.yaml").write_text(ARM)
    path = tmp_path / "s.yaml"
    path.write_text("cranefe: 1\nscene: arm\nmodel: arm.yaml\nanalysis:\n  type: loads\n"
                    "  hoist: {drum: hoist, load: H, speed: 0.5, creep: 0.1}\n"
                    "  after_lift_off: 0.3\n  time_step: 0.002\n")
    p1 = cranefe.loads(str(path), only=["phi1"]).factors["phi1"]
    by = p1["by_mass"]
    assert set(by) == {"arm", "lamp", "T", "C", "E"}
    assert by["lamp"]["mass_kg"] == by["E"]["mass_kg"] == 0.5
    tip = by["T"]
    assert tip["upper"] > 1.1                            # the arm does swing
    for name, x in (("arm", 5.0), ("lamp", 11.0), ("C", 0.5), ("E", 12.0)):
        assert by[name]["upper"] - 1 == pytest.approx(x / 10 * (tip["upper"] - 1),
                                                      rel=1e-9), name
        assert 1 - by[name]["lower"] == pytest.approx(x / 10 * (1 - tip["lower"]),
                                                      rel=1e-9), name
    assert p1["mass"] == "E" and p1["value"] == by["E"]["upper"]


def test_the_warnings_of_a_joint_move_are_kept(tmp_path):
    """A joint move's own warnings reach the result (they were dropped: only the
    transient runs' were collected): a stay rope between two points of the cart joins
    only a body whose motion is prescribed, which the operation engine says (its force
    is not computed), and the travel run ends less than a swing period after the move
    (the run lasts the move plus 0.75 of the 10 m pendulum's period)."""
    (tmp_path / "cart.yaml").write_text(CART + "  stay: {EA: 1.0e7, path: [P, D]}\n")
    w = np.sqrt(G / 10.0)
    ramp = float(2 * np.pi / w)
    path = tmp_path / "s.yaml"
    path.write_text("cranefe: 1\nscene: t\nmodel: cart.yaml\nanalysis:\n  type: loads\n"
                    "  hoist: {speed: 0.2}\n  drives:\n"
                    f"    travel: {{v_max: 0.5, ramp: {ramp!r}, jerk_time: 0, "
                    "distance: 6.0}\n")
    r = cranefe.loads(str(path), only=["travel"])
    assert [t.name for t in r.simulations] == ["travel move"]
    assert any(x.startswith("rope(s) stay join only bodies") for x in r.warnings)
    assert any("less than the swing period of L" in x for x in r.warnings)
