"""Value tests of cranefe/analysis/operation/lean.py (issue 20, mutation testing): `Lean`,
the integrator's fast view of a mechanism, and `Generic`, Mechanism's own methods
behind the same interface.

- the trolley pendulum (a load on an elastic rope from a trolley on a driven slider,
  a dashpot on the rope) by hand: the force F = m g - (S + S_d) e with
  S = EA ln(L/L0), L0 = L_ref exp(-m g/EA), S_d = b e.(v - V_K),
  b = psi c / (2 pi w), c = EA/L, w^2 = c/m (docs/operations.md "Mechanics"), the
  tangent K = -dF/dq by central differences of that hand force, C = b e e^T, the
  energies (1/2 m v^2, -F_g.q, Hencky EA (L ln(L/L0) - L + L0)), the trolley's power
  -(S + S_d) e.V_K and the dashpot's S_d e'; sway off: the guided load's kinetic
  energy 1/2 m V_K^2;
- a winch (a drum turned by a profile, two falls, an extra length) by hand:
  L0 = L0_ref - R theta / lambda_ref, the drum's power R (S + S_d) omega and the power
  the wound rope carries onto the drum, S R omega - dU/dt|winding;
- the reference implementation (mechanism.py's evaluate/powers/energy/place, itself
  mutation-tested against hand values: docs/mutation.md) on scenes that reach every
  branch: a slewing jib with a trolley on it (a slider on a hinge), a boom luffed on a
  slewing tower (a hinge on a hinge), an undriven joint on a driven one, a joint listed
  child first, sway on and off, two ropes with one slack, damping on and off, at
  times in and after the moves. Lean rearranges the same formulas, so they agree to
  rounding: 1e-10 of each quantity's scale (a few ulps of sums of O(10) terms).

Tolerances of the hand values: 1e-9 relative (closed forms in double precision; the
strain ln(L/L0) of 1e-3 loses 3 digits); central differences with step 1e-6 m: bound
1e-6 relative (truncation h^2 |F'''| ~ 1e-12 of EA/L, round-off 1e-16 |F| / h).
"""

import numpy as np
import pytest
from test_mutation_kills_integrate import DROP2
from test_mutation_kills_mechanism import (LUFF_ON_SLEW, SLEWING, TROLLEY, WINCH,
                                           _pendulum_force, _scene_mech, _trolley,
                                           trolley_xs)

from cranefe.analysis.operation import lean as lean_mod
from cranefe.analysis.operation.lean import Generic, Lean, ops

G = 9.81
RTOL = 1e-9
REF = 1e-10          # Lean against Mechanism: the same formulas rearranged


# ----------------------------------------------------------------- hand values

