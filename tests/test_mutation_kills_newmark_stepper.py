"""Fast kill tests for cranefe/analysis/transient/newmark.py (tools/mutation.py newmark;
docs/testing.md, "Mutation testing"): the `Stepper` run on `Equations` of 1-2
coordinates built here by hand (no model, no statics: each case runs in milliseconds, so
a whole mutation run of the module's 859 mutants takes minutes, not hours).

Every expected value is the EXACT solution of the trapezoidal rule (Newmark beta = 1/4,
gamma = 1/2) written independently of the code:
- an undamped linear oscillator: the rule maps (w u, u') by a rotation through
  theta(h) = 2 atan(w h / 2) per step (the Cayley transform of the rotation generator),
  so u_n = u_0 cos(n theta): the method's known period error (theta < w h);
- a damped or driven linear system: the first-order Cayley recurrence
  z1 = (I - hA/2)^-1 ((I + hA/2) z0 + h/2 (f(t0+) + f(t1-))), with the loads' right limit
  at a step's start and left limit at its end (accelerations recomputed at breakpoints);
- a constant acceleration: integrated exactly (x1 = x0 + h v0 + h^2 a / 2);
- events (a rope going slack/taut, lift-off, landing): the step is cut where the event
  function of the discrete solution from the step's start crosses zero: an angle of the
  rotation (tau = 2/w tan(phi/2)), a root of the parabola, or a linear function of time;
- a motor with a quadratic characteristic: each step's speed from the quadratic equation
  J (v1 - v0) = h/2 (f(v0) + f(v1)) by its root formula (the code uses Newton).
"""

import math

import numpy as np
import pytest

from cranefe.analysis.transient.equations import Equations, MotorLoad, Signal
from cranefe.analysis.transient.newmark import Stepper
from cranefe.errors import AnalysisError

EPS = 1e-12          # a step's end t0 + (t1 - t0) may differ from t1 by an ulp


def jump(value, t_on, t_off):
    """A Signal: `value` on [t_on, t_off), 0 elsewhere, with left/right limits at both
    jumps (left=True: the limit from below)."""
    value = np.atleast_1d(np.asarray(value, dtype=float))

    def f(t, left=False):
        lo = t > t_on + EPS or (t >= t_on - EPS and not left)
        hi = t < t_off - EPS or (t <= t_off + EPS and left)
        return value * float(lo and hi)
    return Signal(f)


def ramp(slope):
    """A Signal rising linearly, slope * t (continuous: no breakpoint)."""
    return Signal(lambda t, left=False: np.array([slope * t]))


class Recorder:
    """Records the sampled states (copies) and the accepted steps."""

    def __init__(self):
        self.t, self.x, self.v, self.a, self.steps = [], [], [], [], []

    def start(self, s, stepper):
        self.stepper = stepper
        self.sample(s)

    def accept(self, s0, s1):
        self.steps.append((s0.t, s1.t))

    def sample(self, s):
        self.t.append(s.t)
        self.x.append(s.x.copy())
        self.v.append(s.v.copy())
        self.a.append(s.a.copy())

    def arrays(self):
        return (np.array(self.t), np.array(self.x), np.array(self.v), np.array(self.a))


class SpeedRamp:
    """A prescribed speed (duck type of scene.Profile): A t up to T, A T after; its
    integral and its rate with the left/right limits at T."""

    def __init__(self, A, T):
        self.A, self.T = A, T

    def __call__(self, t):
        return np.array([self.A * min(t, self.T)])

    def rate(self, t, left=False):
        on = t < self.T - EPS or (left and t <= self.T + EPS)
        return np.array([self.A if on else 0.0])

    def integral(self, t):
        A, T = self.A, self.T
        return np.array([A * t * t / 2 if t <= T else A * T * T / 2 + A * T * (t - T)])


class ConstantSpeed:
    """A prescribed constant speed V from t = 0 (duck type of scene.Profile)."""

    def __init__(self, V):
        self.V = V

    def __call__(self, t):
        return np.array([self.V])

    def rate(self, t, left=False):
        return np.array([0.0])

    def integral(self, t):
        return np.array([self.V * t])


def rot(p, phi):
    """The trapezoidal rule's map of (w u, u') of an undamped oscillator: a rotation."""
    c, s = math.cos(phi), math.sin(phi)
    return np.array([c * p[0] + s * p[1], -s * p[0] + c * p[1]])


def theta(w, h):
    return 2 * math.atan(w * h / 2)


def cayley(A, z, f0, f1, h):
    n = len(z)
    return np.linalg.solve(np.eye(n) - h / 2 * A, (np.eye(n) + h / 2 * A) @ z
                           + h / 2 * (f0 + f1))


