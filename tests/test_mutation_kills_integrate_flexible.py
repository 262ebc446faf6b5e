"""Value tests of cranefe/analysis/operation/integrate.py (issue 20, mutation testing,
fourth round): its branches for an elastic structure (flexible.py), which the first
three kill files never build. Every run passes fast=False (the numpy loop; a mechanism
with an elastic structure is never compiled).

- a rod on a trolley, vibrating along its axis: the trolley is moved by a speed table
  (kinks at 0.5, 1 and 1.5 s); a step that ends at a kink must see the frame's
  acceleration from the left (simulate's `flex` flag, Stepper.step's `left`), the next
  one starts from the right limits. The tip's axial displacement d obeys
  m d'' + (EA/L) d = -m s''(t) exactly (the Green elongation of a tip displaced along
  the rod is d, tests/test_mutation_kills_flexible_frames.py), s'' piecewise constant:
  the closed form below;
- the rope's rows of the step's force error include the elastic coordinates
  (`_FlexOps`): a rope hanging straight from the elastic tip of a jib.
"""

import math

import numpy as np
from test_operation_flexible import JIB, write

from cranefe.analysis.operation.integrate import Stepper, simulate
from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse
from cranefe.model import load

G = 9.81

# a 2 m rod K-T along x on a trolley travelling along x, a 500-kg point mass at its tip
# T; no gravity, so the tip moves along the rod only (no bending: uy = uz = 0 exactly)
ROD = """cranefe: 1
name: a rod on a trolley, vibrating along its axis
gravity: [0, 0, 0]
nodes:
  K:  [0.0, 0.0, 1.0]
  T:  [2.0, 0.0, 1.0]
ground: []
masses: {T: 500}
bodies:
  trolley: {mass: 10, com: [0, 0, 1], inertia: [1, 1, 1], nodes: [K]}
joints:
  - {name: travel, type: slider, bodies: [ground, trolley], at: K, axis: [1, 0, 0],
     range: [-1, 5]}
members:
  rod: {type: beam, nodes: [K, T], E: 2.1e+11, G: 8.0e+10, A: 1.0e-6, Iy: 1.0e-9,
       Iz: 1.0e-9, J: 2.0e-9, rho: 7850, orientation: [0, 0, 1], elements: 1,
       mass: lumped}
"""
# speed table: s'' = 1 on (0, 0.5), 0 on (0.5, 1), -1 on (1, 1.5), 0 after (m/s^2)
TABLE = ("  duration: 2\n  tolerance: 1.0e-5\n  output_step: 0.01\n  drives:\n"
         "    tr: {slider: travel, profile: {type: table, speed: [[0, 0], [0.5, 0.5], "
         "[1.0, 0.5], [1.5, 0]]}}\n")
ACC = ((0.0, 1.0), (0.5, 0.0), (1.0, -1.0), (1.5, 0.0))
M_TIP = 500.0 + 7850 * 1.0e-6 * 2.0 / 2          # the point mass + half the rod's
K_ROD = 2.1e11 * 1.0e-6 / 2.0                    # EA / L
W_ROD = math.sqrt(K_ROD / M_TIP)                 # 14.5 rad/s


def _axial_exact(t):
    """d(t) of d'' + w^2 d = -a_i on each segment (d = d' = 0 at t = 0): on a segment
    from t_i, d = p + (d_i - p) cos w tau + d'_i / w sin w tau with p = -a_i / w^2."""
    d, dd = 0.0, 0.0
    ends = [t0 for t0, _ in ACC[1:]] + [math.inf]
    for (t0, a), t1 in zip(ACC, ends):
        if t <= t0:
            break
        tau = min(t, t1) - t0
        p = -a / W_ROD**2
        c, s = math.cos(W_ROD * tau), math.sin(W_ROD * tau)
        d, dd = p + (d - p) * c + dd / W_ROD * s, -(d - p) * W_ROD * s + dd * c
    return d


def _trolley(t):
    """s(t) of the table (s'' as ACC)."""
    if t <= 0.5:
        return 0.5 * t * t
    if t <= 1.0:
        return 0.125 + 0.5 * (t - 0.5)
    if t <= 1.5:
        return 0.375 + 0.5 * (t - 1.0) - 0.5 * (t - 1.0) ** 2
    return 0.5