@pytest.mark.parametrize("t", [0.5, 1.5, 3.5])
def test_trolley_pendulum_by_hand(t):
    """The trolley accelerating (0.5 s), cruising (1.5 s) and at rest (3.5 s: no
    kinematic span velocity, the dvk/vkin of _kin are None)."""
    m, EA, psi = 1000.0, 1.0e7, 0.3
    mech = _trolley(m, EA, effects="{damping: exact}")
    lean = Lean(mech)
    assert Lean.covers(mech) and isinstance(ops(mech), Lean)
    L0 = 10.0 * np.exp(-m * G / EA)
    q, v = np.array([0.7, 0.9]), np.array([0.3, -0.2])
    taut = np.array([True])
    kt = lean.kin(t)
    ev = lean.evaluate(t, q, v, taut, kt, tangent=True, full=True)
    F0, L, S = _pendulum_force(t, *q, m, EA, L0)
    xs, vs = trolley_xs(t)[:2]
    e2 = np.array([q[0] - xs, q[1] - 10.0]) / L
    c = EA / L
    b = psi * c / (2 * np.pi * np.sqrt(c / m))
    edot = e2 @ (v - [vs, 0])
    Sd = b * edot
    np.testing.assert_allclose([ev.L[0], ev.L0[0], ev.S[0], ev.Sd[0], ev.edot[0]],
                               [L, L0, S, Sd, edot], rtol=RTOL, atol=1e-12)
    np.testing.assert_allclose(ev.F, F0 - Sd * e2, rtol=RTOL)
    np.testing.assert_allclose(ev._G, [e2], rtol=RTOL, atol=1e-15)
    h = 1e-6
    Kfd = np.zeros((2, 2))
    for j in range(2):
        dq = np.zeros(2)
        dq[j] = h
        Kfd[:, j] = -(_pendulum_force(t, *(q + dq), m, EA, L0)[0]
                      - _pendulum_force(t, *(q - dq), m, EA, L0)[0]) / (2 * h)
    np.testing.assert_allclose(ev.K, Kfd, rtol=1e-6, atol=1e-6 * np.abs(Kfd).max())
    np.testing.assert_allclose(ev.C, b * np.outer(e2, e2), rtol=RTOL, atol=1e-12 * b)
    np.testing.assert_allclose(ev.X[1], [q[0], 0, q[1]], atol=0)
    np.testing.assert_allclose(ev.V[1], [v[0], 0, v[1]], atol=0)
    np.testing.assert_allclose(ev.X[0], [xs, 0, 10], atol=1e-12)
    np.testing.assert_allclose(ev.V[0], [vs, 0, 0], atol=1e-12)
    lean.powers(ev)
    assert ev.P_drive == pytest.approx(-(S + Sd) * e2[0] * vs, rel=RTOL, abs=1e-9)
    assert ev.P_diss == pytest.approx(Sd * edot, rel=RTOL)
    assert ev.P_wound == 0.0 and ev.T_guided == 0.0
    P = ev.P_drive
    assert lean.powers(ev) is ev and ev.P_drive == P            # once per Eval
    T, Vg, U = lean.energy(ev, taut)
    assert T == pytest.approx(0.5 * m * (v @ v), rel=RTOL)
    assert Vg == pytest.approx(m * G * q[1], rel=RTOL)
    assert U == pytest.approx(EA * (L * np.log(L / L0) - L + L0), rel=1e-7)
    # another taut array with the same values: the energy's general branch
    assert lean.energy(ev, np.array([True]))[2] == pytest.approx(U, rel=1e-12)
    X, V, th, om = lean.place(t, q, v)
    np.testing.assert_allclose(X, ev.X, atol=0)
    np.testing.assert_allclose(V, ev.V, atol=0)
    assert lean.span_lengths(ev)[0] == pytest.approx(np.hypot(q[0] - xs, q[1] - 10), rel=1e-14)
    # without the tangent and the node arrays: the same forces
    ev2 = lean.evaluate(t, q, v, taut, kt, tangent=False, full=False)
    assert ev2.K is None and ev2.C is None and ev2.X is None and ev2.V is None
    np.testing.assert_allclose(ev2.F, ev.F, rtol=0, atol=0)
    # slack: no force, no dashpot, no energy
    slack = np.array([False])
    evs = lean.evaluate(t, q, v, slack, kt)
    np.testing.assert_allclose(evs.F, [0, -m * G], atol=0)
    np.testing.assert_allclose(evs.K, 0.0, atol=0)
    np.testing.assert_allclose(evs.C, 0.0, atol=0)
    assert evs.S[0] == 0.0 and evs.Sd[0] == 0.0
    lean.powers(evs)
    assert evs.P_drive == 0.0 and evs.P_diss == 0.0
    assert lean.energy(evs, slack)[2] == 0.0


def test_dashpot_by_hand_with_two_ropes_one_slack():
    """Two loads on their ropes (psi 0.2 and 0.5): b = psi c / (2 pi w) per taut rope
    (w^2 = c/m), none on the slack one, whose rope carries nothing."""
    text = DROP2.replace("r1: {EA: 1.0e6,", "r1: {EA: 1.0e6, psi: 0.2,").replace(
        "r2: {EA: 1.0e6,", "r2: {EA: 2.0e6, psi: 0.5,")
    mech = _scene_mech(text, "  duration: 1\n", "{sway: false, damping: exact}")
    lean = Lean(mech)
    L0 = mech.L0_ref
    q, v = np.array([4.99, 4.97]), np.array([0.3, -0.4])
    for taut, on in ((np.array([True, True]), [1, 1]), (np.array([True, False]), [1, 0]),
                     (np.array([False, True]), [0, 1])):
        ev = lean.evaluate(0.2, q, v, taut, lean.kin(0.2))
        for k, (EA, psi) in enumerate(((1.0e6, 0.2), (2.0e6, 0.5))):
            L = 10.0 - q[k]
            S = EA * np.log(L / L0[k]) * on[k]
            c = EA / L
            b = psi * c / (2 * np.pi * np.sqrt(c / 100.0)) * on[k]
            edot = -v[k]
            assert ev.S[k] == pytest.approx(S, rel=RTOL, abs=0)
            assert ev.Sd[k] == pytest.approx(b * edot, rel=RTOL, abs=0)
            assert ev.F[k] == pytest.approx(-100 * G + S + b * edot, rel=RTOL)
            assert ev.C[k, k] == pytest.approx(b, rel=RTOL, abs=0)
            assert ev.K[k, k] == pytest.approx(c * on[k], rel=RTOL, abs=0)
        lean.powers(ev)
        assert ev.P_diss == pytest.approx(float(ev.Sd @ ev.edot), rel=RTOL)
        U = lean.energy(ev, taut)[2]
        want = sum(EA * (L * np.log(L / L0k) - L + L0k) * o for EA, L, L0k, o in
                   zip((1.0e6, 2.0e6), 10.0 - q, L0, on))
        assert U == pytest.approx(want, rel=1e-7)