# --------------------------------------------------------------------- linear steps
def test_step_load_rotates_by_the_trapezoidal_angle_with_a_massless_coordinate():
    """A mass m on a spring k1 to a MASSLESS coordinate on a spring k2 to the ground
    (M = diag(m, 0)), a constant force F = F0 + a signal part on the mass: the massless
    coordinate follows statically, x2 = k1 x1 / (k1 + k2), and the mass is an oscillator
    of stiffness k = k1 k2 / (k1 + k2) (w h = 0.5): x1_n = F/k (1 - cos n theta),
    v1_n = F/k w sin n theta, a1_n = F/m cos n theta to 1e-12 relative (round-off of 39
    steps). The grid: duration 1 with h = 0.026 asked gives 39 steps of 1/39. The work
    of the loads F x1_N, no dissipation, the energy balance to 1e-12, the progress
    callback at every step."""
    m, k1, k2, F0, F1 = 2.0, 1200.0, 2400.0, 3.0, 5.0
    k = k1 * k2 / (k1 + k2)                                # 800: w = 20
    w, F = math.sqrt(k / m), F0 + F1
    K = np.array([[k1, -k1], [-k1, k1 + k2]])
    eq = Equations(M=np.diag([m, 0.0]), K=K, F0=np.array([F0, 0.0]),
                   loads=[(np.array([[1.0], [0.0]]), jump(F1, 0.0, 1.0))])
    calls = []
    rec = Recorder()
    st = Stepper(eq, 10.0, 0.01, rec, progress=lambda t, T: calls.append((t, T)))
    st.run(1.0, 0.026, breakpoints=(1.0,))    # F1 ends at the end: a is its left limit
    t, x, v, a = rec.arrays()
    h = 1.0 / 39
    n = np.arange(40)
    assert st.h == h and st.steps == 39
    np.testing.assert_allclose(t, n * h, rtol=0, atol=1e-14)
    th = theta(w, h)
    np.testing.assert_allclose(x[:, 0], F / k * (1 - np.cos(n * th)), rtol=0,
                               atol=1e-12 * F / k)
    np.testing.assert_allclose(x[:, 1], k1 / (k1 + k2) * x[:, 0], rtol=0,
                               atol=1e-12 * F / k)
    np.testing.assert_allclose(v[:, 0], F / k * w * np.sin(n * th), rtol=0,
                               atol=1e-12 * F / k * w)
    np.testing.assert_allclose(a[:, 0], F / m * np.cos(n * th), rtol=0, atol=1e-11 * F / m)
    # the period error is what is tested: the exact solution differs by far more
    assert abs(F / k * (1 - math.cos(w)) - x[-1, 0]) > 1e-3 * F / k
    assert st.energy["work_loads"] == pytest.approx(F * x[-1, 0], rel=1e-12)
    assert st.energy["dissipated"] == st.energy["work_drives"] == 0.0
    assert st.energy["impact_loss"] == 0.0
    err, E1 = st.energy_error()
    assert err < 1e-12
    assert E1 == pytest.approx(0.5 * m * v[-1, 0]**2 + 0.5 * k * x[-1, 0]**2, rel=1e-12)
    assert st.events == [] and st.warnings == [] and st.lift_off == {}
    np.testing.assert_allclose([c[0] for c in calls], n[1:] * h, rtol=0, atol=1e-14)
    assert {c[1] for c in calls} == {1.0}
    assert rec.steps[-1] == (pytest.approx(38 * h), 1.0)
    assert st.final.t == 1.0 and np.array_equal(st.final.x, x[-1])


