"""Joint coordinates with moving joints below them (docs/operations.md, "Joint
coordinates", References 10): a torque-free slewing jib with the trolley running out at
a constant speed (angular momentum about the axis), a slewing torque and a trolley force
in series against an independent Lagrangian, a bead free on a swinging boom (energy, its
order of convergence), a pendulum body on a trolley with a trapezoidal profile (the
carried acceleration's jumps: the reference and the energy error's order), the Newton
tangent against finite differences, and a load without sway guided by a free trolley."""

from itertools import pairwise

import numpy as np
import scipy.linalg as sla
import pytest
from test_operation import scene
from scipy.integrate import solve_ivp

from cranefe.analysis.operation.integrate import Stepper, simulate
from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse
from cranefe.model import load

G = 9.81

# a jib slewing about the vertical axis through O, a trolley on it along x (its com
# C_Y off the slider's axis: the two coordinates couple in the mass matrix)
ARM = """cranefe: 1
name: slewing jib with a trolley
nodes:
  O: [0, 0, 0]
  T: [0, 0, 30]
  K: [10, 0, 30]
ground: [O]
bodies:
  jib: {mass: 4000, com: [12, 0, 30], inertia: [1.0e3, 2.0e5, 3.0e5], nodes: [O, T]}
  trolley: {mass: 600, com: [10, C_Y, 30.5], inertia: [40, 50, 70], nodes: [K]}
joints:
  - {name: slew, type: hinge, bodies: [ground, jib], at: O, axis: [0, 0, 1]}
  - {name: travel, type: slider, bodies: [jib, trolley], at: K, axis: [1, 0, 0],
     range: [-9, 60]}
"""
J_JIB = 3.0e5 + 4000 * 12**2          # about the axis: Izz + m (cx^2 + cy^2)
M_T, I_T = 600.0, 70.0


def start(model, speeds):
    """The static state with the joint coordinates' speeds (rad/s or m/s) given."""
    mech = Mechanism(model, parse(model))
    v = np.zeros(mech.n)
    for c, (jc, w) in enumerate(zip(mech.jc, speeds)):
        v[mech.nc + c] = w * jc["rho"]
    return mech, {"q": mech.q0.copy(), "v": v}


def test_torque_free_slewing_with_the_trolley_running_out_keeps_angular_momentum(
        tmp_path):
    """No torque on the slewing (torque 0), the trolley driven outward at constant speed
    v by a profile (a moving joint below the joint coordinate): the angular momentum
    about the vertical axis J(r) w is conserved (the slider's force is internal to the
    turning body and gravity is parallel to the axis), J(r) = J_jib + I_t + m (r^2 + c^2)
    with r = 10 + v t the trolley's com radius along the jib and c its offset across:
    w = w0 J(r0) / J(r), and with A = J_jib + I_t + m c^2, k = sqrt(m / A),
    phi = w0 J(r0) / (v sqrt(A m)) (atan(k r) - atan(k r0)). The speed halves over the
    20 s. The trapezoidal rule's global error falls as h^2 (measured, speed / w0, angle,
    energy: 1.0e-6, 2.1e-6 rad, 9.5e-7 at tolerance 1e-9; 2.2e-7, 4.7e-7, 2.1e-7 at
    1e-10; 5.0e-8, 1.0e-7, 4.8e-8 at 1e-11): asserted at 1e-10 with a factor 2."""
    v, w0, c = 1.5, 0.2, 0.0
    path = scene(tmp_path, ARM, "  duration: 20\n  tolerance: 1.0e-10\n  drives:\n"
                 "    s: {hinge: slew, torque: 0}\n"
                 f"    t: {{slider: travel, profile: {{type: table, speed: [[0, {v}]]}}}}\n",
                 C_Y=c)
    model = load(path)
    _, init = start(model, [w0])
    res = simulate(model, initial=init)
    t = res.times
    A = J_JIB + I_T + M_T * c**2
    r = 10 + v * t
    Jr = A + M_T * r**2
    w = w0 * Jr[0] / Jr
    k = np.sqrt(M_T / A)
    phi = w0 * Jr[0] / (v * np.sqrt(A * M_T)) * (np.arctan(k * r) - np.arctan(k * 10))
    i = res.drive_names.index("s")
    np.testing.assert_allclose(res.drive_speed[:, i], w, atol=5e-7 * w0)
    np.testing.assert_allclose(res.drive_position[:, i], phi, atol=1e-6)
    assert w[-1] < 0.55 * w0
    assert res.drive_position[:, res.drive_names.index("t")][-1] == pytest.approx(v * 20)
    # the energy balance: the profile's power on the trolley int (x'' - g) . x_t dm
    # feeds the kinetic energy the slewing loses (J w^2 / 2 falls as 1 / J)
    assert res.energy_error < 5e-7