def test_sway_off_guided_load_by_hand():
    m, EA, t = 1000.0, 1.0e7, 0.5
    mech = _trolley(m, EA, effects="{sway: false, damping: none}")
    lean = Lean(mech)
    L0 = 10.0 * np.exp(-m * G / EA)
    z, vz = 0.05, 0.1
    q, v = np.array([z]), np.array([vz])
    ev = lean.evaluate(t, q, v, np.array([True]), lean.kin(t))
    xs, vs = trolley_xs(t)[:2]
    L = 10.0 - z
    S = EA * np.log(L / L0)
    np.testing.assert_allclose(ev.X[1], [xs, 0, z], atol=1e-12)
    np.testing.assert_allclose(ev.V[1], [vs, 0, vz], atol=1e-12)
    np.testing.assert_allclose(ev.F, [S - m * G], rtol=RTOL)
    np.testing.assert_allclose(ev.K, [[EA / L]], rtol=RTOL)
    np.testing.assert_allclose(ev.C, [[0.0]], atol=0)
    assert ev.Sd[0] == 0.0
    lean.powers(ev)
    assert ev.T_guided == pytest.approx(0.5 * m * vs * vs, rel=RTOL)
    # the trolley moves the rope's end horizontally, normal to the vertical rope: no power
    assert ev.P_drive == pytest.approx(0.0, abs=1e-9)
    T, Vg, U = lean.energy(ev, np.array([True]))
    assert T == pytest.approx(0.5 * m * (vs * vs + vz * vz), rel=RTOL)
    assert Vg == pytest.approx(m * G * z, rel=RTOL)


def test_winch_profile_winds_rope_by_hand():
    """The drum turned at omega: L0 = L0_ref - R theta / lambda_ref; L = |WS| + 2 l +
    extra; the power of the drum R (S + S_d) omega and of the wound rope
    S R omega - dU/dt|winding, dU/dL0 = EA (1 - L/L0), dL0/dt = -R omega / lambda_ref."""
    m, EA, R, om = 1000.0, 2.0e6, 0.5, 0.4
    mech = _scene_mech(WINCH, f"  duration: 5\n  drives:\n    h: {{drum: hoist, profile: "
                       f"{{type: table, speed: [[0, {om}]]}}}}\n", "{damping: exact}")
    lean = Lean(mech)
    assert lean.wound
    S0 = m * G / 2
    Lr = 2.0 + 2 * 10.0 + 1.5
    lam = np.exp(S0 / EA)
    t = 1.5
    theta = om * t
    L0 = Lr / lam - R * theta / lam
    q, v = np.array([0.2, 30.1]), np.array([0.05, 0.3])
    taut = np.array([True])
    ev = lean.evaluate(t, q, v, taut, lean.kin(t))
    l = np.hypot(q[0], 40 - q[1])
    L = 2.0 + 2 * l + 1.5
    S = EA * np.log(L / L0)
    e = np.array([q[0], q[1] - 40]) / l
    edot = 2 * e @ v + R * om
    c = EA / L
    b = 0.2 * c / (2 * np.pi * np.sqrt(c * 4 / m))
    Sd = b * edot
    np.testing.assert_allclose([ev.L[0], ev.L0[0], ev.S[0], ev.edot[0], ev.Sd[0]],
                               [L, L0, S, edot, Sd], rtol=RTOL)
    np.testing.assert_allclose(ev.theta, [theta], rtol=RTOL)
    np.testing.assert_allclose(ev.omega, [om], rtol=RTOL)
    np.testing.assert_allclose(ev.F, np.array([0, -m * G]) - 2 * (S + Sd) * e, rtol=RTOL)
    lean.powers(ev)
    assert ev.P_drive == pytest.approx(R * (S + Sd) * om, rel=RTOL)
    assert ev.P_diss == pytest.approx(Sd * edot, rel=RTOL)
    dU = EA * (1 - L / L0) * (-R * om / lam)
    assert ev.P_wound == pytest.approx(S * R * om - dU, rel=1e-7)
    U = lean.energy(ev, taut)[2]
    assert U == pytest.approx(EA * (L * np.log(L / L0) - L + L0), rel=1e-7)
    X, V, th, omg = lean.place(t, q, v)
    np.testing.assert_allclose([th[0], omg[0]], [theta, om], rtol=RTOL)
    # slack: nothing wound carries energy, the drum does no work
    evs = lean.evaluate(t, q, v, np.array([False]), lean.kin(t))
    lean.powers(evs)
    assert evs.P_wound == 0.0 and evs.P_drive == 0.0


