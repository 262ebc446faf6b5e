"""Value tests of cranefe/analysis/operation/results.py's Recorder (issue 20, mutation
testing of session 10): the samples it makes at output times INSIDE a step
(`Recorder._between`, which interpolates and evaluates no forces).

Two winches (tests/test_mutation_kills_integrate_events.py's WINCH2, the second drum
with a motor behind a gear of 20): drum d1 on a torque table, drum d2 on a linear motor.
Output times every 7 ms fall inside the ~1.5 ms steps the error control takes, not on
their ends (s < 1 - 1e-12), so each sample but the first comes from `_between`. Its drive torques are checked against
the drives' laws by hand at the sample's time and drum speed:

    d1: M(t) = 5000 + 2000 t / 0.3 N m (the table [[0, 5000], [0.3, 7000]], linear);
    d2: M = i M_s (1 - i omega / n_s), i = 20, M_s = 120 N m, n_s = 157 rad/s
        (transient.md's linear motor at the motor shaft, omega the drum's speed).

Tolerance 1e-12 relative: the same arithmetic on the sampled speed (the speed itself
is the Hermite interpolant's; only the law is checked here).
"""

import numpy as np
import pytest
from test_mutation_kills_integrate import _scene
from test_mutation_kills_integrate_events import WINCH2

from cranefe.analysis.operation.integrate import simulate

MOTOR = WINCH2.replace("  d2: {node: W2, radius: 0.25, inertia: 4, rope_reserve: 100}",
                       "  d2: {node: W2, radius: 0.25, inertia: 4, rope_reserve: 100,\n"
                       "       motor: {rotor_inertia: 0.002, gear_ratio: 20}}")


def test_drive_torques_sampled_inside_steps_follow_the_drives_laws():
    """Torque table and linear motor at output times inside steps (kills `_between`'s
    drum block: its torque and motor branches, the table read at `ts`, the motor's
    gear on both sides, the sample's torque array)."""
    assert MOTOR != WINCH2
    model = _scene("winch_motor", MOTOR,
                   "  duration: 0.3\n  output_step: 0.007\n  drives:\n"
                   "    a: {drum: d1, torque: [[0, 5000], [0.3, 7000]]}\n"
                   "    b: {drum: d2, motor: {stall_torque: 120, synchronous_speed: 157}}\n",
                   "{sway: false}")
    res = simulate(model, fast=False)
    t = res.times
    assert len(t) == 44 and res.steps > 100           # ~1.5 ms steps, not on the 7 ms grid
    np.testing.assert_allclose(res.drive_torque[:, 0], 5000 + 2000 * t / 0.3, rtol=1e-12)
    omega = res.drive_speed[:, 1]
    assert omega[-1] > 1.0                            # the motor has run up
    np.testing.assert_allclose(res.drive_torque[:, 1],
                               20 * 120 * (1 - 20 * omega / 157), rtol=1e-12)


@pytest.mark.parametrize("S0, S1, m0, m1", [
    (0.0, -1.0, 1.0, 1.0),          # rises, falls below S1's level, rises: m0, m1 > 0
    (0.0, 1.0, -1.0, -1.0),         # falls, rises above S1, falls: m0, m1 < 0
    (1.0, 1.2, 2.0, -3.0),          # one interior maximum: m0 > 0 > m1
    (1.0, 0.5, -0.2, 0.1),          # m0 <= 0 <= m1: no interior maximum, S0 is
    (2.0, 2.0, 0.0, 0.0),           # constant
    (0.0, 0.0, 1.0, 1.0),           # A = 6 (S0 - S1) + 3 (m0 + m1) != 0, B = -6
    (0.0, -0.5, 0.25, 0.5),         # A = 0: p' linear, one root
])
def test_the_force_peak_inside_a_step_against_the_sampled_cubic(S0, S1, m0, m1):
    """_hermite_max1's largest value of the force's cubic over a step (and where) against
    the cubic sampled at 2e5 + 1 points (its own error: the curvature times (5e-6)^2/2,
    below 1e-9 here); hermite_bound is never below it. The first case was missed before
    (the search looked inside a step only when m0 > 0 > m1): 0.0443 at s = 0.092."""
    from cranefe.analysis.operation.results import _hermite_max1, hermite_bound
    s = np.linspace(0.0, 1.0, 200001)
    p = (2 * s**3 - 3 * s**2 + 1) * S0 + (s**3 - 2 * s**2 + s) * m0 \
        + (-2 * s**3 + 3 * s**2) * S1 + (s**3 - s**2) * m1
    best, where = _hermite_max1(S0, S1, m0, m1)
    assert best == pytest.approx(p.max(), abs=1e-9)
    if p.max() > max(S0, S1) + 1e-6:
        assert where == pytest.approx(s[np.argmax(p)], abs=1e-4)
    assert hermite_bound(S0, S1, m0, m1) >= best
    if (S0, S1, m0, m1) == (0.0, -1.0, 1.0, 1.0):
        assert best == pytest.approx(0.0443, abs=1e-4) and 0.09 < where < 0.095