def lagrange_arm(t_end, M, F, c, y0, t_eval):
    """The slewing jib with its trolley by Lagrange's equations written out by hand:
    the trolley's com at (r, c) in the jib's frame turned by phi,
    T = 1/2 A phi'^2 + 1/2 m ((r' - c phi')^2 + r^2 phi'^2), A = J_jib + I_t, so
        (A + m (r^2 + c^2)) phi'' - m c r'' = M - 2 m r r' phi'
        -m c phi'' + m r''                  = F + m r phi'^2
    (y = (phi, r, phi', r'))."""
    A, m = J_JIB + I_T, M_T

    def f(_, y):
        _, r, w, rd = y
        Mm = np.array([[A + m * (r * r + c * c), -m * c], [-m * c, m]])
        acc = np.linalg.solve(Mm, [M - 2 * m * r * rd * w, F + m * r * w * w])
        return [w, rd, acc[0], acc[1]]
    return solve_ivp(f, (0, t_end), y0, method="DOP853", rtol=1e-12, atol=1e-12,
                     t_eval=t_eval).y


def test_slewing_torque_and_trolley_force_in_series_equal_lagrange(tmp_path):
    """Two joint coordinates in series (a slewing torque M and a trolley force F, the
    trolley's com c = 1.5 m off its axis: the mass matrix couples them, M_12 = -m c; with
    c = 0 the same code runs without the coupling, measured alike) against
    Lagrange's equations integrated by DOP853 at 1e-12 (lagrange_arm), from a turning
    start with the trolley moving in (it turns back and runs out 16 m, the jib turns by
    1.36 rad): the engine's error falls as h^2 (measured for c = 0 / 1.5: angle 1.1e-6 /
    1.1e-6 rad, travel 2.2e-5 / 2.1e-5 m, energy 3.6e-7 / 3.5e-7 at tolerance 1e-9;
    2.4e-7 / 2.5e-7, 4.8e-6 / 4.5e-6, 7.7e-8 / 7.5e-8 at 1e-10; 5.1e-8, 1.0e-6, 1.6e-8
    at 1e-11): asserted at 1e-10 with a factor 2."""
    M, F, c = 2.0e4, 200.0, 1.5
    path = scene(tmp_path, ARM, "  duration: 8\n  tolerance: 1.0e-10\n  drives:\n"
                 f"    s: {{hinge: slew, torque: {M}}}\n"
                 f"    t: {{slider: travel, force: {F}}}\n", C_Y=c)
    model = load(path)
    mech, init = start(model, [0.1, -0.5])
    assert mech.nJ == 2
    res = simulate(model, initial=init)
    t = res.times
    phi, r, _, _ = lagrange_arm(8.0, M, F, c, [0.0, 10.0, 0.1, -0.5], t)
    i, k = res.drive_names.index("s"), res.drive_names.index("t")
    np.testing.assert_allclose(res.drive_position[:, i], phi, atol=5e-7)
    np.testing.assert_allclose(res.drive_position[:, k], r - 10, atol=1e-5)
    assert res.energy_error < 1.5e-7


BEAD = """cranefe: 1
name: bead on a swinging boom
plane: xz
nodes:
  A: [0, 0, 10]
  K: [6, 0, 10]
ground: []
bodies:
  boom: {mass: 800, com: [5, 0, 10], inertia: 2000, nodes: [A]}
  bead: {mass: 300, com: [6, 0, 10.2], inertia: 20, nodes: [K]}
joints:
  - {name: luff, type: hinge, bodies: [ground, boom], at: A, axis: [0, 1, 0]}
  - {name: run, type: slider, bodies: [boom, bead], at: K, axis: [1, 0, 0],
     range: [-5.5, 30]}
"""


@pytest.mark.parametrize("bead", ["{slider: run, force: 0}",
                                  ("{slider: run, profile: {type: trapezoid, distance: 4, "
                                   "v_max: 2, a_max: 4, start: 0.2}}")])