# ----------------------------------------------------------------- the reference

def _drives(*items):
    return "  duration: 4\n  drives:\n" + "".join(f"    {x}\n" for x in items)


SLEW = "s: {hinge: slew, profile: {type: table, speed: [[0, 0.2], [2, 0.5]]}}"
TRAVEL = ("t: {slider: travel, profile: {type: trapezoid, distance: 2, v_max: 1, "
          "a_max: 1}}")
CASES = {
    "trolley": lambda eff: (TROLLEY.replace("MASS", "1000").replace("EAVAL", "1.0e7"),
                            _drives(TRAVEL.replace("t:", "trolley:")), eff),
    "trolley child first": lambda eff: (
        TROLLEY.replace("MASS", "1000").replace("EAVAL", "1.0e7").replace(
            "bodies: [ground, trolley]", "bodies: [trolley, ground]"),
        _drives(TRAVEL.replace("t:", "trolley:")), eff),
    "slewing trolley": lambda eff: (SLEWING.replace("hoist: {EA: 1.0e8,",
                                                    "hoist: {EA: 1.0e8, psi: 0.3,"),
                                    _drives(SLEW, TRAVEL), eff),
    "slewing, trolley held": lambda eff: (SLEWING, _drives(SLEW), eff),
    "trolley on a held jib": lambda eff: (SLEWING, _drives(TRAVEL), eff),
    "luffing on slewing": lambda eff: (
        LUFF_ON_SLEW, _drives(SLEW, "l: {hinge: luff, profile: {type: table, speed: "
                              "[[0, 0.1], [2, 0.2]]}}"), eff),
    "winch": lambda eff: (WINCH, _drives("h: {drum: hoist, profile: {type: table, speed: "
                                         "[[0, 0.4], [2, -0.3]]}}"), eff),
    "two ropes": lambda eff: (DROP2.replace("r1: {EA: 1.0e6,", "r1: {EA: 1.0e6, psi: 0.2,"),
                              "  duration: 1\n", eff),
}
# a trolley carrying a load on two ropes of a V (the second reeved from the load up:
# a span whose second end is the kinematic one)
VSLING = """cranefe: 1
name: v sling
plane: xz
nodes:
  K: [-1, 0, 10]
  J: [1, 0, 10]
  H: [0, 0, 0]
masses: {H: 1000}
bodies:
  trolley: {mass: 500, com: [0, 0, 10], inertia: [10, 10, 10], nodes: [K, J]}
joints:
  - {name: travel, type: slider, bodies: [ground, trolley], at: K, axis: [1, 0, 0],
     range: [-1, 20]}
ropes:
  a: {EA: 1.0e7, psi: 0.3, path: [K, H]}
  b: {EA: 2.0e7, psi: 0.1, path: [H, J]}
"""
# a boom with a trolley on a slewing tower whose axis is off the origin: three drives
# chained (a slider on a hinge on a hinge), the parents' translations non-zero
BOOM = """cranefe: 1
name: boom trolley
nodes:
  O: [1, 2, 0]
  P: [2, 2, 20]
  T: [22, 2, 20]
  K: [12, 2, 20]
  H: [12, 2, 10]
ground: [O]
masses: {H: 1000}
bodies:
  tower: {mass: 1000, com: [1, 2, 10], inertia: [10, 10, 10], nodes: [O]}
  boom: {mass: 500, com: [12, 2, 20], inertia: [10, 10, 10], nodes: [P, T]}
  trolley: {mass: 100, com: [12, 2, 20], inertia: [1, 1, 1], nodes: [K]}
joints:
  - {name: slew, type: hinge, bodies: [ground, tower], at: O, axis: [0, 0, 1]}
  - {name: luff, type: hinge, bodies: [tower, boom], at: P, axis: [0, -1, 0]}
  - {name: travel, type: slider, bodies: [boom, trolley], at: K, axis: [1, 0, 0],
     range: [-5, 8]}
ropes:
  hoist: {EA: 1.0e8, psi: 0.2, path: [K, H]}
"""
# the winch's sheave S on a trolley: a rope wound on a profile drum over a moving sheave
WINCH_TROLLEY = WINCH.replace("ground: [W, S]", """ground: [W]
bodies:
  trolley: {mass: 500, com: [0, 0, 40], inertia: [10, 10, 10], nodes: [S]}
joints:
  - {name: travel, type: slider, bodies: [ground, trolley], at: S, axis: [1, 0, 0],
     range: [-1, 20]}""")
