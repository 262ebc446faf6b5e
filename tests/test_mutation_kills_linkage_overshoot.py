"""Kill test for cranefe/analysis/operation/linkage.py (issue 20, mutation testing;
tools/mutation.py linkage) in a configuration the other kill tests do not build: a Newton
step on the boom angle that leaves the linkage's range AFTER a pose was reached, so that
`LinkageDrive.solve` halves back toward that reached angle (not toward the last
solution's).

The four-bar of tests/test_mutation_kills_linkage.py, its cylinder retracted by 2.2 m and
asked first at the end of the stroke. Its length d(alpha) rises steeply just above the
lower end of the angles the linkage can take (the rocker and coupler circles touch at
about -22.65 deg from the model's angle, where d - d_ref = -2.59 m: dd/dalpha grows like
1/sqrt there), so it is concave: Newton from above (d > target) lands below the root.
From the model's angle the steps are clipped at ALPHA_STEP (0, -5.7, -11.5, -17.2 deg,
each a pose reached); the fourth step, from -17.2 deg, lands at -22.3 deg, past the
-22 deg the linkage's analysis covers, and the next trial is halfway back to -17.2 deg.
The angle is then the hand geometry's root of d(alpha) = d_ref - 2.2 m (circle
intersections, scipy's brentq, no cranefe code), the rates zero (the drive at rest),
every body's turn the hand maps'.

Tolerances: alpha to 1e-11 rad (Newton stops at |d - target| < 1e-13 of the linkage's
size, ~1e-12 m, over dd/dalpha >= 4 m/rad); the turns to 1e-9 (the hand maps'
arctan2, test_mutation_kills_linkage.py's docstring).
"""

import numpy as np
from scipy.optimize import brentq
from test_mutation_kills_linkage import A_NODE, ALPHA_REF, NODES, _maps, drive_of

from cranefe.analysis.operation.linkage import ALPHA_STEP, LinkageDrive
from cranefe.errors import AnalysisError


def test_a_newton_step_past_the_range_after_a_reached_pose_halves_back(tmp_path):
    model, drive = drive_of(tmp_path, dist=-2.2)
    ld = LinkageDrive(model, drive, {})
    trials = []
    state = ld._state

    def spy(t, alpha):
        try:
            st = state(t, alpha)
        except AnalysisError:
            trials.append((alpha, False))
            raise
        trials.append((alpha, True))
        return st
    ld._state = spy
    t = 20.0                                   # the stroke ended at 13 s: at rest
    s, ds, dds = drive.motion(t)
    assert abs(s + 2.2) < 1e-12 and ds == 0.0 and dds == 0.0
    alpha, a1, a2, st = ld.solve(t)
    d_ref = float(np.linalg.norm(NODES["C"] - A_NODE))
    ref = brentq(lambda x: _maps(x)[1] - (d_ref + s), ALPHA_REF - np.radians(22.6),
                 ALPHA_REF, xtol=1e-15)
    assert abs(alpha - ref) < 1e-11
    assert np.degrees(ref - ALPHA_REF) < -21.4
    assert a1 == 0.0 and a2 == 0.0
    names = [b.name for b in model.bodies]
    maps, _ = _maps(ref)
    for b in ld.bodies:
        R, _ = maps[names[b]]
        th = st.q[0, 3 * ld.link.local[b] + 2]
        assert abs(th - np.arctan2(R[1, 0], R[0, 0])) < 1e-9, names[b]
    # the configuration: four clipped steps reached, the fifth trial past the range,
    # the next one halfway back to the angle reached last
    ok = [a for a, good in trials[:4]]
    assert all(good for _, good in trials[:4])
    np.testing.assert_allclose(np.diff(ok), -ALPHA_STEP, rtol=1e-12)
    bad, good = trials[4]
    assert not good and bad < ALPHA_REF - np.radians(22.0)
    assert trials[5][1] and abs(trials[5][0] - 0.5 * (bad + ok[-1])) < 1e-15