def test_bead_on_a_swinging_boom_keeps_its_energy_at_order_two(tmp_path, bead):
    """A boom on a horizontal hinge, free (torque 0), and a bead on it, released from
    rest under gravity. (a) The bead free too (force 0): a conservative system with a
    configuration-dependent, coupled mass matrix (the bead's radius changes the boom's
    inertia, its com off the rail couples them); the boom falls 1.42 rad and the bead
    runs out 10.5 m in 1.6 s. (b) The bead driven out 4 m by a trapezoid (acceleration
    steps of 4 m/s^2) along the falling boom: a prescribed child, whose relative
    acceleration jumps act on the boom through Kane's term, and whose power
    int (x'' - g) . x_t dm the balance books (x_t the bead's velocity along the rail).
    The trapezoidal rule keeps the balance to its own error, which falls as
    h^2 ~ tolerance^(2/3) (x4.6 per decade; measured (a) 1.2e-5, 2.6e-6, 5.7e-7,
    (b) 2.3e-5, 5.0e-6, 1.1e-6 at tolerances 1e-7, 1e-8, 1e-9): asserted < 1e-5 at 1e-8
    and the observed order in the steps 2 +- 0.5."""
    errs, steps = [], []
    free = "force" in bead
    for tol in (1e-7, 1e-8, 1e-9):
        path = scene(tmp_path, BEAD, f"  duration: {1.6 if free else 3}\n  tolerance: "
                     f"{tol}\n  drives:\n    l: {{hinge: luff, torque: 0}}\n"
                     f"    b: {bead}\n", name=f"s{tol}.yaml")
        res = simulate(load(path))
        errs.append(res.energy_error)
        steps.append(res.to_dict()["steps"])
        if tol == 1e-8:
            assert res.energy_error < 1e-5
    # the boom fell a good way and the bead ran out along it
    assert res.drive_position[-1, 0] > 1.4
    assert res.drive_position[-1, 1] == pytest.approx(10.5 if free else 4.0, abs=0.05)
    order = -np.polyfit(np.log(steps), np.log(errs), 1)[0]
    assert 1.5 < order < 2.5, (errs, steps)


PEND = """cranefe: 1
name: pendulum body on a trolley
plane: xz
nodes:
  G: [0, 0, 20]
  K: [0, 0, 20]
  B: [0, 0, 15]
ground: [G]
bodies:
  trolley: {mass: 1000, com: [0, 0, 20], inertia: 50, nodes: [K]}
  arm: {mass: 500, com: [0, 0, 16], inertia: 300, nodes: [B]}
joints:
  - {name: travel, type: slider, bodies: [ground, trolley], at: G, axis: [1, 0, 0],
     range: [-50, 50]}
  - {name: swing, type: hinge, bodies: [trolley, arm], at: K, axis: [0, 1, 0]}
"""
TRAP = "{type: trapezoid, distance: 3, v_max: 1, a_max: 0.5, start: 0.5}"


def _pendulum_on_trapezoid(t_eval):
    """(m d^2 + I) phi'' = m d s''(t) cos(phi) - m g d sin(phi) (Lagrange: the arm's com
    at K + (-d sin phi, -d cos phi), d = 4 m, I = 300 kg m^2 about its com), s'' the
    trapezoid's piecewise constant acceleration, integrated segment by segment (DOP853,
    1e-12)."""
    m, d, I = 500.0, 4.0, 300.0
    bps = [0.0, 0.5, 2.5, 3.5, 5.5, 7.0]
    acc = [0.0, 0.5, 0.0, -0.5, 0.0]
    y = [0.0, 0.0]
    out = np.zeros((2, len(t_eval)))
    for (a, b), s2 in zip(pairwise(bps), acc):
        sel = (t_eval >= a) & (t_eval <= b)
        sol = solve_ivp(lambda _, z, s2=s2: [z[1], (m * d * s2 * np.cos(z[0]) - m * G * d *
                                                    np.sin(z[0])) / (m * d * d + I)],
                        (a, b), y, method="DOP853", rtol=1e-12, atol=1e-14,
                        t_eval=t_eval[sel], dense_output=True)
        out[:, sel] = sol.sol(t_eval[sel])
        y = sol.sol(b)
    return out