# the winch and a sling below its hook: the drum winds the first rope only
WINCH_SLING = WINCH.replace("  H: [0, 0, 30]\n", "  H: [0, 0, 30]\n  B: [0, 0, 25]\n").replace(
    "masses: {H: 1000}", "masses: {H: 1000, B: 500}") + \
    "  sling: {EA: 1.0e6, psi: 0.1, path: [H, B]}\n"
# a tag line: a horizontal rope from the ground to the trolley's load; without sway the
# load moves vertically only, so the tag line has no row in G (r^T M^-1 r = 0)
TAG = TROLLEY.replace("MASS", "1000").replace("EAVAL", "1.0e7").replace(
    "  H: [0, 0, 0]\n", "  H: [0, 0, 0]\n  B: [6, 0, 0]\nground: [B]\n") + \
    "  tag: {EA: 1.0e5, psi: 0.2, path: [B, H]}\n"
# a heavy load on a soft rope (w^2 = c/m = 0.5 /s^2 < 1) beside a stiff one
SOFT = """cranefe: 1
name: soft
nodes:
  A: [0, 0, 100]
  H: [0, 0, 0]
  B: [3, 0, 10]
  K: [3, 0, 5]
ground: [A, B]
masses: {H: 1.0e4, K: 100}
ropes:
  r1: {EA: 1.0e6, psi: 0.2, path: [B, K]}
  r2: {EA: 5.0e5, psi: 0.3, path: [A, H]}
"""
# a load on a running sheave: one rope of two spans, both ending at the load (its row of
# G sums two spans)
SHEAVE = """cranefe: 1
name: running sheave
plane: xz
nodes:
  A: [-1, 0, 10]
  B: [1, 0, 10]
  H: [0, 0, 0]
ground: [A, B]
masses: {H: 800}
ropes:
  r: {EA: 3.0e6, psi: 0.2, path: [A, H, B]}
"""
TRAP = "{type: trapezoid, distance: 2, v_max: 1, a_max: 1}"
CASES.update({
    "v sling": lambda eff: (VSLING, _drives(f"t: {{slider: travel, profile: {TRAP}}}"), eff),
    "boom trolley": lambda eff: (BOOM, _drives(
        "s: {hinge: slew, profile: {type: trapezoid, distance: 0.3, v_max: 0.2, a_max: 0.2}}",
        "l: {hinge: luff, profile: {type: trapezoid, distance: 0.1, v_max: 0.1, a_max: 0.2}}",
        f"t: {{slider: travel, profile: {TRAP}}}"), eff),
    "winch on a trolley": lambda eff: (WINCH_TROLLEY, _drives(
        "h: {drum: hoist, profile: {type: table, speed: [[0, 0.4], [2, -0.3]]}}",
        f"t: {{slider: travel, profile: {TRAP}}}"), eff),
    "winch and sling": lambda eff: (WINCH_SLING, _drives(
        "h: {drum: hoist, profile: {type: table, speed: [[0, 0.4], [2, -0.3]]}}"), eff),
    "tag line": lambda eff: (TAG, _drives(f"t: {{slider: travel, profile: {TRAP}}}"), eff),
    "soft rope": lambda eff: (SOFT, "  duration: 1\n", eff),
    "running sheave": lambda eff: (SHEAVE, "  duration: 1\n", eff),
})
EFFECTS = ["{damping: exact}", "{sway: false, damping: exact}", "{damping: none}"]
# every case with every effect (the V sling's and the sheave's loads are off the vertical
# below their ropes' ends: sway on only)
PAIRS = [(c, e) for c in CASES for e in EFFECTS
         if not (c in ("v sling", "running sheave") and "sway" in e)]


