"""Kill test for the trigger of cranefe/condense.py's weak quasi-cyclic warning
(tools/mutation.py condense; docs/testing.md, "Mutation testing", condense.py): a motion
that is exactly free must not be reported as "nearly unrestrained", even when the
computed w^2 = r^T K r of its M-normalised rigid vector r is round-off rather than an
exact 0. The warning's trigger is w^2 > 1e-15 * touched (touched = r^T |diag K| r, the
stiffness the motion meets on the diagonal); a trigger scaled the other way
(1e-15 / touched) fires on round-off.

The model (plane xz, sway off, gravity off): A (1000 kg) at (0, 0) on an axial spring
k1 = 1e6 N/m to B (2000 kg) at (1, 1); B on an axial spring k2 = 3e5 N/m to the ground
at C (3, 0). A moves along e1 = (1, 1)/sqrt 2 (its one coordinate u), B in x and z.
Elongations: AB e1 . uB - u, BC -e2 . uB with e2 = (2, -1)/sqrt 5. So
K = k1 r1 r1^T + k2 r2 r2^T, r1 = (-1, e1x, e1z), r2 = (0, -e2x, -e2z),
M = diag(1000, 2000, 2000): rank 2, one free motion (B perpendicular to BC, A
following, u = e1 . uB), and the two frequencies are the non-zero roots of
det(K - w^2 M) = 0, computed here at 30 digits with mpmath. The round-off of the free
motion's w^2 here is about 1.7e-14 s^-2 (a trigger of 1e-15 / touched reports "about
1.32e-07 rad/s"), against touched of order k/m = 1e2-1e3 s^-2: far below the
warning's 1e-15 of touched.

Tolerance: the frequencies to 1e-10 relative (condensation and eigh in double
precision: round-off about 1e-13 of the largest eigenvalue).
"""

import mpmath as mp
import numpy as np
import scipy.linalg as sl

from cranefe.condense import condense
from cranefe.model import load
from cranefe.system import assemble

FREE = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {A: [0, 0, 0], B: [1, 0, 1], C: [3, 0, 0]}
ground: [C]
masses: {A: 1000, B: 2000}
springs:
  - {name: k1, type: axial, nodes: [A, B], stiffness: 1.0e6}
  - {name: k2, type: axial, nodes: [B, C], stiffness: 3.0e5}
effects: {sway: false}
"""


def _frequencies_by_hand():
    mp.mp.dps = 30
    s2, s5 = mp.sqrt(2), mp.sqrt(5)
    r1 = mp.matrix([-1, 1 / s2, 1 / s2])
    r2 = mp.matrix([0, -2 / s5, 1 / s5])
    K = mp.mpf(10) ** 6 * r1 * r1.T + 3 * mp.mpf(10) ** 5 * r2 * r2.T
    Mi = mp.diag([1 / mp.sqrt(m) for m in (1000, 2000, 2000)])
    ev = sorted(mp.eigsy(Mi * K * Mi)[0])
    assert abs(ev[0]) < mp.mpf(10) ** -20                   # the free motion
    return [float(mp.sqrt(e)) for e in ev[1:]]


def test_an_exactly_free_motion_is_not_reported_as_weak():
    c = condense(assemble(load("free.yaml", FREE)))
    assert c.quasi_cyclic == ("node A along (0.707, 0, 0.707)",)
    assert c.warnings == ()
    w = np.sqrt(sl.eigh(c.K, c.M, eigvals_only=True))
    assert np.allclose(w, _frequencies_by_hand(), rtol=1e-10, atol=0)