def test_pendulum_body_on_a_trapezoidal_trolley_move(tmp_path):
    """A body hanging on a torque-free hinge below a trolley driven by a trapezoid
    (acceleration steps of 0.5 m/s^2 at 0.5, 2.5, 3.5 and 5.5 s): the carried
    acceleration acts on the joint coordinate through Kane's term, so it jumps at the
    breakpoints; a step ending at one sees it from the left, the next starts from the
    right. Against Lagrange's equation integrated segment by segment (swing up to
    0.17 rad), the error falls as h^2 (measured angle / speed error 4.5e-5 / 8.0e-5,
    1.1e-5 / 1.9e-5, 2.3e-6 / 4.1e-6, 5.2e-7 / 9.0e-7 at tolerance 1e-7 .. 1e-10):
    asserted at 1e-9 with a factor 2. The energy balance (the profile's power on the
    arm int (x'' - g) . x_t dm) converges at order 2 in the steps (measured 5.0e-5,
    1.1e-5, 2.4e-6, 5.1e-7; audit: with the right limits at a step's end it stalled at
    first order). 6 s (0.5 s past the last breakpoint) instead of 7 s: 0.82 of the
    steps; measured at 1e-9 angle / speed error 2.4e-6 / 3.0e-6, energy 5.0e-5, 1.1e-5,
    2.4e-6 at 1e-7 .. 1e-9 (order 2.04), the swing's peak 0.168 rad as over 7 s."""
    errs, steps = [], []
    for tol in (1e-7, 1e-8, 1e-9):
        path = scene(tmp_path, PEND, f"  duration: 6\n  tolerance: {tol}\n"
                     "  output_step: 0.05\n  drives:\n"
                     f"    tr: {{slider: travel, profile: {TRAP}}}\n"
                     "    sw: {hinge: swing, torque: 0}\n", name=f"p{tol}.yaml")
        res = simulate(load(path))
        errs.append(res.energy_error)
        steps.append(res.to_dict()["steps"])
    ref = _pendulum_on_trapezoid(res.times)
    k = res.drive_names.index("sw")
    np.testing.assert_allclose(res.drive_position[:, k], ref[0], atol=5e-6)
    np.testing.assert_allclose(res.drive_speed[:, k], ref[1], atol=8e-6)
    assert np.abs(ref[0]).max() > 0.15          # it swung
    order = -np.polyfit(np.log(steps), np.log(errs), 1)[0]
    assert 1.6 < order < 2.5, (errs, steps)
    assert errs[-1] < 5e-6


def _residual(mech, st, t, q, v, a, taut):
    ev = mech.evaluate(t, q, v, taut)
    return ev.F - st.inertia(ev, a), ev


@pytest.mark.parametrize("left", [False, True])
def test_newton_tangent_equals_finite_differences(tmp_path, left):
    """The Newton tangent of the residual F(t, q, q') - M(q, t) a at a moving state of a
    slewing jib (torque) carrying a trolley (force, com off its axis) with a load
    swinging on its rope, at random (q, q', a), also with the prescribed side limits:
    -dR/dq = K + dM/dq a (the rope's elastic and tension stiffness through the moving
    joints, gravity, Kane's terms' position derivatives and the mass matrix's) and
    -dR/dq' = C (Kane's Coriolis/centrifugal velocity derivative) against central
    differences (step 1e-6: truncation ~1e-12, round-off ~1e-10 relative; asserted
    1e-6 of the largest entry)."""
    text = ARM.replace("  K: [10, 0, 30]\n", "  K: [10, 0, 30]\n  H: [10, 0, 20]\n") \
        .replace("ground: [O]\n", "ground: [O]\nmasses: {H: 2000}\n") + \
        "ropes:\n  hoist: {EA: 1.0e8, path: [K, H]}\n"
    path = scene(tmp_path, text, "  duration: 5\n  drives:\n"
                 "    s: {hinge: slew, torque: 1000}\n"
                 "    t: {slider: travel, force: 50}\n", C_Y=0.8)
    model = load(path)
    mech = Mechanism(model, parse(model))
    st = Stepper(mech, parse(model), model.length_scale, fast=False)
    rng = np.random.default_rng(3)
    n = mech.n
    q = mech.q0 + 0.3 * rng.standard_normal(n)
    v = 0.4 * rng.standard_normal(n)
    a = 0.5 * rng.standard_normal(n)
    taut = mech.taut0
    t = 1.3
    mech.left_at = t if left else None
    _, ev = _residual(mech, st, t, q, v, a, taut)
    Jq = ev.K.copy()
    jd = st.jd
    Jq[jd, jd] += np.einsum("ijk,j->ik", ev.dMJ, a[jd])
    fd_q, fd_v = np.zeros((n, n)), np.zeros((n, n))
    for k in range(n):
        d = 1e-6
        e = np.zeros(n)
        e[k] = d
        fd_q[:, k] = -(_residual(mech, st, t, q + e, v, a, taut)[0] -
                       _residual(mech, st, t, q - e, v, a, taut)[0]) / (2 * d)
        fd_v[:, k] = -(_residual(mech, st, t, q, v + e, a, taut)[0] -
                       _residual(mech, st, t, q, v - e, a, taut)[0]) / (2 * d)
    np.testing.assert_allclose(Jq, fd_q, atol=1e-6 * np.abs(fd_q).max())
    np.testing.assert_allclose(ev.C, fd_v, atol=1e-6 * np.abs(fd_v).max())
    assert np.abs(ev.C[jd, jd]).max() > 1.0           # there is something to test
    assert np.abs(ev.dMJ).max() > 1.0


