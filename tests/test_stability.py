"""Hard cases stay numerically stable: every case has a 50-digit reference (mpmath) or a
closed form, and a tolerance with its reason. Run alone with ``pytest -m stability``."""

from dataclasses import replace

import mpmath as mp
import numpy as np
import pytest

from cranefe.system import assemble
from cranefe.model import load
from cranefe.analysis.modal import modes

pytestmark = pytest.mark.stability
mp.mp.dps = 50
G = 9.81


def chain_yaml(ks, ms, free=False):
    """Masses in a line joined by axial springs; the first spring to ground unless free."""
    n = len(ms)
    nodes = ", ".join(f"N{i}: [{i + 1}, 0, 0]" for i in range(n))
    ends = (["G"] if not free else []) + [f"N{i}" for i in range(n)]
    pairs = list(zip(ends[:-1], ends[1:]))
    springs = "\n".join(f"  - {{name: k{i}, type: axial, nodes: [{a}, {b}], "
                        f"stiffness: {k!r}}}" for i, (k, (a, b)) in enumerate(zip(ks, pairs)))
    masses = ", ".join(f"N{i}: {m!r}" for i, m in enumerate(ms))
    return (f"cranefe: 1\nplane: xz\ngravity: [0, 0, 0]\nnodes: {{G: [0, 0, 0], {nodes}}}\n"
            f"ground: [G]\nmasses: {{{masses}}}\nsprings:\n{springs}\n"
            "effects: {sway: false}\n")


def chain_reference(ks, ms, free=False):
    """Frequencies of the chain in 50-digit arithmetic (exact matrices, mp.eigsy)."""
    n = len(ms)
    K = mp.zeros(n, n)
    ends = ([-1] if not free else []) + list(range(n))
    for k, (a, b) in zip(ks, zip(ends[:-1], ends[1:])):
        k = mp.mpf(k)
        for i, j, s in ((a, a, 1), (b, b, 1), (a, b, -1), (b, a, -1)):
            if i >= 0 and j >= 0:
                K[i, j] += s * k
    Mi = mp.diag([1 / mp.sqrt(mp.mpf(m)) for m in ms])
    w2 = mp.eigsy(Mi * K * Mi, eigvals_only=True)
    return np.array(sorted(float(mp.sqrt(max(x, 0))) for x in w2))


def solve(text, **kw):
    return modes(load("case.yaml", text), **kw)


# Tolerance 1e-12: solved from the element factor (K never formed, so a stiffness of 1e12
# next to 1 loses nothing of the 1) by Jacobi SVD with relative accuracy; worst error
# measured 7e-16 (it was 9e-11 when the factor came from the assembled K).
CONTRAST = [
    ("stiffness 1e12", [1e12, 1.3, 1e6, 1e-3], [1.0, 2.0, 1.0, 3.0]),
    ("mass 1e9", [1.0, 2.0, 1.5, 1.0], [1e9, 1.0, 1e-3, 1e4]),
    ("both", [1e12, 1.0, 1e6, 1.0, 7.0], [1e3, 1e-6, 1.0, 1e3, 0.5]),
]


@pytest.mark.parametrize("name, ks, ms", CONTRAST, ids=[c[0] for c in CONTRAST])
def test_stiffness_and_mass_contrasts(name, ks, ms):
    r = solve(chain_yaml(ks, ms))
    np.testing.assert_allclose(r.omega, chain_reference(ks, ms), rtol=1e-12)
    M = assemble(load("case.yaml", chain_yaml(ks, ms))).M.toarray()
    np.testing.assert_allclose(r.shapes.T @ M @ r.shapes, np.eye(len(ms)), atol=1e-10)


