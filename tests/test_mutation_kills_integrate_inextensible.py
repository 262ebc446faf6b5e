"""Value tests of cranefe/analysis/operation/integrate.py (issue 20, mutation testing,
fourth round): simulate's branches for inextensible ropes (`rope_elasticity: false`,
constraints.py's ConstrainedStepper), which the first three kill files never build.

- a given initial state of an inextensible rope is projected onto the static state's
  taut ropes (the elastic ropes' rule, taut where the given state stretches the rope,
  is not for them): a pendulum given a hair inside its circle starts taut;
- a rope jerked taut while its drum hauls: the drum's work in the jerk enters the drive
  work with its sign (the balance closes to round-off), the impulse and the dissipated
  energy by hand.
"""

import math

import numpy as np
from test_operation import WINCH, scene
from test_operation_inextensible import INEXT, PENDULUM

from cranefe.analysis.operation.integrate import simulate
from cranefe.model import load

G = 9.81


def test_a_given_state_inside_the_circle_is_projected_onto_the_taut_rope(tmp_path):
    """The 100-kg pendulum (10 m) given at rest at 60 deg, 1e-6 of its length inside
    the circle: projected onto it, taut from the start: S(0) = m g cos 60 deg (to 1e-9:
    at rest on the circle the multiplier is exactly that; Newton stops at 1e-13 of the
    size), no rope event, on the circle at every sample (1e-6 m). Taken as slack (its
    stretch L < L0) the load would fall freely and be jerked: S(0) = 0 and an event."""
    th0, r = math.radians(60), 10.0 * (1 - 1e-6)
    model = load(scene(tmp_path, PENDULUM, "  duration: 0.2\n  tolerance: 1.0e-6\n"
                       "  output_step: 0.05\n", effects=INEXT, EAVAL=1.0e9))
    res = simulate(model, initial={"q": np.array([r * math.sin(th0),
                                                  10 - r * math.cos(th0)]),
                                   "v": np.zeros(2)}, fast=False)
    assert abs(res.rope_force[0, 0] / (100 * G * math.cos(th0)) - 1) < 1e-9
    assert not [e for e in res.events if e[1].startswith("rope")], res.events
    P = res.mass_position[:, 0]
    assert np.abs(np.hypot(P[:, 0], 10 - P[:, 2]) - 10).max() < 1e-6


def test_a_rope_jerked_taut_by_a_hauling_drum_books_the_drums_work(tmp_path):
    """The winch (drum R 0.5 m, no sway, 1000 kg) hauls in at 2 m/s of rope and slows
    to 1 m/s in 0.05 s (20 m/s^2 > g): the rope goes slack at t2 = 3 s and the load
    flies up, z = z2 + 2 tau - g tau^2 / 2, while the rope's end, still hauled, is at
    z2 + 0.075 + (tau - 0.05) (tau > 0.05); they meet at the larger root of
    (g/2) tau^2 - tau + 0.025 = 0, tau = (1 + sqrt(1 - 0.05 g)) / g = 0.17470 s, the
    load at v_c = 2 - g tau = 0.2862 m/s: the jerk gives it the rope's 1 m/s, impulse
    m (1 - v_c), the drum's work in the jerk P x 1 m/s, dissipated m (1 - v_c)^2 / 2
    (event time to 1e-9 s: located to 1e-13 in the event function, constant
    accelerations; impulse and dissipation to 1e-6). The energy balance closes to
    1e-9 (the drive work with the jerk's share P x 1 m/s = 714 J in it; with its sign
    flipped it would be off by 1.4 kJ)."""
    m, t2 = 1000.0, 3.0
    path = scene(tmp_path, WINCH, "  duration: 4\n  tolerance: 1.0e-9\n  drives:\n"
                 "    hoist: {drum: hoist, profile: {type: table, speed: [[0, 0], "
                 "[1.0, 4.0], [3.0, 4.0], [3.05, 2.0], [4.0, 2.0]]}}\n",
                 effects="{rope_elasticity: false, sway: false}", Z=20.0, MASS=m,
                 EAVAL=1.0e9)
    res = simulate(load(path), fast=False)
    ev = [e for e in res.events if e[1].startswith("rope")]
    assert [e[1].split(":")[0] for e in ev] == ["rope r slack", "rope r taut"], ev
    tau = (1 + math.sqrt(1 - 0.05 * G)) / G
    assert abs(ev[0][0] - t2) < 1e-9 and abs(ev[1][0] - (t2 + tau)) < 1e-9, ev
    vc = 2.0 - G * tau
    P = float(ev[1][1].split("impulse ")[1].split(" N s")[0])
    np.testing.assert_allclose(P, m * (1.0 - vc), rtol=1e-6)
    np.testing.assert_allclose(res.energy["dissipated"], 0.5 * m * (1.0 - vc) ** 2,
                               rtol=1e-6)
    assert res.energy_error < 1e-9, res.energy_error
    after = res.times > t2 + tau + 1e-6
    np.testing.assert_allclose(res.rope_force[after, 0], m * G, rtol=1e-8)
