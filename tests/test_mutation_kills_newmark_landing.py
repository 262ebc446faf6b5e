"""Kill tests for the landing of a load in cranefe/analysis/transient/newmark.py
(`_switch`: the plastic impact's energy loss, its sign, the stop of the load, the contact
index with two ground contacts; docs/testing.md, "Mutation testing", newmark).

Two loads rest on the ground (`initial: grounded`), each on its own vertical rope from a
fixed point, sway off: B (5000 kg, contact 0) and C (3000 kg, contact 1). Only C is
pushed up by a triangular force table, F(t) = P t / T up to T, P (2T - t) / T up to 2T,
0 after, with P = 4 m g, T = 0.1 s (m = 3000 kg, g = cases.G = 9.81). C lifts off when
F = m g, t0 = T / 4; its rope, just taut at zero force, goes slack at once and C flies
freely, a = F / m - g, then falls back and lands. B is pushed the same way with its own
P = 4 m_B g and T_B = 0.2 s: it is in flight when C lands (so the state after C's impact
still has kinetic energy, B's, which the impact must leave alone) and lands later (a
second landing, whose loss adds to the first).

Hand derivation in units g, T (tau = t / T; v in g T, x in g T^2), from rest at tau = 1/4:
- tau in [1/4, 1]: a = 4 tau - 1, v = 2 tau^2 - tau + 1/8, x = [2s^3/3 - s^2/2 + s/8]
  from 1/4 to tau: v(1) = 9/8, x(1) = 7/24 - 1/96 = 9/32;
- tau in [1, 2]: a = 7 - 4 tau, v = 9/8 + 7 (tau - 1) - 2 (tau^2 - 1): v(2) = 17/8,
  x(2) = 9/32 + 9/8 + 7/2 - 2 (7/3 - 1) = 215/96;
- then free fall: v_land^2 = v(2)^2 + 2 x(2) = 289/64 + 215/48 = 1727/192, landing at
  tau = 2 + v(2) + sqrt(1727/192).
The landing is a plastic impact (docs/transient.md): C stops, the loss is m v_land^2 / 2
= m g^2 T^2 1727/384 (= the work of F, since C ends at rest where it started), positive;
for both loads the sum of m g^2 T^2 1727/384 over them.

The trapezoidal rule integrates a linear acceleration with the velocity exact and the
displacement short by h^2 (a_{n+1} - a_n) / 12 per step (x_{n+1} = x_n + h v_n +
h^2 (a_n + a_{n+1}) / 4 against the exact h^2 (a_n / 3 + a_{n+1} / 6)); summed over the
flight's steps (every step inside one linear piece: t0, T and 2T are on the grid), the
height at 2T is short by g h^2 / 12 (a goes from 0 at t0 to -g), and the free fall is
integrated exactly; so the computed loss of each landing is m g^2 T^2 1727/384 -
m g^2 h^2 / 12 up to the event location (EVENT_TOL) and round-off.
"""

import numpy as np
import pytest

from cranefe.analysis.transient.integrate import simulate
from cranefe.cases import G
from cranefe.model import load

MODEL = """cranefe: 1
name: two grounded loads
plane: xz
nodes: {S: [0, 0, 30], B: [0, 0, 10], T: [5, 0, 30], C: [5, 0, 10]}
ground: [S, T]
masses: {B: 5000, C: 3000}
ropes:
  r1: {EA: 2.0e7, path: [S, B]}
  r2: {EA: 2.0e7, path: [T, C]}
"""


def test_two_loads_pushed_up_land_again_plastic_impact(tmp_path):
    """The impact losses m v^2 / 2 (value and sign, relative 1e-7 against the corrected
    value: the event location's and round-off's share, measured 2e-8), the landing times
    (to the 6 digits of the event text; the h^2 height error shifts them by only
    g h^2 / 12 / v_land = 3e-7 s), the lift-off times (to 1e-9 s, the event location), B's
    velocity untouched by C's landing (its landing time would move otherwise), each load
    at rest on the ground after its landing (q = 0 exactly, ground force m g), the
    lift-offs recorded under their own contacts."""
    h = 0.001
    loads = {"B": (5000.0, 0.2), "C": (3000.0, 0.1)}          # m, T
    (tmp_path / "m.yaml").write_text(MODEL)
    forces = "".join(f"    {n}: {{force: [[0, 0, 0, 0], [{T}, 0, 0, {4 * m * G!r}], "
                     f"[{2 * T}, 0, 0, 0]]}}\n" for n, (m, T) in loads.items())
    (tmp_path / "s.yaml").write_text(
        f"cranefe: 1\nscene: landing\nmodel: {tmp_path / 'm.yaml'}\neffects: {{sway: false}}\n"
        f"analysis:\n  type: transient\n  duration: 1.6\n  time_step: {h}\n"
        f"  initial: grounded\n  forces:\n" + forces)
    r = simulate(load(tmp_path / "s.yaml"))
    loss = sum(m * G**2 * T**2 * 1727 / 384 for m, T in loads.values())
    newmark = loss - sum(m for m, _ in loads.values()) * G**2 * h**2 / 12
    assert r.energy["impact_loss"] == pytest.approx(newmark, rel=1e-7)
    assert r.energy["impact_loss"] == pytest.approx(loss, rel=3e-6)   # h^2 term: 1.9e-6
    assert r.energy["work_loads"] == pytest.approx(r.energy["impact_loss"], rel=1e-7)
    assert r.energy_error < 1e-6
    events = [(float(e.split(" s: ")[0]), e.split(" s: ")[1]) for e in r.events]
    assert [what for _, what in events] == ["C lift-off", "rope r2 slack", "B lift-off",
                                            "rope r1 slack", "C landing", "B landing"]
    times = {what: t for t, what in events}
    for i, (n, (m, T)) in enumerate(loads.items()):
        t_land = T * (2 + 17 / 8 + np.sqrt(1727 / 192))
        # the event texts carry 6 significant digits: half a unit is 5e-6 s at 1.4 s
        assert times[f"{n} landing"] == pytest.approx(t_land, abs=5e-6 * t_land)
        after = r.times > times[f"{n} landing"]
        assert after.sum() > 150
        assert np.all(r.q[after, i] == 0.0)               # stopped on the ground
        assert np.allclose(r.ground_force[after, i], m * G, rtol=1e-12)
        assert r.lift_off_times[i] == pytest.approx(T / 4, abs=1e-9)
    assert r.to_dict()["lift_off_times_s"] == {"B": pytest.approx(0.05, abs=1e-9),
                                               "C": pytest.approx(0.025, abs=1e-9)}