def test_damped_two_dof_with_jumps_and_breakpoints_against_the_cayley_recurrence():
    """Two masses in a chain, viscous damping C (a dashpot to the ground and one between
    them) plus a low-rank part U diag(W) U^T, under a constant force, a ramp force, a
    force switched on at t = 0.137 and off at 0.3 and one switched on 1e-8 s after the
    grid time 0.28 (breakpoints off, on and next to the grid h = 0.02: 0.28 + 1e-8 is a
    step of its own and no sample; those outside (0, T) and at 0 ignored): the states
    at every second step (stride 2, the last one always) against the Cayley recurrence
    over the same steps (1e-12 relative: round-off), the work of the loads and the
    dissipated energy summed over the steps with the step's mean velocity (1e-12), the
    balance (1e-12)."""
    M = np.diag([3.0, 1.5])
    K = np.array([[900.0, -400.0], [-400.0, 400.0]])
    C = np.array([[4.0, -1.0], [-1.0, 1.0]])
    U, W = np.array([[1.0], [-2.0]]), np.array([0.7])
    Ct = C + U @ np.diag(W) @ U.T
    F0 = np.array([2.0, -1.0])
    G1, G2 = np.array([[0.0], [1.0]]), np.array([[1.0], [0.5]])
    s1, s2, s3 = ramp(30.0), jump(-7.0, 0.137, 0.3), jump(3.0, 0.28 + 1e-8, 10.0)
    eq = Equations(M=M, K=K, C=C, U=U, W=W, F0=F0,
                   loads=[(G1, s1), (G2, s2), (G1, s3)])
    rec = Recorder()
    st = Stepper(eq, 10.0, 0.01, rec)
    T, h = 0.5, 0.02
    st.run(T, h, breakpoints=(-1.0, 0.0, 0.137, 0.28 + 1e-8, 0.3, T, 0.7), stride=2)

    def F(t, left):
        return F0 + G1 @ (s1.value(t, left) + s3.value(t, left)) + G2 @ s2.value(t, left)
    A = np.block([[np.zeros((2, 2)), np.eye(2)],
                  [-np.linalg.solve(M, K), -np.linalg.solve(M, Ct)]])
    times = np.unique(np.r_[0.0, h * np.arange(1, 26), 0.137, 0.28 + 1e-8])
    z, out, work, diss = np.zeros(4), {0: np.zeros(4)}, 0.0, 0.0
    for t0, t1 in zip(times[:-1], times[1:]):
        f0 = np.r_[0, 0, np.linalg.solve(M, F(t0, False))]
        f1 = np.r_[0, 0, np.linalg.solve(M, F(t1, True))]
        z1 = cayley(A, z, f0, f1, t1 - t0)
        work += 0.5 * (F(t0, False) + F(t1, True)) @ (z1[:2] - z[:2])
        vbar = 0.5 * (z[2:] + z1[2:])
        diss += (t1 - t0) * vbar @ Ct @ vbar
        z = z1
        k = round(t1 / h)
        if abs(t1 - k * h) < 1e-12 and (k % 2 == 0 or k == 25):
            out[k] = z
    t, x, v, a = rec.arrays()
    ks = sorted(out)
    np.testing.assert_allclose(t, h * np.array(ks), rtol=0, atol=1e-14)
    ref = np.array([out[k] for k in ks])
    scale = np.abs(ref).max(axis=0)
    np.testing.assert_allclose(x, ref[:, :2], rtol=0, atol=1e-12 * scale[:2].max())
    np.testing.assert_allclose(v, ref[:, 2:], rtol=0, atol=1e-12 * scale[2:].max())
    # the accelerations from the equations (right limits at the breakpoint 0.3 = 15 h,
    # not sampled: stride 2; at the samples the loads are continuous)
    acc = np.linalg.solve(M, (F(t[-1], True) - K @ x[-1] - Ct @ v[-1]))
    np.testing.assert_allclose(a[-1], acc, rtol=1e-10)
    assert len(rec.steps) == 27                  # 25 grid steps + the cuts at 0.137, 0.28+
    assert st.energy["work_loads"] == pytest.approx(work, rel=1e-12)
    assert st.energy["dissipated"] == pytest.approx(diss, rel=1e-12)
    assert st.energy_error()[0] < 1e-12