CART = """cranefe: 1
name: cart with a load
plane: xz
nodes:
  G: [0, 0, 20]
  K: [0, 0, 20]
  H: [0, 0, 10]
ground: []
masses: {H: 2000}
bodies:
  trolley: {mass: 1000, com: [0, 0, 20.5], inertia: 50, nodes: [G, K]}
joints:
  - {name: travel, type: slider, bodies: [ground, trolley], at: G, axis: [1, 0, 0],
     range: [-50, 50]}
ropes:
  hoist: {EA: 1.0e8, path: [K, H]}
"""


def test_sway_off_load_guided_by_a_free_trolley_rides_on_its_joint(tmp_path):
    """With sway off the load hangs vertically below the trolley, so its horizontal
    inertia rides on the trolley's slider: under a force F the trolley and the load move
    together, s = F t^2 / (2 (M + m)) (the trapezoidal rule integrates a constant
    acceleration exactly: 1e-10 of the travel), the load's height stays its own
    coordinate at rest on its rope, and the work F s is the kinetic energy
    (M + m) s'^2 / 2 (energy error at round-off)."""
    F = 1500.0
    path = scene(tmp_path, CART, "  duration: 10\n  drives:\n"
                 f"    c: {{slider: travel, force: {F}}}\n",
                 effects="{sway: false}")
    res = simulate(load(path))
    t = res.times
    s = F * t**2 / (2 * 3000)
    np.testing.assert_allclose(res.drive_position[:, 0], s, atol=1e-10 * s[-1])
    np.testing.assert_allclose(res.mass_position[:, 0, 0], s, atol=1e-10 * s[-1])
    np.testing.assert_allclose(res.mass_position[:, 0, 2], 10.0, atol=1e-9)
    assert res.energy["kinetic_final"] == pytest.approx(F * s[-1], rel=1e-9)
    assert res.energy_error < 1e-9
    assert res.coordinates[-1] == "joint c"


def test_sway_off_load_on_a_trolley_running_out_along_a_torque_free_slewing_jib(tmp_path):
    """The torque-free slewing jib with its trolley running out at constant speed v
    (profile) and a load of mass m_L hanging on its rope below the trolley without
    sway: the load's horizontal inertia rides on the slewing joint at the trolley's
    radius, so the angular momentum (J_jib + I_t + (m_t + m_L) r^2) w is conserved
    (r = 10 + v t; the rope and the slider's forces are internal, gravity parallel to
    the axis): w = w0 J(r0) / J(r) as in the first test with m = m_t + m_L; the load
    stays at its height (its own coordinate, at rest on its rope) and turns with the
    jib. At tolerance 1e-10 the speed to 5e-7 of w0 (the same error as without the
    load)."""
    v, w0, mL = 1.5, 0.2, 2000.0
    text = ARM.replace("  K: [10, 0, 30]\n", "  K: [10, 0, 30]\n  H: [10, 0, 20]\n") \
        .replace("ground: [O]\n", f"ground: [O]\nmasses: {{H: {mL}}}\n") + \
        "ropes:\n  hoist: {EA: 1.0e8, path: [K, H]}\n"
    path = scene(tmp_path, text, "  duration: 10\n  tolerance: 1.0e-10\n  drives:\n"
                 "    s: {hinge: slew, torque: 0}\n"
                 f"    t: {{slider: travel, profile: {{type: table, speed: [[0, {v}]]}}}}\n",
                 effects="{sway: false}", C_Y=0.0)
    model = load(path)
    mech, init = start(model, [w0])
    assert mech.guided_joint.all()
    res = simulate(model, initial=init)
    t = res.times
    r = 10 + v * t
    Jr = J_JIB + I_T + (M_T + mL) * r**2
    w = w0 * Jr[0] / Jr
    i = res.drive_names.index("s")
    np.testing.assert_allclose(res.drive_speed[:, i], w, atol=5e-7 * w0)
    phi = res.drive_position[:, i]
    X = res.mass_position[:, 0]
    np.testing.assert_allclose(X[:, 0], r * np.cos(phi), atol=1e-9 * r[-1])
    np.testing.assert_allclose(X[:, 1], r * np.sin(phi), atol=1e-9 * r[-1])
    np.testing.assert_allclose(X[:, 2], X[0, 2], atol=1e-9)
    assert res.energy_error < 5e-7


