"""Kill test for `Reduced.drive_length` in cranefe/analysis/luffing/energy.py
(tools/mutation.py luffing_energy; docs/testing.md): the derivatives of the drive length
s = |C - A| with BOTH ends moving. In the portal crane the rack's housing A is on the
ground (dA/dalpha = 0), so `dXc + dXa` for `dXc - dXa` (and the same for the second
derivative) changed nothing; here the rack acts between the boom's eye C and the
counterweight centre W on the rocker (models/portal_crane_luffing.yaml otherwise).

By hand (tests/test_values.py `_portal_linkage`: the boom turns about O by
d = alpha - alpha_0, the rocker about G by the angle of Q from the circle intersection):
C(alpha) = O + R(d) (C_0 - O), W(alpha) = G + R(t_r) (W_0 - G), s = |C - W|; ds and dds
by mpmath's differentiation at 30 digits.
"""

from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
import yaml
from test_values import ROOT, _portal_linkage

from cranefe.analysis.luffing.analysis import Luffing, read_scene
from cranefe.model import load


def _read(name):
    return yaml.safe_load(Path(ROOT, "models", name).read_text())


@pytest.mark.parametrize("deg", [55.0])
def test_drive_between_two_moving_bodies(tmp_path, deg):
    """s, ds, dds to 1e-9 (absolute for s, metres: Newton closes the loops to 1e-13 m;
    relative for the derivatives, as the portal crane's kill test)."""
    doc = _read("portal_crane_luffing.yaml")
    doc["linear_drives"]["luffing"]["nodes"] = ["W", "C"]
    (tmp_path / "model.yaml").write_text(yaml.safe_dump(doc, sort_keys=False))
    sd = _read("portal_crane_luffing_scene.yaml")
    sd["model"] = str(tmp_path / "model.yaml")
    (scene := tmp_path / "scene.yaml").write_text(yaml.safe_dump(sd, sort_keys=False))
    model = load(scene)
    v = Luffing(model, read_scene(model, str(scene)), str(scene)).reduced.evaluate(
        np.radians([deg]))
    mp.mp.dps = 30
    pose, _, alpha0_deg = _portal_linkage()
    vec = lambda p: mp.matrix([mp.mpf(str(p[0])), mp.mpf(str(p[2]))])
    O, C0 = vec(doc["nodes"]["O"]), vec(doc["nodes"]["C"])

    def s(t):
        d = t - mp.radians(alpha0_deg)
        C = O + mp.matrix([mp.cos(d) * (C0 - O)[0] - mp.sin(d) * (C0 - O)[1],
                           mp.sin(d) * (C0 - O)[0] + mp.cos(d) * (C0 - O)[1]])
        W = pose(t)[0][4][2]                       # the counterweight's centre
        return mp.sqrt((C - W)[0] ** 2 + (C - W)[1] ** 2)

    a = mp.radians(deg)
    assert v["s"][0] == pytest.approx(float(s(a)), abs=1e-9)
    assert v["ds"][0] == pytest.approx(float(mp.diff(s, a)), rel=1e-9)
    assert v["dds"][0] == pytest.approx(float(mp.diff(s, a, 2)), rel=1e-9)