def test_several_quasi_cyclic_coordinates_at_once():
    # a free-free chain (1 rigid mode), a free drum hoist and a free body: 3 at once
    ks, ms = [1e6, 3e5, 2e7], [1000.0, 2000.0, 500.0, 700.0]
    text = chain_yaml(ks, ms, free=True).replace("effects: {sway: false}\n", "") + """\
  - {name: h, type: axial, nodes: [S, B], stiffness: 5.0e5}
drums:
  winch: {node: D, radius: 0.3, inertia: 80}
ropes:
  r: {EA: 2.0e7, path: [winch, S2, B2]}
bodies:
  trolley: {mass: 300, com: [20, 0, 0], inertia: 10, nodes: [T]}
effects: {sway: false}
"""
    text = text.replace("nodes: {G: [0, 0, 0],", "nodes: {G: [0, 0, 0], S: [10, 0, 5], "
                        "B: [10, 0, 0], D: [15, 0, 0], S2: [15, 0, 10], B2: [15, 0, 2], "
                        "T: [20, 0, 0],").replace("ground: [G]", "ground: [G, S, D, S2]")
    text = text.replace("masses: {", "masses: {B: 400, B2: 900, ")
    r = solve(text)
    assert r.rigid.sum() == 1 + 1 + 3          # chain, drum+load, trolley (3 planar)
    assert "drum winch" in r.quasi_cyclic
    # the elastic ones: the chain's from 50 digits, the hook on its spring, the hoist
    chain = chain_reference(ks, ms, free=True)[1:]
    k = 2.0e7 / (10.0 + 8.0)          # drum to sheave, sheave to hook
    hoist = np.sqrt(k * (1 / 900 + 0.3**2 / 80))
    np.testing.assert_allclose(np.sort(r.omega[~r.rigid]),
                               np.sort(np.r_[chain, np.sqrt(5.0e5 / 400), hoist]), rtol=1e-10)
    M = assemble(load("case.yaml", text)).M.toarray()
    np.testing.assert_allclose(r.shapes.T @ M @ r.shapes, np.eye(len(r.omega)), atol=1e-10)


def two_pendulums(l1, l2, coupling):
    spring = f"""springs:
  - {{name: c, type: axial, nodes: [A, B], stiffness: {coupling!r}}}
""" if coupling else ""
    return f"""cranefe: 1
nodes: {{S1: [0, 0, 30], S2: [3, 0, 30], A: [0, 0, {30 - l1}], B: [3, 0, {30 - l2}]}}
ground: [S1, S2]
masses: {{A: 1000, B: 1000}}
ropes:
  a: {{EA: 1.0e9, path: [S1, A]}}
  b: {{EA: 1.0e9, path: [S2, B]}}
""" + spring


@pytest.mark.parametrize("dl, coupling", [(0.0, 0.0), (1e-9, 0.0), (1e-7, 1e-6)])
def test_repeated_and_nearly_repeated_frequencies(dl, coupling):
    # four pendulum modes near sqrt(g/l) (two per mass, in x and y); exact for the
    # uncoupled case; the mode subspaces stay M-orthonormal to 1e-10 however close
    l = 12.0
    text = two_pendulums(l, l * (1 + dl), coupling)
    r = solve(text)
    sys_ = assemble(load("case.yaml", text))
    M, K = sys_.M.toarray(), sys_.K.toarray()
    np.testing.assert_allclose(r.shapes.T @ M @ r.shapes, np.eye(len(r.omega)), atol=1e-10)
    np.testing.assert_allclose(r.shapes.T @ K @ r.shapes, np.diag(r.omega**2),
                               atol=1e-10 * r.omega.max() ** 2)
    if coupling == 0:
        expected = sorted([np.sqrt(G / l)] * 2 + [np.sqrt(G / (l * (1 + dl)))] * 2)
        np.testing.assert_allclose(r.omega[:4], expected, rtol=1e-12)


HOIST = """cranefe: 1
plane: xz
nodes: {{D: [0, 0, 0], S: [0, 0, {h}], B: [0, 0, {b}]}}
ground: [D, S]
masses: {{B: 5000}}
drums:
  hoist: {{node: D, radius: {R}, inertia: 500}}
ropes:
  r: {{EA: 2.0e7, path: [hoist, S, {{node: B, falls: 2}}]}}
"""