def test_prescribed_drum_ramp_drives_a_coupled_oscillator():
    """Coordinate 0 prescribed (a drum: speed A t up to T = 0.21, then A T: the rate
    jumps, T off the grid h = 0.03), coordinate 1 a mass coupled to it by inertia mu,
    a dashpot c and a spring k, with a force
    switched on at 0.05 and off at 0.4 on both (on the drum it is seen only by the
    drive work: its left limit at a step's end). Coordinate 1 is the oscillator
    m x1'' + c x1' + k x1 = F1 + k x0 + c x0' - mu x0'' with x0, x0', x0'' known at each
    step's end (x0'' its left limit there, the right one at the step's start): the
    Cayley recurrence to 1e-12; the drum's reaction r = J x0'' + mu x1'' + c (x0' - x1')
    + k (x0 - x1) summed as the drive work 1/2 (r0 + r1) dx0 (1e-12); the balance."""
    J, mu, m, c, k, Acc, T = 5.0, 0.4, 2.0, 3.0, 500.0, 2.0, 0.21
    prof = SpeedRamp(Acc, T)
    Fs = jump(np.array([1.5, 4.0]), 0.05, 0.4)
    eq = Equations(M=np.array([[J, mu], [mu, m]]),
                   K=np.array([[k, -k], [-k, k]]), C=np.array([[c, -c], [-c, c]]),
                   loads=[(np.eye(2), Fs)], prescribed={0: prof})
    rec = Recorder()
    st = Stepper(eq, 10.0, 0.01, rec)
    h, dur = 0.03, 0.6
    st.run(dur, h, breakpoints=(T, 0.05, 0.4))

    def drum(t, left):
        return prof.integral(t)[0], prof(t)[0], prof.rate(t, left)[0]

    def f(t, left):
        x0, v0, a0 = drum(t, left)
        return np.array([0.0, (Fs.value(t, left)[1] + k * x0 + c * v0 - mu * a0) / m])
    A = np.array([[0.0, 1.0], [-k / m, -c / m]])

    def acc1(t, z, left):
        return f(t, left)[1] + A[1] @ z

    def reaction(t, z, left):
        x0, v0, a0 = drum(t, left)
        return J * a0 + mu * acc1(t, z, left) + c * (v0 - z[1]) + k * (x0 - z[0]) \
            - Fs.value(t, left)[0]
    times = np.unique(np.r_[0.0, h * np.arange(1, 21), T, 0.05, 0.4])
    z, zs, wd = np.zeros(2), [np.zeros(2)], 0.0
    for t0, t1 in zip(times[:-1], times[1:]):
        z1 = cayley(A, z, f(t0, False), f(t1, True), t1 - t0)
        wd += 0.5 * (reaction(t0, z, False) + reaction(t1, z1, True)) \
            * (drum(t1, True)[0] - drum(t0, True)[0])
        z = z1
        if abs(t1 / h - round(t1 / h)) < 1e-9:
            zs.append(z)
    zs = np.array(zs)
    t, x, v, a = rec.arrays()
    np.testing.assert_allclose(t, h * np.arange(21), rtol=0, atol=1e-14)
    np.testing.assert_allclose(x[:, 0], [prof.integral(tt)[0] for tt in t], rtol=1e-13)
    np.testing.assert_allclose(v[:, 0], [prof(tt)[0] for tt in t], rtol=1e-13)
    np.testing.assert_allclose(x[:, 1], zs[:, 0], rtol=0, atol=1e-12 * abs(zs[:, 0]).max())
    np.testing.assert_allclose(v[:, 1], zs[:, 1], rtol=0, atol=1e-12 * abs(zs[:, 1]).max())
    assert np.array_equal(a[:, 0], np.where(t < T, Acc, 0.0))      # the drum's rate
    np.testing.assert_allclose(a[:, 1], [acc1(tt, zz, False) for tt, zz in zip(t, zs)],
                               rtol=0, atol=1e-10)
    assert st.energy["work_drives"] == pytest.approx(wd, rel=1e-12)
    assert st.energy_error()[0] < 1e-12


# --------------------------------------------------------------------- events
def bounce_reference(m, c, S0, P, t_off, h, dur):
    """The trapezoidal rule's exact solution of a load m on a tension-only spring c
    (tension S0 + c x, x down), pushed up by P until t_off: taut, the oscillator about
    x = -P / c (then 0) rotating by theta(step); slack, the constant acceleration
    (F + S0) / m. Each step from the grid's (or an event's) state: if the event
    x = -S0 / c is crossed, cut there (the rotation angle or the parabola's root)."""
    w = math.sqrt(c / m)
    targets = np.unique(np.r_[h * np.arange(1, round(dur / h) + 1), t_off])
    t, x, v, taut = 0.0, 0.0, 0.0, True
    events, samples = [], [(0.0, 0.0, 0.0)]
    xe = -S0 / c
    for te in targets:
        while te - t > 1e-13:
            H = te - t
            F = -P if t < t_off - 1e-12 else 0.0
            if taut:
                xc = F / c
                p = np.array([w * (x - xc), v])
                pe = rot(p, theta(w, H))
                if xc + pe[0] / w < xe:          # the tension S0 + c x falls below 0
                    R, d = math.hypot(*p), math.atan2(p[1], p[0])
                    phi = (d - math.acos(w * (xe - xc) / R)) % (2 * math.pi)
                    phi = min(phi, (d + math.acos(w * (xe - xc) / R)) % (2 * math.pi))
                    tau = 2 / w * math.tan(phi / 2)
                    p = rot(p, phi)
                    t, x, v, taut = t + tau, xe, p[1], False
                    events.append((t, "slack"))
                    continue
                t, x, v = te, xc + pe[0] / w, pe[1]
            else:
                acc = (F + S0) / m
                if x + v * H + acc * H * H / 2 > xe:    # taut again
                    r = np.roots([acc / 2, v, x - xe])
                    tau = min(rr.real for rr in r if 0 < rr.real <= H * (1 + 1e-9))
                    t, x, v, taut = t + tau, xe, v + acc * tau, True
                    events.append((t, "taut"))
                    continue
                t, x, v = te, x + v * H + acc * H * H / 2, v + acc * H
        if abs(te / h - round(te / h)) < 1e-9:
            samples.append((te, x, v))
    return events, np.array(samples)