def _mech(case, eff):
    return _scene_mech(*CASES[case](eff))


def _same(x, y, scale):
    np.testing.assert_allclose(x, y, rtol=0, atol=REF * scale)


@pytest.mark.parametrize("case, eff", PAIRS)
def test_lean_equals_the_mechanism(case, eff):
    """Every output of Lean against Mechanism at states off the static one, at times
    before, in and after the moves, all ropes taut and the first slack; G = dL/dq
    against central differences of Mechanism's rope lengths (step 1e-6 m: 1e-7 of the
    falls)."""
    mech = _mech(case, eff)
    assert Lean.covers(mech)
    lean = Lean(mech)
    rng = np.random.default_rng(11)
    nr = len(mech.ropes)
    for t in (0.0, 0.5, 1.5, 2.5, 3.7):
        for taut in (np.ones(nr, bool), np.r_[False, np.ones(nr - 1, bool)],
                     np.r_[np.ones(nr - 1, bool), False]):
            q = mech.q0 + rng.uniform(-0.3, 0.3, mech.n)
            v = rng.uniform(-1.0, 1.0, mech.n)
            kt = lean.kin(t)
            a = lean.evaluate(t, q, v, taut, kt, tangent=True, full=True)
            b = mech.evaluate(t, q, v, taut)
            F = np.abs(b.S).max() + np.abs(b.Sd).max() + np.abs(mech.Fg).max()
            for x, y, s in ((a.F, b.F, F), (a.K, b.K, np.abs(b.K).max() + 1.0),
                            (a.C, b.C, np.abs(b.C).max() + 1.0), (a.X, b.X, 60.0),
                            (a.V, b.V, 10.0), (a.L, b.L, 60.0), (a.L0, b.L0, 60.0),
                            (a.S, b.S, F), (a.Sd, b.Sd, F), (a.edot, b.edot, 10.0),
                            (a.theta, b.theta, 1.0), (a.omega, b.omega, 1.0)):
                _same(x, y, s)
            lean.powers(a)
            P = max(abs(b.P_drive), abs(b.P_diss), abs(b.P_wound), 1.0)
            for x, y in ((a.P_drive, b.P_drive), (a.P_diss, b.P_diss),
                         (a.P_wound, b.P_wound), (a.T_guided, b.T_guided)):
                assert x == pytest.approx(y, rel=0, abs=REF * P)
            Ea, Eb = lean.energy(a, taut), mech.energy(b, taut)
            _same(Ea, Eb, max(abs(x) for x in Eb) + 1.0)
            Xa, Va, tha, oma = lean.place(t, q, v)
            Xb, Vb, thb, omb = mech.place(t, q, v)
            _same(Xa, Xb, 60.0)
            _same(Va, Vb, 10.0)
            _same(np.r_[tha, oma], np.r_[thb, omb], 1.0)
            _same(lean.span_lengths(a),
                  np.linalg.norm(b.X[mech.span_b] - b.X[mech.span_a], axis=1), 60.0)
            h = 1e-6
            Gfd = np.zeros((nr, mech.n))
            for j in range(mech.n):
                dq = np.zeros(mech.n)
                dq[j] = h
                Gfd[:, j] = (mech.evaluate(t, q + dq, v, taut).L
                             - mech.evaluate(t, q - dq, v, taut).L) / (2 * h)
            np.testing.assert_allclose(a._G, Gfd, rtol=0, atol=1e-7)
            # Generic, Mechanism behind the same interface
            gen = Generic(mech)
            g = gen.evaluate(t, q, v, taut, gen.kin(t))
            np.testing.assert_allclose(g._G, Gfd, rtol=0, atol=1e-7)
            _same(g.F, b.F, F)
            gen.powers(g)
            assert g.P_drive == pytest.approx(b.P_drive, rel=0, abs=REF * P)
            _same(gen.energy(g, taut), Eb, max(abs(x) for x in Eb) + 1.0)
            _same(gen.place(t, q, v)[0], Xb, 60.0)
            _same(gen.span_lengths(g), lean.span_lengths(a), 60.0)