@pytest.mark.parametrize("s", [1e-3, 1.0, 1e3])
def test_lengths_scaled(s):
    # every length x s (node coordinates and drum radius): k = EA / (L s),
    # w^2 = k (4/m + (R s)^2/J), pendulum sqrt(g / (l s)); exact in closed form
    r = solve(HOIST.format(h=30 * s, b=10 * s, R=0.25 * s))
    L = (30 + 2 * 20) * s
    k = 2.0e7 / L
    expected = [np.sqrt(G / (20 * s)), np.sqrt(k * (4 / 5000 + (0.25 * s) ** 2 / 500))]
    np.testing.assert_allclose(np.sort(r.omega[~r.rigid]), np.sort(expected), rtol=1e-10)


@pytest.mark.parametrize("length", [1000.0, 0.01])
def test_very_long_and_very_short_ropes(length):
    text = f"""cranefe: 1
plane: xz
nodes: {{S: [0, 0, {length + 1}], B: [0, 0, 1]}}
ground: [S]
masses: {{B: 2000}}
ropes:
  r: {{EA: 1.0e7, path: [S, B]}}
"""
    r = solve(text)
    np.testing.assert_allclose(r.omega, [np.sqrt(G / length), np.sqrt(1.0e7 / length / 2000)],
                               rtol=1e-10)


def junction(angle):
    """A mass hangs from a massless junction J held by two ropes at `angle` above the
    horizontal: J's vertical stiffness 2 k sin^2(angle) in series with the hanger."""
    c, s_ = float(np.cos(angle)), float(np.sin(angle))
    return f"""cranefe: 1
plane: xz
nodes: {{A: [{-10 * c!r}, 0, {10 * s_!r}], C: [{10 * c!r}, 0, {10 * s_!r}], J: [0, 0, 0],
        L: [0, 0, -5]}}
ground: [A, C]
masses: {{L: 1000}}
ropes:
  a: {{EA: 1.0e8, path: [A, J]}}
  c: {{EA: 1.0e8, path: [C, J]}}
  h: {{EA: 1.0e8, path: [J, L]}}
effects: {{sway: false}}
"""


def test_nearly_unrestrained_massless_node_solves_correctly():
    angle = 1e-3
    r = solve(junction(angle))
    k, kh = 1.0e8 / 10, 1.0e8 / 5
    kv = 2 * k * np.sin(angle) ** 2
    # the junction's horizontal motion is stiff (2k), its vertical one soft: the answer
    # is the series spring, to the accuracy of the condensation (1e-9 of a 1e-6 ratio)
    np.testing.assert_allclose(r.omega, [np.sqrt(1 / (1 / kv + 1 / kh) / 1000)], rtol=1e-8)


@pytest.mark.parametrize("angle", [1e-5, 1e-7])
def test_unrestrained_beyond_resolution_is_flagged_not_garbage(angle):
    # below 1e-10 of the ropes' stiffness the motion is treated as free (a quasi-cyclic,
    # zero-frequency mode) and a warning says so, with the Rayleigh-quotient estimate of
    # the true frequency (within 5 %: the null vector is nearly the true mode)
    r = solve(junction(angle))
    assert r.rigid.tolist() == [True] and r.omega[0] == 0.0
    assert len(r.warnings) == 1 and "nearly unrestrained" in r.warnings[0]
    estimate = float(r.warnings[0].rsplit("about ", 1)[1].split()[0])
    kv, kh = 2 * 1.0e7 * np.sin(angle) ** 2, 2.0e7
    assert estimate == pytest.approx(np.sqrt(1 / (1 / kv + 1 / kh) / 1000), rel=0.05)


def test_heavy_sway_off_on_equivalence_of_a_vertical_hoist():
    # a vertical lift: the vertical modes are the same with and without sway
    model = load("case.yaml", HOIST.format(h=30, b=10, R=0.25))
    on, off = modes(model), modes(model, replace(model.effects, sway=False))
    np.testing.assert_allclose(off.omega[~off.rigid], on.omega[~on.rigid][-1:], rtol=1e-12)