def test_slack_and_taut_events_at_the_exact_discrete_times():
    """A load (m = 1, w = 20) on a tension-only rope (S0 = 10 N = its weight), pushed up
    by P = 20 N until t = 0.1037: the rope goes slack when the discrete oscillation
    reaches x = -S0/c (an angle of the rotation), the load flies at -10 m/s^2, falls
    after the push ends, the rope is taut again at x = -S0/c (a parabola's root) and
    oscillates, slack and taut again. Event times to 1e-10 s (the event tolerance 1e-9
    of S0 gives 2.5e-11 m; |v| >= 0.3 m/s there), the states at every step to 1e-9 m
    and 1e-8 m/s (the event errors carried on), the energy kept across the events (no
    loss: the balance to 1e-8). Three more rows start in compression (slack
    throughout): the warning; one more sits at zero force all the time: not an event."""
    m, c, S0, P, t_off, h, dur = 1.0, 400.0, 10.0, 20.0, 0.1037, 0.01, 1.0
    events, ref = bounce_reference(m, c, S0, P, t_off, h, dur)
    assert [e[1] for e in events][:4] == ["slack", "taut", "slack", "taut"]
    # rows 1-4 are not stretched by x (zero rows; a slack row's R^T S0 would load the
    # mass): three start in compression (slack throughout), row 3 sits at zero force
    # (taut, event function exactly 0 all the time: no event)
    eq = Equations(M=np.array([[m]]), K=np.zeros((1, 1)),
                   R=np.array([[1.0], [0.0], [0.0], [0.0], [0.0]]),
                   c=np.array([c, 50.0, 50.0, 50.0, 50.0]),
                   S0=np.array([S0, -1e3, -5.0, 0.0, -2.0]),
                   loads=[(np.array([[1.0]]), jump(-P, 0.0, t_off))])
    rec = Recorder()
    st = Stepper(eq, S0, 0.01, rec)
    st.run(dur, h, breakpoints=(t_off,))
    t, x, v, a = rec.arrays()
    assert [(k, what) for _, k, what in st.events] == [(0, e[1]) for e in events]
    np.testing.assert_allclose([e[0] for e in st.events], [e[0] for e in events],
                               rtol=0, atol=1e-10)
    np.testing.assert_allclose(t, ref[:, 0], rtol=0, atol=1e-14)
    np.testing.assert_allclose(x[:, 0], ref[:, 1], rtol=0, atol=1e-9)
    np.testing.assert_allclose(v[:, 0], ref[:, 2], rtol=0, atol=1e-8)
    assert st.warnings == ["3 rope element(s) start in compression, i.e. slack"]
    assert st.energy["impact_loss"] == 0.0
    assert st.energy_error()[0] < 1e-8


def test_lift_off_at_constant_hauling_speed():
    """A drum (coordinate 0, inertia J) hauls at constant speed V a rope (stiffness k,
    no initial force) to a load m resting on the ground (coordinate 1, up positive):
    the ground force m g - k V t vanishes at t0 = m g / (k V) = 0.2 s (off the grid
    h = 0.03; linear in the step length: found to 1e-12 s), then the load follows
    x1 = V (t - t0) - V/w sin(phi), phi = theta(t_1 - t0) + (n - 1) theta(h) (the
    discrete oscillation about the exact particular solution V (t - t0), which the rule
    integrates exactly), to 1e-12 m. The drive work is the energy gained: m v^2/2 +
    S^2/(2k) + m g x1 (to 1e-10: the event's share)."""
    J, m, k, g, V = 4.0, 100.0, 1e4, 10.0, 0.5
    w = math.sqrt(k / m)
    profile = ConstantSpeed(V)
    # a second rope, drum to load, slack throughout (S0 = -1e4 N, stretch < 0.3 m):
    # a slack row's R^T S0 is balanced in F0; its stiffness must stay out of the steps
    S2 = -1e4
    eq = Equations(M=np.diag([J, m]), K=np.zeros((2, 2)),
                   R=np.array([[1.0, -1.0], [1.0, -1.0]]), c=np.array([k, k]),
                   S0=np.array([0.0, S2]),
                   F0=np.array([0.0, -m * g]) - S2 * np.array([1.0, -1.0]),
                   prescribed={0: profile}, contacts=np.array([1]), up=np.array([1.0]))
    rec = Recorder()
    st = Stepper(eq, m * g, 0.1, rec)
    h, dur = 0.03, 0.6
    st.run(dur, h)
    t0 = m * g / (k * V)
    assert st.lift_off == {0: pytest.approx(t0, abs=1e-12)}
    assert [(k_, what) for _, k_, what in st.events] == [(2, "lift-off")]
    assert st.warnings == ["1 rope element(s) start in compression, i.e. slack"]
    t, x, v, a = rec.arrays()
    np.testing.assert_allclose(x[:, 0], V * t, rtol=1e-14)
    n1 = math.ceil(t0 / h)
    phi = np.where(t > t0, theta(w, n1 * h - t0) + (np.arange(len(t)) - n1) * theta(w, h),
                   0.0)
    x1 = np.where(t > t0, V * (t - t0) - V / w * np.sin(phi), 0.0)
    v1 = np.where(t > t0, V - V * np.cos(phi), 0.0)
    np.testing.assert_allclose(x[:, 1], x1, rtol=0, atol=1e-12)
    np.testing.assert_allclose(v[:, 1], v1, rtol=0, atol=1e-11)
    assert np.all(x[t < t0, 1] == 0.0)
    S = k * (x[-1, 0] - x[-1, 1])
    assert S + S2 < -5e3                                     # the second rope: slack
    gain = 0.5 * m * v[-1, 1]**2 + S**2 / (2 * k) + m * g * x[-1, 1]
    # the slack rope's -R^T S0 and its balance in F0 cancel in the equations (and in the
    # drum's reaction); the balance's work -S2 (x0 - x1) is the slack rope's potential
    # -S0 R x in E
    assert st.energy["work_drives"] == pytest.approx(gain, rel=1e-10)
    assert st.energy["work_loads"] == pytest.approx(
        -m * g * x[-1, 1] - S2 * (x[-1, 0] - x[-1, 1]), rel=1e-10)
    assert st.energy_error()[0] < 1e-10


