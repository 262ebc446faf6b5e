"""Kill tests for the paper's own-axis inertia Jp (Loveikin et al. (2013) eq. 3) in
cranefe/analysis/luffing/energy.py (`Reduced._own_axis`; tools/mutation.py
luffing_energy, docs/testing.md) on a linkage unlike the portal crane in the three ways
the portal crane cannot tell apart:
- the massless tie rod listed FIRST among the bodies (a loop that stopped at a body
  without mass would leave out every body after it);
- the rocker's joint to the ground a `ball` (a ball joint to the ground is an own axis
  like a hinge: the rocker, with its counterweight W, still turns about G);
- a point mass (m_p = 1200 kg, I_p = 400 kg m^2) at the jib tip D: the jib has no joint
  to the ground, so it turns about the centre of gravity c of all it carries.
The geometry and joints are otherwise those of models/portal_crane_luffing.yaml, so the
kinematics are the hand linkage's (tests/test_values.py `_portal_linkage`, circle
intersections at 30 digits, derivatives by mpmath) and the portal crane's J and Jp by
hand (tests/test_mutation_kills_luffing.py `_hand`) change only by the point mass:

- J  -> J + m_p |dD/dalpha|^2 + I_p w_jib^2 (D turns with the jib);
- Jp -> Jp + (I_own' - I_jib) w_jib^2, with the jib's own-axis inertia about the common
  centre c = (m_j c_j + m_p D) / (m_j + m_p) (steiner for two masses):
  I_own' = I_jib + I_p + m_j |c_j - c|^2 + m_p |D - c|^2
         = I_jib + I_p + m_j m_p / (m_j + m_p) |D - c_j|^2,
  a constant of the reference geometry (I_jib = 2.7e5, m_j = 9000, c_j the jib's com).
"""

from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
import yaml
from test_mutation_kills_luffing import _hand
from test_values import ROOT, _portal_linkage

from cranefe.analysis.luffing.analysis import Luffing, read_scene
from cranefe.model import load

M_P, I_P = 1200, 400


def _read(name):
    return yaml.safe_load(Path(ROOT, "models", name).read_text())


def _reduced(tmp_path):
    doc = _read("portal_crane_luffing.yaml")
    bodies = doc["bodies"]
    doc["bodies"] = {"rod": bodies.pop("rod"), **bodies}           # massless body first
    for j in doc["joints"]:
        if j["at"] == "G":
            j["type"] = "ball"                                     # ball joint to ground
    doc["masses"]["D"] = {"mass": M_P, "inertia": I_P}             # point mass on the jib
    assert next(iter(doc["bodies"])) == "rod" and doc["bodies"]["rod"]["mass"] == 0
    (tmp_path / "model.yaml").write_text(yaml.safe_dump(doc, sort_keys=False))
    scene_doc = _read("portal_crane_luffing_scene.yaml")
    scene_doc["model"] = str(tmp_path / "model.yaml")
    (scene := tmp_path / "scene.yaml").write_text(yaml.safe_dump(scene_doc, sort_keys=False))
    model = load(scene)
    return Luffing(model, read_scene(model, str(scene)), str(scene)).reduced


@pytest.mark.parametrize("deg", [55.0])
def test_own_axis_inertia_of_a_linkage_unlike_the_portal_crane(tmp_path, deg):
    """J and Jp to 1e-10 relative (as the portal crane's kill test: mpmath's derivatives
    at 30 digits against the code's Jacobian solves closed to 1e-13)."""
    mp.mp.dps = 30
    pose, _, _ = _portal_linkage()
    doc = _read("portal_crane_luffing.yaml")
    vec = lambda v: mp.matrix([mp.mpf(str(v[0])), mp.mpf(str(v[2]))])
    cj, D0 = vec(doc["bodies"]["jib"]["com"]), vec(doc["nodes"]["D"])
    mj, Ij = mp.mpf(doc["bodies"]["jib"]["mass"]), mp.mpf(doc["bodies"]["jib"]["inertia"])
    I_own = Ij + I_P + mj * M_P / (mj + M_P) * ((D0 - cj)[0]**2 + (D0 - cj)[1]**2)
    a = mp.radians(deg)
    w_jib = mp.diff(lambda t: pose(t)[0][1][3], a)
    dD = [mp.diff(lambda t, i=i: pose(t)[2][i], a) for i in (0, 1)]
    portal = _hand(deg)
    J = portal["J"] + float(M_P * (dD[0]**2 + dD[1]**2) + I_P * w_jib**2)
    Jp = portal["Jp"] + float((I_own - Ij) * w_jib**2)
    v = _reduced(tmp_path).evaluate(np.radians([deg]))
    assert v["J"][0] == pytest.approx(J, rel=1e-10)
    assert v["Jp"][0] == pytest.approx(Jp, rel=1e-10)
    # the point mass matters to Jp at this tolerance (its share is far above 1e-10)
    assert abs(Jp / portal["Jp"] - 1) > 1e-4
