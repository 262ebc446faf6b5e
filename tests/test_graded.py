"""Graded problems (issue 15): a near-rigid link among soft springs keeps every frequency
to relative accuracy, wherever the link sits and whatever the order of the coordinates,
because the eigen-solution works on the element factor K = F^T F (F = diag(sqrt c) R T)
and never forms K (docs/theory.md, "The graded factor").

The assembled K of a chain with a 1e12 N/m link next to a 1.3 N/m spring holds 1e12 + 1.3
with 4 digits of the 1.3 left: any method that starts from K loses the soft frequencies
to ~1e-4 relative. References: the same matrices in 50-digit arithmetic (mpmath).
"""

import mpmath as mp
import numpy as np
import pytest

from cranefe.analysis.graded import element_factor
from cranefe.analysis.modal import modes
from cranefe.model import load
from cranefe.system import assemble

mp.mp.dps = 50


def chain(ks, ms, free=False, order=None):
    """Masses along x joined by axial springs ks (the first to ground unless free);
    ms[i] = 0 makes node i massless. `order`: the order the nodes are listed in the
    file (it sets the order of the coordinates)."""
    n = len(ms)
    order = range(n) if order is None else order
    nodes = ", ".join(f"N{i}: [{i + 1}, 0, 0]" for i in order)
    ends = ([] if free else ["G"]) + [f"N{i}" for i in range(n)]
    springs = "\n".join(f"  - {{name: k{i}, type: axial, nodes: [{a}, {b}], "
                        f"stiffness: {k!r}}}"
                        for i, (k, a, b) in enumerate(zip(ks, ends[:-1], ends[1:])))
    masses = ", ".join(f"N{i}: {m!r}" for i, m in enumerate(ms) if m > 0)
    return (f"cranefe: 1\nplane: xz\ngravity: [0, 0, 0]\nnodes: {{G: [0, 0, 0], {nodes}}}\n"
            f"ground: [G]\nmasses: {{{masses}}}\nsprings:\n{springs}\n"
            "effects: {sway: false}\n")


def reference(ks, ms, free=False):
    """Elastic frequencies in 50 digits: massless nodes condensed exactly, then the
    eigenvalues of M^-1/2 K* M^-1/2; a free chain's zero frequency dropped."""
    n = len(ms)
    K = mp.zeros(n, n)
    ends = ([] if free else [-1]) + list(range(n))
    for k, a, b in zip(ks, ends[:-1], ends[1:]):
        for i, j, s in ((a, a, 1), (b, b, 1), (a, b, -1), (b, a, -1)):
            if i >= 0 and j >= 0:
                K[i, j] += s * mp.mpf(k)
    a = [i for i in range(n) if ms[i] > 0]
    b = [i for i in range(n) if ms[i] == 0]
    sub = lambda r, c: mp.matrix([[K[i, j] for j in c] for i in r])  # noqa: E731
    Ks = sub(a, a)
    if b:
        Ks = Ks - sub(a, b) * mp.inverse(sub(b, b)) * sub(b, a)
    Mi = mp.diag([1 / mp.sqrt(mp.mpf(ms[i])) for i in a])
    w2 = sorted(mp.eigsy(Mi * Ks * Mi, eigvals_only=True))
    return np.array([float(mp.sqrt(x)) for x in (w2[1:] if free else w2)])


SOFT = (1.3, 0.7, 2.9)          # not round: 1e12 + 1.3 is not exact in double
MASSES = [1.0, 2.5, 0.8]


def placed(where, stiff):
    """Spring stiffnesses of a 3-spring chain with the stiff link(s) at `where`."""
    return {"soft-stiff-soft": [SOFT[0], stiff, SOFT[1]],
            "stiff-soft-stiff": [stiff, SOFT[0], 1.7 * stiff],
            "stiff at the ground": [stiff, SOFT[0], SOFT[1]],
            "stiff at the free end": [SOFT[0], SOFT[1], stiff]}[where]


WHERE = ["soft-stiff-soft", "stiff-soft-stiff", "stiff at the ground",
         "stiff at the free end"]


# Tolerance 1e-12: the Jacobi SVD of the row-graded factor has relative errors of order
# eps times the condition of the factor with its rows scaled (here O(10)); measured
# errors are below 1e-15. The assembled-K path failed these by 1e-5 to 1e-4.
@pytest.mark.parametrize("contrast", [1e8, 1e10, 1e12, 1e14])
@pytest.mark.parametrize("where", WHERE)
def test_stiff_link_anywhere(where, contrast):
    ks = placed(where, 1.1 * contrast)
    r = modes(load("chain.yaml", chain(ks, MASSES)))
    np.testing.assert_allclose(r.omega, reference(ks, MASSES), rtol=1e-12, atol=0)


@pytest.mark.parametrize("order", [(2, 0, 1), (1, 2, 0)])
def test_any_coordinate_order(order):
    ks = placed("stiff-soft-stiff", 1.1e12)
    r = modes(load("chain.yaml", chain(ks, MASSES, order=order)))
    np.testing.assert_allclose(r.omega, reference(ks, MASSES), rtol=1e-12, atol=0)