def test_two_loads_lift_off_and_land_plastic_impacts():
    """Two loads on the ground, no rope between them: C (coordinate 1, contact 0, up
    +x, 2 kg) pushed up by 60 N from t = 0 to 0.1 (it lifts off at once: the boundary
    at the start of a step), B (coordinate 0, contact 1, up -x, 3 kg) by 60 N from
    tb = 0.0537 to tb + 0.2 (lift-off at tb). Flights with constant accelerations (exact
    in the rule): C lands at 0.1 + 0.2 + sqrt(0.06) with v^2 = 6 while B is in the air
    (C's impact must leave B's kinetic energy alone), B at tb + 0.4 + sqrt(0.08) with
    v^2 = 8: the plastic impact losses m v^2 / 2 = 6 and 12 J (= the pushes' work), to
    1e-8 (length scale 1e-4 m: heights located to 1e-13 m); after each landing the load
    stays at x = v = 0; the lift-off times per contact (contact j sits on coordinate
    1 - j, so a contact index used as a coordinate is caught); the event indices after
    the one (slack) rope row."""
    g, mB, mC, tb = 10.0, 3.0, 2.0, 0.0537
    eq = Equations(M=np.diag([mB, mC]), K=np.zeros((2, 2)), R=np.zeros((1, 2)),
                   c=np.array([1.0]), S0=np.array([-1.0]), F0=np.array([mB * g, -mC * g]),
                   loads=[(np.array([[0.0], [1.0]]), jump(60.0, 0.0, 0.1)),
                          (np.array([[1.0], [0.0]]), jump(-60.0, tb, tb + 0.2))],
                   contacts=np.array([1, 0]), up=np.array([1.0, -1.0]))
    rec = Recorder()
    st = Stepper(eq, 10.0, 1e-4, rec)     # heights to EVENT_TOL x 1e-4 m
    st.run(0.9, 0.01, breakpoints=(0.1, tb, tb + 0.2))
    assert st.warnings == ["1 rope element(s) start in compression, i.e. slack"]
    tC, tB = 0.3 + math.sqrt(0.06), tb + 0.4 + math.sqrt(0.08)
    assert [(k, what) for _, k, what in st.events] == [
        (1, "lift-off"), (2, "lift-off"), (1, "landing"), (2, "landing")]
    np.testing.assert_allclose([e[0] for e in st.events], [0.0, tb, tC, tB], rtol=0,
                               atol=1e-9)
    assert st.lift_off == {0: 0.0, 1: pytest.approx(tb, abs=1e-14)}
    assert st.energy["impact_loss"] == pytest.approx(18.0, rel=1e-8)
    assert st.energy["work_loads"] == pytest.approx(18.0, rel=1e-8)
    assert st.energy_error()[0] < 1e-8
    t, x, v, a = rec.arrays()
    # C at its apex t = 0.3: x = 0.3; B at t = 0.4 (rising, pushed until 0.2537)
    i3, i4 = np.searchsorted(t, [0.3 - 1e-9, 0.4 - 1e-9])
    assert x[i3, 1] == pytest.approx(0.3, abs=1e-12) and abs(v[i3, 1]) < 1e-12
    s = 0.4 - tb - 0.2
    assert x[i4, 0] == pytest.approx(-(0.2 + 2 * s - 5 * s * s), abs=1e-12)
    after_C, after_B = t > tC, t > tB
    assert np.all(x[after_C, 1] == 0.0) and np.all(v[after_C, 1] == 0.0)
    assert np.all(x[after_B, 0] == 0.0) and np.all(v[after_B, 0] == 0.0)
    assert np.all(a[after_B] == 0.0)