LUFF_TROLLEY = """cranefe: 1
name: boom on its luffing rope with a trolley held on it
plane: xz
nodes:
  F: [0, 0, 0]
  T: [0, 0, 15]
  B: [16, 0, 12]
  K: [8, 0, 6]
  H: [8, 0, -2]
ground: [F, T]
masses: {H: 1000}
bodies:
  boom: {mass: 3000, com: [8, 0, 6], inertia: 1.0e5, nodes: [F, B]}
  trolley: {mass: 500, com: [8, 0, 6.3], inertia: 30, nodes: [K]}
joints:
  - {name: luff, type: hinge, bodies: [ground, boom], at: F, axis: [0, 1, 0]}
  - {name: run, type: slider, bodies: [boom, trolley], at: K, axis: [0.8, 0, 0.6],
     range: [-5, 5]}
ropes:
  luffing: {EA: 1.0e8, path: [T, B]}
  holding: {EA: 5.0e7, path: [B, K]}
  hoist: {EA: 1.0e8, path: [K, H]}
"""


def test_linearised_chain_is_the_energy_hessian_and_near_the_linear_core(tmp_path):
    """A free boom on its luffing rope carrying a free trolley held up its inclined rail
    by a rope to the tip, a load on the trolley (two joint coordinates in series, the
    rail turning with the boom). At the static state the engine's mass matrix is the
    Hessian of its kinetic energy (1/2 int |x'|^2 dm from the velocities, by central
    differences: 1e-10) and its force the negative gradient of its potential energy
    (gravity and Hencky ropes from the positions, at a displaced state: 1e-6, the
    differences' round-off); with the tangent (= -dF/dq, test above) the linearisation
    is exact. `cranefe modes` of the same model: the load's pendulum to 1e-7, the three
    rope-borne modes to 1e-4 (measured 3.8e-5, 4.4e-5, 5.4e-6: the linear core, whose
    joints are linear constraints, differs there; without the load and the trolley's
    com offset they agree to 2e-9)."""
    from cranefe.analysis.modal import modes
    path = scene(tmp_path, LUFF_TROLLEY, "  duration: 5\n  drives:\n"
                 "    b: {hinge: luff, free: true}\n    t: {slider: run, free: true}\n")
    model = load(path)
    mech = Mechanism(model, parse(model))
    n, q0, taut = mech.n, mech.q0, mech.taut0
    ev = mech.evaluate(0.0, q0, np.zeros(n), taut)
    assert np.abs(ev.F).max() < 1e-8 * 1000 * G * 10
    M = mech.mass_matrix(ev)

    def kinetic(v):
        return mech.energy(mech.evaluate(0.0, q0, v, taut), taut)[0]

    def potential(q):
        _, Vg, U = mech.energy(mech.evaluate(0.0, q, np.zeros(n), taut), taut)
        return Vg + U
    I = np.eye(n)
    Mh = np.array([[(kinetic(I[i] + I[j]) - kinetic(I[i] - I[j])) / 2 for j in range(n)]
                   for i in range(n)])             # T quadratic in v: exact differences
    np.testing.assert_allclose(Mh, M, atol=1e-10 * np.abs(M).max())
    assert abs(M[2, 3]) > 1.0                       # the coordinates couple
    q = q0 + 0.02 * np.random.default_rng(1).standard_normal(n)
    F = mech.evaluate(0.0, q, np.zeros(n), taut).F
    grad = np.array([(potential(q + 1e-6 * I[i]) - potential(q - 1e-6 * I[i])) / 2e-6
                     for i in range(n)])
    np.testing.assert_allclose(F, -grad, atol=1e-6 * np.abs(grad).max())
    w = np.sort(np.sqrt(np.abs(sla.eigvals(ev.K, M).real)))
    lin = np.sort(modes(model).omega)
    assert len(w) == len(lin) == 4
    assert w[0] == pytest.approx(lin[0], rel=1e-7)
    np.testing.assert_allclose(w[1:], lin[1:], rtol=1e-4)