def test_time_cache_keeps_recent_times_and_is_refreshed():
    """The records by time: the same object for a repeated time; after more than 8
    times the store starts again, and each record stays the one of its time."""
    calls = []
    c = lean_mod._TimeCache(lambda t: calls.append(t) or (t, len(calls)))
    assert c(0.5) is c(0.5) and calls == [0.5]
    for k in range(20):
        assert c(float(k))[0] == float(k)
        assert len(c.store) <= 9
    assert len(calls) == 21
    assert c(19.0) is c(19.0) and len(calls) == 21
    mech = _mech("slewing trolley", "{}")
    lean = Lean(mech)
    for t in np.linspace(0, 3.5, 23):
        X = lean.place(t, mech.q0, np.zeros(mech.n))[0]
        np.testing.assert_allclose(X, mech.place(t, mech.q0, np.zeros(mech.n))[0],
                                   rtol=0, atol=1e-12)


def test_torque_drum_goes_to_generic_with_the_drum_column_of_G():
    """A drum driven by a torque is a coordinate: Lean does not cover it, ops hands the
    mechanism to Generic, whose G has the drum's column dL/dtheta... as +R on the
    elongation (two falls: the load's columns 2 e)."""
    mech = _scene_mech(WINCH, "  duration: 1\n  drives:\n    h: {drum: hoist, torque: 2000}\n",
                       "{damping: exact}")
    assert mech.qdrums and not Lean.covers(mech) and isinstance(ops(mech), Generic)
    gen = Generic(mech)
    q = mech.q0 + np.array([0.2, 0.1, 0.05])
    v = np.array([0.05, 0.3, 0.2])
    taut = np.array([True])
    ev = gen.evaluate(0.3, q, v, taut, gen.kin(0.3))
    l = np.hypot(q[0], 40 - q[1])
    e = np.array([q[0], q[1] - 40]) / l
    np.testing.assert_allclose(ev._G, [[2 * e[0], 2 * e[1], 0.5]], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(ev._q, q, atol=0)
    np.testing.assert_allclose(ev._v, v, atol=0)


def test_what_lean_does_not_cover():
    """No ropes, an axial spring, a joint coordinate: Generic."""
    spring = ("cranefe: 1\nname: s\nnodes:\n  A: [0, 0, 10]\n  H: [0, 0, 5]\n  B: [1, 0, 10]\n"
              "ground: [A, B]\nmasses: {H: 200}\nsprings:\n  - {name: s, type: axial, nodes: "
              "[A, H], stiffness: 4.0e5}\n")
    m1 = _scene_mech(spring, "  duration: 1\n")
    assert not Lean.covers(m1) and isinstance(ops(m1), Generic)
    m2 = _scene_mech(spring.replace("springs:", "ropes:\n  r: {EA: 1.0e6, path: [A, H]}\n"
                                    "springs:"), "  duration: 1\n")
    assert not Lean.covers(m2)
    arm = _scene_mech(LUFF_ON_SLEW, "  duration: 3\n  drives:\n    l: {hinge: luff, torque: 0}\n"
                      f"    {SLEW}\n")
    assert arm.nJ and not Lean.covers(arm)
    # Generic.place: the prescribed slewing at t, the luffing from its coordinate
    gen = Generic(arm)
    q = arm.q0 + 0.01
    v = np.full(arm.n, 0.1)
    for t in (0.5, 2.5):
        X, V, _, _ = gen.place(t, q, v)
        Xm, Vm, _, _ = arm.place(t, q, v)
        np.testing.assert_allclose(X, Xm, rtol=0, atol=1e-12)
        np.testing.assert_allclose(V, Vm, rtol=0, atol=1e-12)
        assert abs(X[2, 1]) > 0.5                   # the tip has slewed off the xz plane
    m3 = _mech("two ropes", "{}")
    assert Lean.covers(m3)
    m3.linear = object()                     # a linkage: Mechanism's own methods
    assert not Lean.covers(m3)


def test_powers_and_energy_of_an_earlier_state_use_its_own_ropes():
    """Lean keeps the last taut array it saw; powers and energy of a state evaluated
    before another (with another taut array) still use that state's own: the winch's
    wound rope taut and its sling slack, then everything taut, then the first state's
    powers and energy (against Mechanism's) and its time."""
    mech = _mech("winch and sling", "{damping: exact}")
    lean = Lean(mech)
    q = mech.q0 + np.array([0.1, -0.05, 0.05, 0.1])
    v = np.array([0.1, 0.2, -0.1, 0.3])
    t = 1.3
    one = np.array([True, False])
    a = lean.evaluate(t, q, v, one, lean.kin(t))
    lean.evaluate(t, q, v, np.array([True, True]), lean.kin(t))
    lean.powers(a)
    b = mech.evaluate(t, q, v, one)
    assert a.t == t and b.P_wound != 0.0
    for x, y in ((a.P_drive, b.P_drive), (a.P_diss, b.P_diss), (a.P_wound, b.P_wound)):
        assert x == pytest.approx(y, rel=1e-10)
    lean.evaluate(t, q, v, np.array([True, True]), lean.kin(t))
    np.testing.assert_allclose(lean.energy(a, one), mech.energy(b, one), rtol=1e-10)
    assert Generic(mech).evaluate(t, q, v, one, mech.kinematics(t)).t == t


TWO_DRUMS = """cranefe: 1
name: two winches
plane: xz
nodes:
  W: [-2, 0, 40]
  V: [5, 0, 40]
  S: [0, 0, 40]
  U: [3, 0, 40]
  H: [0, 0, 30]
  K: [3, 0, 30]
ground: [W, V, S, U]
masses: {H: 1000, K: 500}
drums:
  d1: {node: W, radius: 0.5, inertia: 10, rope_reserve: 100}
  d2: {node: V, radius: 0.3, inertia: 5, rope_reserve: 100}
ropes:
  r1: {EA: 2.0e6, psi: 0.2, path: [d1, S, H]}
  r2: {EA: 1.0e6, psi: 0.2, path: [d2, U, K]}
"""


def test_two_torque_drums_have_their_own_columns_of_G():
    """Two drums driven by torques (two coordinates after the loads'): G's drum columns
    dL/dtheta_k = R_k on its own rope's row (the elongation grows as the drum pays
    out), zero on the other's."""
    mech = _scene_mech(TWO_DRUMS, "  duration: 1\n  drives:\n    a: {drum: d1, torque: 4000}\n"
                       "    b: {drum: d2, torque: 1500}\n")
    assert len(mech.qdrums) == 2 and isinstance(ops(mech), Generic)
    gen = Generic(mech)
    q = mech.q0.copy()
    ev = gen.evaluate(0.2, q, np.zeros(mech.n), np.array([True, True]), gen.kin(0.2))
    G = ev._G
    np.testing.assert_allclose(G[:, mech.nx:], [[0.5, 0.0], [0.0, 0.3]], atol=1e-15)
    np.testing.assert_allclose(np.abs(G[:, :mech.nx]).sum(1), [1.0, 1.0], rtol=1e-12)


def test_a_level_tag_line_without_sway_keeps_a_finite_dashpot():
    """The tag line level with its guided load: its row of G is zero (no coordinate
    stretches it) while the trolley stretches it at L' = -s'. Its dashpot takes the
    frequency of the one mode at rest (no mode strains it: the lowest, the hoisting
    mode w0^2 = c_h0 / m), b = psi sqrt(c c0) / (2 pi w0) (c0 = EA / 6 m), and acts on no
    coordinate; the hoist rope's dashpot by hand (b = psi c / (2 pi w), w^2 = c/m at
    every length); the forces equal Mechanism's."""
    from cranefe.analysis.operation import profiles
    mech = _mech("tag line", "{sway: false, damping: exact}")
    lean = Lean(mech)
    taut = np.array([True, True])
    mot = profiles.trapezoid(2.0, 1.0, 1.0)
    w0 = np.sqrt(1.0e7 / 10.0 / 1000.0)
    for t in (0.5, 1.5):
        q, v = mech.q0.copy(), np.array([0.2])
        ev = lean.evaluate(t, q, v, taut, lean.kin(t))
        ref = mech.evaluate(t, q, v, taut)
        np.testing.assert_allclose(ev._G[1], [0.0], atol=0)
        s, ds = mot(t)[:2]
        Lt = 6.0 - s
        bt = 0.2 * np.sqrt(1.0e5 / Lt * 1.0e5 / 6.0) / (2 * np.pi * w0)
        assert ev.Sd[1] == pytest.approx(bt * -ds, rel=RTOL)
        assert ref.Sd[1] == pytest.approx(bt * -ds, rel=RTOL)
        L = 10.0 - q[0]
        c = 1.0e7 / L
        b = 0.3 * c / (2 * np.pi * np.sqrt(c / 1000.0))
        assert ev.Sd[0] == pytest.approx(b * -v[0], rel=RTOL)
        np.testing.assert_allclose(ev.F, ref.F, rtol=1e-12)
        assert ev.S[1] != 0.0                       # stretched by the trolley's travel
