"""Kill tests for cranefe/analysis/luffing/energy.py and kinematics.py (tools/mutation.py
luffing_energy, luffing_kinematics; docs/testing.md, "Mutation testing"): every quantity
of `Reduced.evaluate` at one boom angle against the portal crane's linkage solved by
hand (`_portal_linkage` of tests/test_values.py: circle intersections at 30 digits, read
from the model file with PyYAML), derivatives by mpmath's high-precision differentiation.

tests/test_values.py checks J and ds; the second transfer functions (dJ, dds, ddx, ddz),
the potential V and its derivative, the drive length s, the jib tip's path and the
paper's own-axis inertia Jp (Loveikin et al. (2013) eq. 3) were checked by no test
against an independent answer.

Jp by hand: the boom, the backstay and the rocker (with the counterweight W it carries)
are hinged to the ground at O, F, G: each turns about its hinge with the inertia
I_c + m |c - hinge|^2 (steiner) and its rate dtheta/dalpha; the jib (hinged to the boom
and the backstay only) turns about its own centre of gravity: I_c dtheta^2 only. The
rotor term J_rotor (i/R)^2 (ds/dalpha)^2 is added to both.
"""

import os

import mpmath as mp
import numpy as np
import pytest

from cranefe.analysis.luffing.analysis import Luffing, read_scene
from cranefe.model import load

from test_values import ROOT, _portal_linkage

mp.mp.dps = 30
G = 9.81             # models/portal_crane_luffing.yaml: gravity [0, 0, -9.81]


def _hand(deg):
    pose, drive, _ = _portal_linkage()
    a = mp.radians(deg)
    ratio = mp.mpf(str(drive["gear_ratio"])) / mp.mpf(str(drive["pinion_radius"]))
    rotor = mp.mpf(str(drive["rotor_inertia"])) * ratio**2
    items0 = pose(a)[0]
    J = dJ = Jp = dJp = V = dV = mp.mpf(0)
    # hinges to the ground of the items (boom O, jib none, backstay F, rocker G, W on G)
    hinge = {0: "O", 1: None, 2: "F", 3: "G", 4: "G"}
    import yaml
    doc = yaml.safe_load(open(os.path.join(ROOT, "models", "portal_crane_luffing.yaml")))
    nodes = {k: mp.matrix([mp.mpf(str(v[0])), mp.mpf(str(v[2]))])
             for k, v in doc["nodes"].items()}
    own = {}
    for k in range(5):
        m, inertia, c, _ = items0[k]
        X = [lambda t, k=k, i=i: pose(t)[0][k][2][i] for i in (0, 1)]
        th = lambda t, k=k: pose(t)[0][k][3]                   # noqa: E731
        d1 = [mp.diff(f, a) for f in X]
        d2 = [mp.diff(f, a, 2) for f in X]
        w, dw = mp.diff(th, a), mp.diff(th, a, 2)
        J += m * (d1[0]**2 + d1[1]**2) + inertia * w**2
        dJ += 2 * (m * (d1[0] * d2[0] + d1[1] * d2[1]) + inertia * w * dw)
        V += m * G * c[1]
        dV += m * G * d1[1]
        body = 3 if k == 4 else k                  # W turns with the rocker
        Ih = inertia if hinge[k] is None else \
            inertia + m * ((c[0] - nodes[hinge[k]][0])**2 + (c[1] - nodes[hinge[k]][1])**2)
        own[body] = own.get(body, 0) + Ih
        own[("w", body)] = (w, dw)
    for b in (0, 1, 2, 3):
        w, dw = own[("w", b)]
        Jp += own[b] * w**2
        dJp += 2 * own[b] * w * dw
    s = lambda t: pose(t)[1]                                   # noqa: E731
    ds, dds = mp.diff(s, a), mp.diff(s, a, 2)
    J += rotor * ds**2
    Jp += rotor * ds**2
    dJ += 2 * rotor * ds * dds
    dJp += 2 * rotor * ds * dds
    tip = {}
    for i, n in ((0, "x"), (1, "z")):
        f = lambda t, i=i: pose(t)[2][i]                       # noqa: E731
        tip[n], tip["d" + n], tip["dd" + n] = f(a), mp.diff(f, a), mp.diff(f, a, 2)
    out = {"J": J, "dJ": dJ, "Jp": Jp, "dJp": dJp, "V": V, "dV": dV, "s": s(a),
           "ds": ds, "dds": dds, **tip}
    return {k: float(v) for k, v in out.items()}


@pytest.fixture(scope="module")
def reduced():
    scene = os.path.join(ROOT, "models", "portal_crane_luffing_scene.yaml")
    model = load(scene)
    return Luffing(model, read_scene(model, scene), scene).reduced


@pytest.mark.parametrize("deg", [55.0])
def test_every_reduced_quantity_against_the_hand_linkage(reduced, deg):
    """Tolerances: 1e-10 relative (1e-11 for J as in tests/test_values.py, looser for
    the second derivatives that the code gets from a second Jacobian solve); V is known
    up to a constant (the code's zero is the model geometry), so V(55) - V(65) is
    compared; s, x, z absolutely to 1e-9 m (Newton closes the loops to 1e-13 m)."""
    hand = {d: _hand(d) for d in (deg, deg + 10.0)}
    v = reduced.evaluate(np.radians([deg, deg + 10.0]))
    for k in ("J", "dJ", "Jp", "dJp", "dV", "ds", "dds", "dx", "ddx", "dz", "ddz"):
        for n, d in enumerate((deg, deg + 10.0)):
            assert v[k][n] == pytest.approx(hand[d][k], rel=1e-10, abs=1e-9), k
    for k in ("s", "x", "z"):
        assert v[k][0] == pytest.approx(hand[deg][k], abs=1e-9), k
    assert v["V"][0] - v["V"][1] == pytest.approx(hand[deg]["V"] - hand[deg + 10]["V"],
                                                  rel=1e-10)
    # the paper's inertia differs from the complete one (the jib translates)
    assert abs(hand[deg]["Jp"] / hand[deg]["J"] - 1) > 1e-3
