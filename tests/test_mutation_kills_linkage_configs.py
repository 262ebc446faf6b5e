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
from test_mutation_kills_linkage import ALPHA_REF, BODY_NODES, NODES, _maps, drive_of

from cranefe.analysis.operation.linkage import LinkageDrive


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