def test_a_step_ending_at_a_kink_sees_the_frame_from_the_left(tmp_path):
    """The rod's tip against the closed form over 2 s at tolerance 1e-5 (0.6 s of CPU):
    d(t) = x_T - 2 - s(t) to 2.5e-3 m of its 1.4e-2 m peak (measured 1.4e-3, 3.5e-4 at
    1e-6, 8.4e-5 at 1e-7, 2.0e-5 at 1e-8: the trapezoidal rule's order 2), across the
    rod 0 to round-off; the energy balance (the trolley's work on the rod through the
    frame's power) to 1e-3 (measured 4.1e-4). A step that ends at a kink evaluated with
    the acceleration after it (the flag `flex` lost, `left` not passed, t1 one ulp late)
    integrates that step with the wrong a1: the balance is then off by 1.5e-2 (at
    1e-6: 2.3e-3 against 2.1e-4)."""
    model = load(write(tmp_path, ROD, TABLE, name="rod.yaml"))
    res = simulate(model, fast=False)
    assert res.coordinates == ("T.ux", "T.uy", "T.uz")
    assert res.mass_names == ("T",)
    x = res.mass_position[:, 0]
    d = x[:, 0] - 2.0 - np.array([_trolley(t) for t in res.times])
    exact = np.array([_axial_exact(t) for t in res.times])
    assert np.abs(exact).max() > 0.013
    assert np.abs(d - exact).max() < 2.5e-3, np.abs(d - exact).max()
    assert np.abs(x[:, 1:] - [0.0, 1.0]).max() < 1e-12
    assert res.energy["work_drives"] != 0.0
    assert res.energy_error < 1e-3, res.energy_error
    # the cost (deterministic counts): measured 93 steps, 10 rejected, 206 iterations
    assert res.steps < 120 and res.rejected <= 12, (res.steps, res.rejected)


# the jib of test_operation_flexible.py with the load hanging straight from its tip
DIRECT = JIB.replace("path: [hoist, T, HOOK]", "path: [T, HOOK]")


def test_the_force_error_counts_the_elastic_tip_of_a_rope(tmp_path):
    """The step's error estimate (Stepper.error) for an acceleration change da of the
    jib tip's vertical coordinate alone, at the static state: the rope T-HOOK hangs
    straight down, so its row dL/du_T.z = 1 (the frame is the ground: R = I), and the
    rope's force error EA/L (G da) h^2/12 over 20 x tolerance x S (S = m g = 1500 g, its
    static force) is 1.2e2 times the position error h^2/12 |da| / (tolerance x size):
    err = EA / (20 tol L m g) h^2/12 (rtol 1e-9: L from the state, G_z = cos of the
    rope's tilt, zero to Newton's tolerance). Without the elastic columns in the rows
    (`_FlexOps` not chosen) only the position error would remain."""
    model = load(write(tmp_path, DIRECT, "  duration: 1\n", name="direct.yaml",
                       IYVAL=2.0e-2, NEL=1, MASS="lumped", GVAL=-G))
    spec = parse(model)
    mech = Mechanism(model, spec)
    st = Stepper(mech, spec, model.length_scale, fast=False)
    labels = mech.flex.labels()
    assert labels == ["T.ux", "T.uz"]
    k = mech.nc + mech.nJ + labels.index("T.uz")
    v = np.zeros(mech.n)
    ev = st.ops.evaluate(0.0, mech.q0, v, mech.taut0, st.kin(0.0), tangent=False)
    assert abs(ev.S[0] / (1500 * G) - 1) < 1e-9          # the static state
    L = float(ev.L[0])
    assert abs(L - 8.0) < 0.02                            # 8 m, stretched and deflected
    da = np.zeros(mech.n)
    da[k] = 1.0
    h = 0.01
    tol = spec.tolerance
    expect = 2.0e7 / (20 * tol * L * 1500 * G) * h * h / 12
    position = 1.0 / (tol * model.length_scale) * h * h / 12
    assert expect > 100 * position
    assert abs(st.error(h, v, da, ev, mech.taut0.copy()) / expect - 1) < 1e-9


def test_the_force_error_of_a_drum_coordinate_beside_the_elastic_ones(tmp_path):
    """The jib's load hoisted over the tip by a torque-driven drum (R = 0.2 m): the
    drum angle is a coordinate after the elastic ones, its row in G is dL/dtheta = R
    (the unstretched length paid out is -R theta). An acceleration change of the drum
    alone: the position error weighs it by R, the rope's force error is
    EA R / (20 tol L m g) h^2/12 (L: the rope's 22 m from the state), 43 times more
    (rtol 1e-9, as above). The elastic columns are written into the rows without
    touching the drum's column."""
    model = load(write(tmp_path, JIB, "  duration: 1\n  drives:\n    h: {drum: hoist, "
                       f"torque: {0.2 * 1500 * G}}}\n", name="drum.yaml", IYVAL=2.0e-2,
                       NEL=1, MASS="lumped", GVAL=-G))
    spec = parse(model)
    mech = Mechanism(model, spec)
    st = Stepper(mech, spec, model.length_scale, fast=False)
    assert mech.n == mech.nc + mech.nJ + mech.flex.nu + 1
    v = np.zeros(mech.n)
    ev = st.ops.evaluate(0.0, mech.q0, v, mech.taut0, st.kin(0.0), tangent=False)
    assert abs(ev.S[0] / (1500 * G) - 1) < 1e-9
    L = float(ev.L[0])
    assert abs(L - 22.0) < 0.05
    da = np.zeros(mech.n)
    da[-1] = 1.0
    h, tol = 0.01, spec.tolerance
    expect = 2.0e7 * 0.2 / (20 * tol * L * 1500 * G) * h * h / 12
    assert expect > 40 * 0.2 / (tol * model.length_scale) * h * h / 12
    assert abs(st.error(h, v, da, ev, mech.taut0.copy()) / expect - 1) < 1e-9
