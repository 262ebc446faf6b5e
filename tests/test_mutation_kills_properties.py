"""Value tests of the decorated functions (properties) of the formula modules (issue 20,
mutation testing): mutmut 3 skips every function with a decorator other than
staticmethod/classmethod, so tools/mutation.py rewrites `@property def f` as
`f = (property)(f)` in its scratch copy and these got mutants only then.

Each result is built directly from its dataclass with values whose answer is written out
by hand (no model, no solver), so the whole file runs in well under a second:
- ModalResult: f = omega / (2 pi), T = 2 pi / omega (inf for a rigid, omega = 0, mode);
- Motion.end: the last boundary when the drive then rests (v = 0), else inf;
- Transient.breakpoints: the union of the profiles' times strictly inside (0, duration);
- LoadsSpec.speeds: creep and 1/4, 1/2, 3/4, 1 x full speed, sorted, without repeats;
- Shaper.duration / AccelSteps.end: the last impulse / step time.
Tolerances: exact equality for table look-ups and sorting; 1e-15 relative for one
division by 2 pi (a couple of roundings of O(1) numbers).
"""

import math

import numpy as np

from cranefe.analysis.loads.scene import LoadsSpec
from cranefe.analysis.modal import ModalResult
from cranefe.analysis.operation.profiles import Motion
from cranefe.analysis.shaping.motion import AccelSteps
from cranefe.analysis.shaping.shapers import Shaper
from cranefe.analysis.transient.scene import DrumDrive, NodeForce, Profile, Transient


def _modal(omega):
    m = len(omega)
    return ModalResult(model_name="m", effects={}, labels=("a", "b", "c", "d"),
                       omega=np.array(omega, float), shapes=np.zeros((4, m)),
                       node_shapes=np.zeros((m, 1, 3)), rigid=np.array(omega) == 0,
                       quasi_cyclic=(), massless=(), solver="dense")


def test_modal_frequency_and_period_by_hand():
    # slow modes (omega <= 1 rad/s, e.g. a load's sway) keep their period too
    r = _modal([0.0, 2 * math.pi, 4 * math.pi, 1.0, 0.5])
    np.testing.assert_allclose(r.frequency_hz, [0.0, 1.0, 2.0, 1 / (2 * math.pi),
                                                1 / (4 * math.pi)], rtol=1e-15, atol=0)
    assert r.period_s[0] == math.inf            # rigid mode: no period
    np.testing.assert_allclose(r.period_s[1:], [1.0, 0.5, 2 * math.pi, 4 * math.pi],
                               rtol=1e-15, atol=0)
    assert r.dofs == 4


def _motion(v):
    """Three boundaries t = 0, 1, 3 with speeds v at them (the state at t[-1] is the rest)."""
    n = len(v)
    return Motion(np.array([0.0, 1.0, 3.0][:n]), np.zeros(n), np.array(v, float),
                  np.zeros(n), np.zeros(n))


def test_motion_end_is_the_last_boundary_only_when_it_rests():
    assert _motion([0.0, 2.0, 0.0]).end == 3.0
    assert _motion([0.0, 0.0, 2.0]).end == math.inf      # still moving at its last boundary
    assert np.array_equal(_motion([0.0, 2.0, 0.0]).breakpoints, [0.0, 1.0, 3.0])
    # rest is |v| <= 1e-12 max(1, max |v|): relative to a fast drive's peak, so a round-off
    # residual of a 150 rad/s drive (1e-13, a few ulp of 150) is a rest, not a move
    assert _motion([0.0, 150.0, 1e-13]).end == 3.0
    assert _motion([0.0, 150.0, 1e-6]).end == math.inf


def _profile(times):
    return Profile(np.array(times, float), np.zeros((len(times), 3)))


def _transient(drums, forces, duration=2.0):
    return Transient(duration=duration, time_step=None, max_steps=10, method="direct",
                     modes=1, static_correction=False, initial="static", grounded=(),
                     output_step=None, drums=tuple(drums), forces=tuple(forces))


def test_transient_breakpoints_strictly_inside_the_run():
    drums = [DrumDrive(0, "hoist", "speed", _profile([0.0, 0.5, 3.0])),
             DrumDrive(1, "trolley", "motor", None)]
    forces = [NodeForce(0, "push", _profile([0.0, 1.25, 2.0]))]
    # {0, 0.5, 3} U {0, 1.25, 2}; 0 (the start) and 2, 3 (>= duration) left out
    assert np.array_equal(_transient(drums, forces).breakpoints, [0.5, 1.25])
    assert np.array_equal(_transient(drums[:1], []).breakpoints, [0.5])
    assert np.array_equal(_transient([], forces).breakpoints, [1.25])
    assert _transient([], []).breakpoints.size == 0
    assert np.array_equal(_profile([0.0, 0.5]).breakpoints, [0.0, 0.5])


def _loads(speed, creep):
    return LoadsSpec(drum="hoist", loads=("hook",), speed=speed, creep=creep, ramp=1.0,
                     jerk=0.0, fraction=0.0, release_time=0.0, moves=(),
                     after_lift_off=1.0, time_step=None)


def test_loads_speeds_creep_then_shares_of_full_speed():
    assert _loads(2.0, 0.1).speeds == (0.1, 0.5, 1.0, 1.5, 2.0)
    assert _loads(2.0, 1.0).speeds == (0.5, 1.0, 1.5, 2.0)      # creep = 1/2 full: once
    assert _loads(2.0, 3.0).speeds == (0.5, 1.0, 1.5, 2.0, 3.0)  # sorted, creep last


def test_shaper_duration_and_steps_end_are_the_last_time():
    s = Shaper("zv", np.array([0.0, 0.25, 0.5]), np.array([0.25, 0.5, 0.25]))
    assert s.duration == 0.5 and isinstance(s.duration, float)
    a = AccelSteps(np.array([0.0, 0.75, 2.0]), np.array([1.0, -1.0, 0.0]))
    assert a.end == 2.0 and isinstance(a.end, float)
