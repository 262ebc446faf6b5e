"""Kill tests for cranefe/condense.py's weak quasi-cyclic warning (tools/mutation.py
condense; docs/testing.md, "Mutation testing", condense.py): a motion that the unit
pattern of the elements sees as free (below NULL_TOL) but K still restrains is treated as
quasi-cyclic, and `condense` says so with its true frequency.

The model: masses m1 = 10 kg at N1 (0, 0, 0) and m2 = 30 kg at N2 (1, 0, 0), gravity off,
four axial springs of the same k = 1e6 N/m: s12 N1-N2 (along x), c N1-G3 and a N2-G1
(along z), and b from N2 to G2 = (1 + 1e-6, 0, -1), tilted from z by sin(theta) =
1e-6 / sqrt(1 + 1e-12) = s. Only b resists the two masses moving together along x, by
k s^2: in the unit-scaled pattern that motion's eigenvalue is about s^2 / 2 = 5e-13 of
the largest, below NULL_TOL = 1e-10, so it becomes the quasi-cyclic coordinate N1 x.
By hand, the motion (1, 0, 1, delta) (N1 x, N1 z, N2 x, N2 z) meets the stiffness
k (s - delta)^2 + k delta^2 (to O(s^3)), least at delta = s / 2: k s^2 / 2 over the
mass m1 + m2, w = sqrt(k s^2 / (2 (m1 + m2))) = 1.118e-4 rad/s. The test also takes the
lowest eigenvalue of (K, M) written out by hand at 30 digits with mpmath (numpy's eigh
has round-off of 1e-16 of the largest eigenvalue, 1e-3 of this one) and compares the
warning's 3 digits with it.
"""

import mpmath as mp
import numpy as np

from cranefe.condense import condense
from cranefe.model import load
from cranefe.system import assemble

WEAK = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {N1: [0, 0, 0], N2: [1, 0, 0], G1: [1, 0, 1], G2: [1.000001, 0, -1], G3: [0, 0, 1]}
ground: [G1, G2, G3]
masses: {N1: 10, N2: 30}
springs:
  - {name: s12, type: axial, nodes: [N1, N2], stiffness: 1.0e6}
  - {name: a, type: axial, nodes: [N2, G1], stiffness: 1.0e6}
  - {name: b, type: axial, nodes: [N2, G2], stiffness: 1.0e6}
  - {name: c, type: axial, nodes: [N1, G3], stiffness: 1.0e6}
effects: {sway: false}
"""


def _lowest_by_hand():
    """sqrt of the lowest eigenvalue of K v = w^2 M v, coordinates (N1 x, N1 z, N2 x,
    N2 z), K = sum k r r^T over the springs' rows r (unit direction, + at one end)."""
    mp.mp.dps = 30
    k = mp.mpf(10) ** 6
    tilt = mp.sqrt(1 + mp.mpf("1e-6") ** 2)
    rows = [[-1, 0, 1, 0],                                   # s12 along x
            [0, 0, 0, 1],                                    # a: N2 up to G1
            [0, 0, mp.mpf("1e-6") / tilt, -1 / tilt],        # b: N2 down to G2
            [0, 1, 0, 0]]                                    # c: N1 up to G3
    K = mp.zeros(4, 4)
    for r in rows:
        K += k * mp.matrix(r) * mp.matrix(r).T
    Mi = mp.diag([1 / mp.sqrt(m) for m in (10, 10, 30, 30)])
    return mp.sqrt(min(mp.eigsy(Mi * K * Mi)[0]))


def test_weak_quasi_cyclic_motion_is_reported_with_its_frequency():
    """The warning names the two coordinates the motion moves most (N1 x, N2 x, equal
    amplitude: ties in order of labels are not asserted, both are) and its frequency to
    the 3 digits printed; the other motions are restrained (no other warning)."""
    s = assemble(load("weak.yaml", WEAK))
    c = condense(s)
    w = _lowest_by_hand()
    sn = 1e-6 / np.sqrt(1 + 1e-12)
    assert abs(float(w) / np.sqrt(1e6 * sn**2 / (2 * 40)) - 1) < 1e-9   # hand formula
    assert c.quasi_cyclic == ("node N1 x",)
    assert len(c.warnings) == 1
    names, text = c.warnings[0].split(": ", 1)
    assert set(names.split(", ")) == {"node N1 x", "node N2 x"}
    assert text == ("nearly unrestrained (its stiffness is below 1e-10 of its elements'), "
                    f"treated as free; its true frequency is about {float(w):.3g} rad/s")
    assert f"{float(w):.3g}" == "0.000112"


def test_a_weak_motion_among_soft_springs_is_still_reported():
    """The same model with springs of k = 1e-2 N/m (the pattern is scale-free: the same
    quasi-cyclic motion). Its w^2 = k s^2 / (2 (m1 + m2)) = 1.25e-16 s^-2 (w = 1.118e-8
    rad/s, the formula checked against mpmath above for k = 1e6: w scales as sqrt(k)) is
    above the trigger 1e-15 * touched, touched = sum |K_ii| v_i^2 of the M-normalised
    motion, about 1e-3 s^-2 here: the warning is given. The trigger's floor (1e-300)
    only guards touched = 0; a floor of 1 s^-2 would hide this warning."""
    s = assemble(load("weak.yaml", WEAK.replace("stiffness: 1.0e6", "stiffness: 1.0e-2")))
    c = condense(s)
    sn = 1e-6 / np.sqrt(1 + 1e-12)
    w = np.sqrt(1e-2 * sn**2 / (2 * 40))
    assert c.quasi_cyclic == ("node N1 x",)
    assert len(c.warnings) == 1
    assert c.warnings[0].endswith(f"its true frequency is about {w:.3g} rad/s")
    assert f"{w:.3g}" == "1.12e-08"
