"""Kill tests for cranefe/analysis/operation/linkage.py (issue 20, mutation testing;
tools/mutation.py linkage) in a configuration the other kill tests do not build: the
pose asked at a boom angle far from the last one, where Newton from the last pose
carried by its Taylor series does not close the loops (a jump of about 60 deg across the
four-bar's range), so `LinkageDrive._state` takes the pose from the luffing analysis'
continuation table instead. The four-bar and its hand geometry are those of
tests/test_mutation_kills_linkage.py (circle intersections, no cranefe code).
Tolerance: the pose to 1e-9 (Newton stops at 1e-13 of the linkage's size, ~10 m).
"""

import numpy as np
import pytest
from scipy.optimize import brentq
from test_mutation_kills_linkage import (
    A_NODE,
    ALPHA_REF,
    BODY_NODES,
    NODES,
    _maps,
    drive_of,
)

from cranefe.analysis.operation.linkage import LinkageDrive
from cranefe.errors import AnalysisError


@pytest.mark.parametrize("jump", [(-15.0, 46.0), (-18.0, 44.0)])
def test_a_pose_far_from_the_last_comes_from_the_table(tmp_path, jump):
    model, drive = drive_of(tmp_path)
    ld = LinkageDrive(model, drive, {})
    calls = []
    table = ld.link.state
    ld.link.state = lambda a: calls.append(list(a)) or table(a)
    a1, a2 = ALPHA_REF + np.radians(jump[0]), ALPHA_REF + np.radians(jump[1])
    ld._state(0.0, a1)                        # no last pose: from the table
    assert len(calls) == 1
    st = ld._state(0.0, a2)                   # the Taylor guess fails: the table again
    assert len(calls) == 2 and calls[1] == [a2]
    assert st.residual[0] < 1e-10 * ld.scale
    maps, _ = _maps(a2)
    names = [b.name for b in model.bodies]
    for b in ld.bodies:
        R, p = maps[names[b]]
        th = st.q[0, 3 * ld.link.local[b] + 2]
        assert np.allclose([np.cos(th), np.sin(th)], R[:, 0], rtol=0, atol=1e-9)
        for nd in BODY_NODES[names[b]]:
            X, _ = ld.link._point(st.q, b, model.node_index[nd])
            assert np.allclose(X[0], R @ NODES[nd] + p, rtol=0, atol=1e-9), (b, nd)
    # the pose is kept as the next Taylor start
    assert ld._pose[0] == a2 and np.array_equal(ld._pose[1], st.q[0])


def test_times_asked_in_any_order_give_the_hand_geometry(tmp_path):
    """A 1.5 m stroke (alpha from 45 to 72.4 deg) asked at 40 times in random order, the
    first two its ends: every alpha is the hand geometry's root of d(alpha) = d_ref + s(t)
    and every body's turn theta (not only cos/sin: the range check reads theta) the hand
    maps' angle. Before the fix, t = 9.5 s right after t = 0 was refused (Newton took the
    whole stroke in one step, past the angles the linkage reaches), and poses carried by
    the Taylor series over large jumps closed the loops on the other assembly or with a
    turn off by 2 pi. 9.5 s asked right after 0.5 s: the rates of the last solution
    carry the first guess past the angles the linkage reaches, and Newton halves back.
    Tolerance: alpha to 1e-11 rad, theta to 1e-9 (module docstring)."""
    model, drive = drive_of(tmp_path, dist=1.5)
    ld = LinkageDrive(model, drive, {})
    d_ref = float(np.linalg.norm(NODES["C"] - A_NODE))
    names = [b.name for b in model.bodies]
    times = np.random.default_rng(1).uniform(0.0, 9.5, 40)
    times[:3] = 0.5, 9.5, 0.0
    failed = []
    state = ld._state

    def spy(t, alpha):
        try:
            return state(t, alpha)
        except AnalysisError:
            failed.append(alpha)
            raise
    ld._state = spy
    for t in times:
        s = drive.motion(t)[0]
        ref = brentq(lambda x: _maps(x)[1] - (d_ref + s), ALPHA_REF - 0.3,
                     ALPHA_REF + 0.55, xtol=1e-15)
        alpha, _, _, st = ld.solve(float(t))
        assert abs(alpha - ref) < 1e-11, t
        maps, _ = _maps(ref)
        for b in ld.bodies:
            R, _ = maps[names[b]]
            th = st.q[0, 3 * ld.link.local[b] + 2]
            assert abs(th - np.arctan2(R[1, 0], R[0, 0])) < 1e-9, (t, names[b])
    # 9.5 s right after 0.5 s: the last solution's rates carried over 9 s overshoot the
    # angles the linkage reaches (past 93.5 deg); Newton halves back (other jumps also
    # overshoot its lower end)
    assert failed and max(failed) > np.radians(93.5)