# --------------------------------------------------------------------- motors
class LinearMotor:
    """M(n) = T0 (1 - n / n0) with a WRONG slope reported (duck type of scene.Motor)."""

    def __init__(self, T0, n0, wrong_slope):
        self.T0, self.n0, self.wrong = T0, n0, wrong_slope

    def torque(self, n):
        return self.T0 * (1 - n / self.n0), self.wrong


class QuadraticMotor:
    """M(n) = T0 (1 - (n / n0)^2) and its slope (a duck type of scene.Motor)."""

    def __init__(self, T0, n0, wrong_slope=None):
        self.T0, self.n0, self.wrong = T0, n0, wrong_slope

    def torque(self, n):
        slope = -2 * self.T0 * n / self.n0**2 if self.wrong is None else self.wrong
        return self.T0 * (1 - (n / self.n0) * (n / self.n0)), slope   # no ** overflow


def test_motor_runs_up_to_its_steady_speed_step_by_step():
    """A drum J = 2 driven through a gear i = 3 by a motor M(n) = T0 (1 - (n/n0)^2)
    (T0 = 100, n0 = 30) against a constant torque L = 150, from rest (two motors of
    T0 / 2 each on the drum): each step's speed
    solves beta v1^2 + J v1 - Q = 0 (beta = h/2 i^3 T0 / n0^2, Q = J v0 + h/2 (f(v0) +
    i T0 - L)), its positive root, and x1 = x0 + h/2 (v0 + v1): to 1e-12 relative (the
    Newton loop stops at 1e-13); the speed reaches (n0/i) sqrt(1 - L/(i T0)) = 7.07; the
    work of the motor and the load torques balances the kinetic energy (1e-12)."""
    J, i, T0, n0, L, h = 2.0, 3.0, 100.0, 30.0, 150.0, 0.01
    eq = Equations(M=np.array([[J]]), K=np.zeros((1, 1)), F0=np.array([-L]),
                   motors=[MotorLoad(np.array([1.0]), QuadraticMotor(T0 / 2, n0), i),
                           MotorLoad(np.array([1.0]), QuadraticMotor(T0 / 2, n0), i)])
    rec = Recorder()
    st = Stepper(eq, 100.0, 1.0, rec)
    st.run(0.5, h)
    t, x, v, a = rec.arrays()

    def f(vv):
        return i * T0 * (1 - (i * vv / n0)**2) - L
    beta = h / 2 * i**3 * T0 / n0**2
    xs, vs = [0.0], [0.0]
    for _ in range(50):
        Q = J * vs[-1] + h / 2 * (f(vs[-1]) + i * T0 - L)
        v1 = (-J + math.sqrt(J * J + 4 * beta * Q)) / (2 * beta)
        xs.append(xs[-1] + h / 2 * (vs[-1] + v1))
        vs.append(v1)
    np.testing.assert_allclose(v[:, 0], vs, rtol=1e-12)
    np.testing.assert_allclose(x[:, 0], xs, rtol=1e-12)
    np.testing.assert_allclose(a[:, 0], [f(vv) / J for vv in vs], rtol=0, atol=1e-9)
    assert v[-1, 0] == pytest.approx(10 * math.sqrt(0.5), rel=1e-4)
    assert st.energy["work_loads"] == pytest.approx(0.5 * J * v[-1, 0]**2, rel=1e-12)
    assert st.energy_error()[0] < 1e-12


def test_motor_newton_that_cannot_converge_is_an_analysis_error():
    """A drive with a linear motor M = T0 (1 - n/n0) whose slope is reported as +30 N m s
    (the true one is -T0/n0 = -3.3): the iteration on the first step multiplies its
    error by (d' - d) / (4 J / h^2 + d') with d' = -(2/h) i^2 30 = -54000, d = +6000
    and 4 J / h^2 = 80000, i.e. by -2.3: it stays finite (2.3^50 = 1e18) and does not
    converge in 50 iterations; an AnalysisError names the step's end time."""
    eq = Equations(M=np.array([[2.0]]), K=np.zeros((1, 1)), F0=np.array([-150.0]),
                   motors=[MotorLoad(np.array([1.0]), LinearMotor(100.0, 30.0, 30.0),
                                     3.0)])
    with pytest.raises(AnalysisError) as e:
        Stepper(eq, 100.0, 1.0).run(0.5, 0.01)
    assert str(e.value) == ("the motor characteristic did not converge at t = 0.01 s; "
                            "give a smaller time_step")