def test_massless_node_between_stiff_and_soft():
    # N1 has no mass: condensed through the element factor (QR of its columns)
    ks, ms = [1.3, 1.1e12, 0.7, 2.9], [1.0, 0.0, 2.5, 0.8]
    r = modes(load("chain.yaml", chain(ks, ms)))
    assert r.massless and r.graded.startswith("element factor")
    np.testing.assert_allclose(r.omega, reference(ks, ms), rtol=1e-12, atol=0)


def test_free_chain_with_stiff_link():
    # no ground: one quasi-cyclic (rigid) motion, removed before the graded solution
    ks, ms = [1.1e12, 1.3, 0.7], [1.0, 2.5, 0.8, 1.9]
    r = modes(load("chain.yaml", chain(ks, ms, free=True)))
    assert r.rigid.sum() == 1 and r.graded.startswith("element factor")
    np.testing.assert_allclose(r.omega[~r.rigid], reference(ks, ms, free=True),
                               rtol=1e-12, atol=0)


HANGING = """cranefe: 1
plane: xz
nodes: {{S: [0, 0, 30], A: [0, 0, 20], B: [0, 0, 19], C: [0, 0, 9]}}
ground: [S]
masses: {{A: 700, B: 900, C: 1300}}
ropes:
  upper: {{EA: 2.3e6, path: [S, A]}}
  lower: {{EA: 1.9e6, path: [B, C]}}
springs:
  - {{name: link, type: axial, nodes: [A, B], stiffness: {k!r}}}
"""


def test_vertical_chain_with_sway_matches_the_assembled_matrices_in_50_digits():
    # the audit's case: a near-rigid link between two ropes hanging in a vertical chain,
    # with sway (tension stiffness blocks factorised element by element)
    text = HANGING.format(k=1.1e12 * 1.7)
    s = assemble(load("hang.yaml", text))
    f = element_factor(s)
    assert not f.indefinite
    r = modes(load("hang.yaml", text))
    assert r.graded.startswith("element factor")
    # reference: K = F^T F in 50 digits from the same element rows, M exact
    F = mp.matrix(f.F.toarray().tolist())
    K = F.T * F
    Mi = mp.diag([1 / mp.sqrt(mp.mpf(x)) for x in s.M.diagonal()])
    w2 = sorted(mp.eigsy(Mi * K * Mi, eigvals_only=True))
    np.testing.assert_allclose(r.omega, [float(mp.sqrt(x)) for x in w2], rtol=1e-12)


def test_factor_reproduces_k():
    # F^T diag(sign) F = K to round-off of K's own entries, with beams and tension
    from cranefe.model import load as ld
    m = ld("models/lattice_tower_crane.yaml")
    from dataclasses import replace
    s = assemble(m, replace(m.effects, structure="flexible"))
    f = element_factor(s)
    K = s.K.toarray()
    KF = (f.F.T @ (f.F.multiply(f.sign[:, None]))).toarray()
    assert np.abs(KF - K).max() <= 1e-12 * np.abs(K).max()


INVERTED = """cranefe: 1
plane: xz
nodes: {{O: [0, 0, 0], T: [0, 0, 8], S: [5, 0, 30], A: [5, 0, 20], B: [5, 0, 19],
         C: [5, 0, 9]}}
ground: [O, S]
masses: {{A: 700, B: 900, C: 1300}}
bodies:
  mast: {{mass: 2000, com: [0, 0, 4], inertia: 1.1e4, nodes: [T]}}
joints:
  - {{type: hinge, bodies: [ground, mast], at: O, axis: [0, 1, 0]}}
springs:
  - {{name: bend, type: rotational, bodies: [ground, mast], at: O, axis: [0, 1, 0],
     stiffness: 3.7e6}}
  - {{name: upper, type: axial, nodes: [S, A], stiffness: 2.3e5}}
  - {{name: link, type: axial, nodes: [A, B], stiffness: {k!r}}}
  - {{name: lower, type: axial, nodes: [B, C], stiffness: 1.9e5}}
"""


def test_negative_load_stiffness_merged_locally():
    # a mast above its hinge (negative load stiffness on its rotation, outweighed by the
    # bending spring) beside a hanging chain with a 1.3e16 N/m link (6e10 times its
    # springs): the negative rows are merged with the spring's row only, the chain's
    # rows stay apart, and every frequency matches the element matrices in 50 digits
    # (the assembled-K fallback: 3e-6 off; at other link values, by the luck of the
    # rounding of K_ii, anywhere from 1e-13 to 1e-4)
    text = INVERTED.format(k=1.3e16)
    s = assemble(load("inv.yaml", text))
    f = element_factor(s)
    assert f.indefinite
    r = modes(load("inv.yaml", text))
    assert r.graded.startswith("element factor (negative parts")
    F = mp.matrix(f.F.toarray().tolist())
    K = F.T * mp.diag([mp.mpf(x) for x in f.sign]) * F
    Mi = mp.diag([1 / mp.sqrt(mp.mpf(x)) for x in s.M.diagonal()])
    w2 = sorted(mp.eigsy(Mi * K * Mi, eigvals_only=True))
    np.testing.assert_allclose(r.omega, [float(mp.sqrt(x)) for x in w2], rtol=1e-12)