def test_unbounded_growth_is_an_analysis_error_at_its_step():
    """A negative stiffness k = -1e6 (m = 1): the rule's growth factor per step
    (1 + w h/2)/(1 - w h/2) = 39 (w h / 2 = 0.95): x passes 1e100 times the length scale
    0.001 in the step that the Cayley recurrence says; the error names it."""
    h = 0.5 / math.ceil(0.5 / 0.0019)                  # the grid step run() makes
    eq = Equations(M=np.array([[1.0]]), K=np.array([[-1e6]]), F0=np.array([1.0]))
    A = np.array([[0.0, 1.0], [1e6, 0.0]])
    z, n = np.zeros(2), 0
    f = np.array([0.0, 1.0])
    while abs(z[0]) < 1e100 * 1e-3:
        z = cayley(A, z, f, f, h)
        n += 1
    with pytest.raises(AnalysisError) as e:
        Stepper(eq, 1.0, 1e-3).run(0.5, 0.0019)
    assert str(e.value) == (
        f"the response grows without bound (overflows) in the step from t = "
        f"{(n - 1) * h:.6g} s to {n * h:.6g} s; check the loads, drive torques and speeds, "
        "the duration and the time step")


def test_an_active_set_that_keeps_switching_is_kept_with_a_warning():
    """A contact whose two states contradict each other: an indefinite mass matrix
    M = [[1, 2], [2, 1]] (not physical; it only provokes the guard), contact on
    coordinate 0, weights -10 N on both, dashpots. On, the ground must pull (reaction
    2 F1 - F0 = -10 N: lift-off); off, the coordinate falls ((2 F1 - F0) / 3 < 0:
    landing), at the same instant. After CHATTER = 25 switches (lift-off first: 13
    lift-offs, 12 landings) the step is taken as it is, off the ground: x after the first
    step is the free system's Cayley step (1e-12 relative); one warning per step naming
    its time; every step starts such a series again (the count is reset by a step)."""
    M, K, F = np.array([[1.0, 2.0], [2.0, 1.0]]), np.diag([100.0, 100.0]), np.array(
        [-10.0, -10.0])
    C = np.diag([0.5, 0.3])
    eq = Equations(M=M, K=K, C=C, F0=F, contacts=np.array([0]), up=np.array([1.0]))
    rec = Recorder()
    st = Stepper(eq, 10.0, 1.0, rec)
    st.run(0.03, 0.01)
    assert st.warnings == [f"chattering at t = {t:.6g} s: the active set keeps switching; "
                           "kept as it is" for t in (0, 0.01, 0.02)]
    assert len(st.events) == 75
    assert [w for _, _, w in st.events[:25]] == ["lift-off", "landing"] * 12 + ["lift-off"]
    assert {t for t, _, _ in st.events[:25]} == {0.0} and st.lift_off == {0: 0.0}
    A = np.block([[np.zeros((2, 2)), np.eye(2)],
                  [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    f = np.r_[0, 0, np.linalg.solve(M, F)]
    z1 = cayley(A, np.zeros(4), f, f, 0.01)
    t, x, v, a = rec.arrays()
    np.testing.assert_allclose(x[1], z1[:2], rtol=1e-12)
    np.testing.assert_allclose(v[1], z1[2:], rtol=1e-12)
    assert x[1, 0] < 0                               # below the ground: kept as it is


def test_energy_error_is_the_balance_over_its_largest_term():
    """energy_error() = |E1 - E0 - W - Wd + D + L| / max(|E0|, |E1|, |W|, |Wd|, D, L)
    (docs/transient.md) on numbers set by hand, each term in turn the largest, and all
    below 1 J (the floor 1e-300 only guards a zero scale): E1 = 1/2 m v^2 + 1/2 k x^2 of
    a final state set by hand."""
    eq = Equations(M=np.array([[2.0]]), K=np.array([[8.0]]))
    st = Stepper(eq, 1.0, 1.0)
    st.final = type("S", (), {"x": np.array([0.1]), "v": np.array([0.2])})()
    E1 = 0.5 * 2.0 * 0.04 + 0.5 * 8.0 * 0.01                         # 0.08
    terms = ["E0", "work_loads", "work_drives", "dissipated", "impact_loss"]
    for big in [None] + terms:
        vals = dict(E0=0.01, work_loads=0.02, work_drives=-0.03, dissipated=0.004,
                    impact_loss=0.005)
        if big is not None:
            vals[big] = 0.5 if big != "work_drives" else -0.5
        st.E0 = vals.pop("E0")
        st.energy = vals
        err, e1 = st.energy_error()
        lhs = E1 - st.E0
        rhs = vals["work_loads"] + vals["work_drives"] - vals["dissipated"] \
            - vals["impact_loss"]
        scale = 0.5 if big is not None else E1
        assert e1 == pytest.approx(E1, rel=1e-15)
        assert err == pytest.approx(abs(lhs - rhs) / scale, rel=1e-13), big
    # nothing moves, no work: the balance is 0 (not 0/0)
    st.final = type("S", (), {"x": np.array([0.0]), "v": np.array([0.0])})()
    st.E0 = 0.0
    st.energy = dict.fromkeys(terms[1:], 0.0)
    assert st.energy_error() == (0.0, 0.0)
