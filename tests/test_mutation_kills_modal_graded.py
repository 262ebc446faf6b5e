"""Fast value tests that kill mutants of cranefe/analysis/modal.py and graded.py left by
tests/test_mutation_kills_modal_paths.py (tools/mutation.py modal, graded;
docs/testing.md, "Mutation testing"): a graded model whose condensed inertia is NOT
diagonal on the Cholesky-factor fallback (a cart on a slider carrying a pendulum above
its hinge), a negative part merged over two coordinates that are not coordinate 0, and
the "fewer element rows than coordinates" exit. References: the 2 x 2 pair derived by
hand in the coordinates (cart x, pendulum angle), solved in 50-digit arithmetic.
"""

from functools import lru_cache

import mpmath as mp
import numpy as np
import pytest

from cranefe.analysis.modal import modes
from cranefe.model import load

G = 9.81
MC, MP, L, IC = 1000.0, 800.0, 3.0, 900.0   # cart, pendulum mass, hinge to com, Ic


def cart(kr, kE, far=None, tip=None):
    """Cart C (mass MC) on a horizontal slider; pendulum p hinged on it at H, its centre
    of mass L above H (a negative load stiffness -MP g L on its angle); a rotational
    spring kr (ground to p) and a horizontal axial spring kE from p's top E (z = 2L) to
    the ground. far = (k, m): a separate body of mass m on a horizontal slider and an
    axial spring k to the ground (an uncoupled third coordinate, w^2 = k / m).
    tip = (k, m): a body d of mass m on a horizontal slider at D (5 m right of E),
    joined to E only by a horizontal axial spring k (a third coordinate coupled to p)."""
    springs = [(f"  - {{name: r, type: rotational, bodies: [ground, p], at: H, "
                f"stiffness: {kr!r}}}"),
               f"  - {{name: e, type: axial, nodes: [E, W], stiffness: {kE!r}}}"]
    nodes, body, joint = "", "", ""
    if tip:
        nodes += f", D: [5, 0, {2 * L}]"
        body += (f"  d: {{mass: {tip[1]!r}, com: [5, 0, {2 * L}], inertia: 1.0e-9, "
                 "nodes: [D]}\n")
        joint += "  - {type: slider, bodies: [ground, d], at: D, axis: [1, 0, 0]}\n"
        springs.append(f"  - {{name: d, type: axial, nodes: [E, D], "
                       f"stiffness: {tip[0]!r}}}")
    if far:
        nodes += ", N: [20, 0, 0], Q: [15, 0, 0]"
        body += f"  f: {{mass: {far[1]!r}, com: [20, 0, 0], inertia: 1.0, nodes: [N]}}\n"
        joint += "  - {type: slider, bodies: [ground, f], at: N, axis: [1, 0, 0]}\n"
        springs.append(f"  - {{name: f, type: axial, nodes: [Q, N], "
                       f"stiffness: {far[0]!r}}}")
    return load("cart.yaml", f"""cranefe: 1
plane: xz
nodes: {{H: [0, 0, 0], E: [0, 0, {2 * L}], W: [-5, 0, {2 * L}]{nodes}}}
ground: [W{", Q" if far else ""}]
bodies:
  c: {{mass: {MC}, com: [0, 0, 0], inertia: 10.0, nodes: [H]}}
  p: {{mass: {MP}, com: [0, 0, {L}], inertia: {IC}, nodes: [E]}}
{body}joints:
  - {{type: slider, bodies: [ground, c], at: H, axis: [1, 0, 0]}}
{joint}  - {{type: hinge, bodies: [c, p], at: H}}
springs:
""" + "\n".join(springs) + "\neffects: {sway: true}\n")


@lru_cache(maxsize=None)
def cart_reference(kr, kE):
    """(w^2 ascending, shapes) of the cart and pendulum in (x of H, angle th), 50 digits.
    E moves x + 2 L th, the centre of mass x + L th (small angles), so
    T = (MC + MP) x'^2 / 2 + MP L x' th' + (IC + MP L^2) th'^2 / 2 and
    V = kE (x + 2 L th)^2 / 2 + (kr - MP g L) th^2 / 2 (the com drops L th^2 / 2):
    M = [[MC + MP, MP L], [MP L, IC + MP L^2]],
    K = kE [[1, 2 L], [2 L, 4 L^2]] + [[0, 0], [0, kr - MP g L]].
    Shapes M-normalised, as node x-translations of H and E per mode (column)."""
    with mp.workdps(50):
        f = mp.mpf
        l, mc, mp_, ic = f(L), f(MC), f(MP), f(IC)
        M = mp.matrix([[mc + mp_, mp_ * l], [mp_ * l, ic + mp_ * l * l]])
        K = f(kE) * mp.matrix([[1, 2 * l], [2 * l, 4 * l * l]])
        K[1, 1] += f(kr) - mp_ * f(G) * l
        Lm = mp.cholesky(M)
        Li = mp.inverse(Lm)
        w2, V = mp.eigsy(Li * K * Li.T)
        Y = Li.T * V                       # M-normalised
        idx = sorted(range(2), key=lambda i: w2[i])
        shapes = [[float(Y[0, i]), float(Y[0, i] + 2 * l * Y[1, i])] for i in idx]
        return tuple(float(w2[i]) for i in idx), tuple(map(tuple, shapes))


def _node_x(r, name, model):
    return r.node_shapes[:, model.node_names.index(name), 0]


def _check_shapes(r, model, shapes, cols, rtol):
    """Node x-translations of H and E against the reference, up to each mode's sign."""
    for j, col in enumerate(cols):
        got = np.array([_node_x(r, "H", model)[col], _node_x(r, "E", model)[col]])
        ref = np.array(shapes[j])
        sign = np.sign(got @ ref)
        np.testing.assert_allclose(sign * got, ref, rtol=rtol, atol=rtol * abs(ref).max())


def test_cholesky_fallback_with_coupled_inertia_shapes():
    # kr = 3e11 beside kE = 1e4: spread of K_ii/M_ii > GRADED; the pendulum's negative
    # load-stiffness row meets every row (its coordinates are p's com ux and ry, on
    # which every element acts) -> not merged: Cholesky factors of K1 and of the
    # NON-diagonal M1 (cart-pendulum coupling MP L), B = L_M^-1 L_K, Jacobi SVD, then
    # y = L_M^-T u. Tolerance: w^2 to 1e-9 (the fallback is as accurate as the assembled
    # K1, whose entries carry 3e11 beside 3.6e5: a few 1e-12 seen); shapes 1e-8.
    kr, kE = 3.0e11, 1.0e4
    model = cart(kr, kE)
    r = modes(model)
    assert "assembled K factorised" in r.graded
    w2, shapes = cart_reference(kr, kE)
    assert r.omega**2 == pytest.approx(list(w2), rel=1e-9)
    _check_shapes(r, model, shapes, [0, 1], 1e-8)


def test_negative_part_merged_over_two_coordinates_away_from_coordinate_0():
    # With a separate 1 kg mass on a 1e12 N/m spring (a third, uncoupled coordinate;
    # spread 1e12 -> graded), the pendulum's negative row meets the rows of kr and kE
    # only: merged with them over the TWO coordinates of p (ux, ry), not all rows, so
    # K_loc = kE r r^T + (kr - MP g L) e e^T (positive definite: kr > MP g L) is
    # factorised by `_psd_rows` into two rows. Frequencies: the 2 x 2 pair and
    # sqrt(1e12 / 1); 1e-10 (the element factor keeps relative accuracy: round-off).
    kr, kE = 5.0e4, 1.0e4
    model = cart(kr, kE, far=(1.0e12, 1.0))
    r = modes(model)
    assert r.graded.startswith("element factor (negative parts")
    w2, shapes = cart_reference(kr, kE)
    assert r.omega**2 == pytest.approx(sorted(list(w2) + [1.0e12]), rel=1e-10)
    _check_shapes(r, model, shapes, [0, 1], 1e-8)


def test_fewer_element_rows_than_coordinates_exit():
    # kr = MP g L exactly: the merged local block kE r r^T has rank 1, its null row is
    # dropped, so the factor has 2 rows for 3 coordinates -> the graded path gives up
    # ("fewer element rows than coordinates") and the assembled K is used. Exact:
    # the mode x = -2 L th (E still) is neutral (w = 0, rigid: its terms kr and
    # -MP g L cancel), the other w^2 from the 2 x 2 pair, and sqrt(1e12).
    kr, kE = MP * G * L, 1.0e4
    model = cart(kr, kE, far=(1.0e12, 1.0))
    r = modes(model)
    assert "fewer element rows than coordinates" in r.graded
    w2, _ = cart_reference(kr, kE)
    assert abs(w2[0]) < 1e-15 * w2[1]       # only the rounding of kr = MP * G * L in floats
    assert r.rigid.tolist() == [True, False, False]
    assert r.omega[0] == 0.0
    assert r.omega[1:] ** 2 == pytest.approx([w2[1], 1.0e12], rel=1e-9)


@lru_cache(maxsize=None)
def tip_reference(kr, kE, kd, md):
    """(w^2 ascending, shapes) of `cart` with tip = (kd, md) in (x of H, th, x of D), 50
    digits. As `cart_reference`, plus the tip body's T = md xd'^2 / 2 and the spring d
    stretched by xd - (x + 2 L th) (E moves x + 2 L th):
    M = diag-block([[MC + MP, MP L], [MP L, IC + MP L^2]], md),
    K = kE a a^T + kd b b^T + (kr - MP g L) e_th e_th^T, a = (1, 2L, 0), b = (-1, -2L, 1).
    Shapes M-normalised, as node x-translations of H, E and D per mode."""
    with mp.workdps(50):
        f = mp.mpf
        l, mc, mp_, ic = f(L), f(MC), f(MP), f(IC)
        M = mp.matrix([[mc + mp_, mp_ * l, 0], [mp_ * l, ic + mp_ * l * l, 0],
                       [0, 0, f(md)]])
        a = mp.matrix([[1], [2 * l], [0]])
        b = mp.matrix([[-1], [-2 * l], [1]])
        K = f(kE) * a * a.T + f(kd) * b * b.T
        K[1, 1] += f(kr) - mp_ * f(G) * l
        Li = mp.inverse(mp.cholesky(M))
        w2, V = mp.eigsy(Li * K * Li.T)
        Y = Li.T * V                       # M-normalised
        idx = sorted(range(3), key=lambda i: w2[i])
        shapes = [[float(Y[0, i]), float(Y[0, i] + 2 * l * Y[1, i]), float(Y[2, i])]
                  for i in idx]
        return tuple(float(w2[i]) for i in idx), tuple(map(tuple, shapes))


def test_cholesky_fallback_keeps_the_low_modes_under_a_mass_contrast():
    # A 1e-12 kg body d on a 100 N/m spring from E (w^2 = 1e14) beside the 1800 kg cart
    # (w^2 ~ 4.5): the spread of K_ii / M_ii is ~1e13 > GRADED, and d's spring meets
    # p's coordinates, so the pendulum's negative row meets every row -> not merged:
    # the Cholesky fallback B = L_M^-1 L_K and the Jacobi SVD, which keeps the low w^2
    # to ~5e-11 (kr = 1e6 keeps K1 well conditioned by rows). eigh on (K1, M1) has
    # absolute errors eps |lam_max| ~ 1e-2 s^-2: the low w^2 off by 2e-5 and 1e-4
    # (checked), so a fallback that drops to eigh fails. Tolerance 1e-9 on w^2 (a few
    # 1e-11 seen); shapes of the two low modes 1e-8.
    kr, kE, kd, md = 1.0e6, 1.0e4, 1.0e2, 1.0e-12
    model = cart(kr, kE, tip=(kd, md))
    r = modes(model)
    assert "assembled K factorised" in r.graded
    w2, shapes = tip_reference(kr, kE, kd, md)
    assert r.omega**2 == pytest.approx(list(w2), rel=1e-9)
    for j in range(2):
        got = np.array([_node_x(r, n, model)[j] for n in "HED"])
        ref = np.array(shapes[j])
        sign = np.sign(got @ ref)
        np.testing.assert_allclose(sign * got, ref, rtol=1e-8, atol=1e-8 * abs(ref).max())


def test_merge_negative_keeps_every_column_of_the_merged_rows():
    # `_merge_negative` on a factor written by hand (exact small integers): rows
    # r0 = (1, 1, 0) negative, r1 = r2 = (1, 1, 0), r3 = (3, 1, 0), r4 = (0, 0, 2).
    # The first ring (rows touching r0's columns 0 and 1) is r0..r3 and not every row;
    # its K_loc = -a a^T + 2 a a^T + b b^T = [[10, 4], [4, 2]] (a = (1, 1), b = (3, 1))
    # is positive definite, so it is merged. Every merged row is non-zero in both
    # columns, and all of them are exactly 1 in column 1: the merge must take the
    # columns any row of the set touches, not those where some row is zero or not 1.
    # Contract: merged^T merged = F^T diag(sign) F = [[10, 4, 0], [4, 2, 0], [0, 0, 4]]
    # (by hand); round-off of a 2 x 2 eigen-decomposition only: 1e-13.
    from cranefe.analysis.graded import _merge_negative
    F = np.array([[1.0, 1, 0], [1, 1, 0], [1, 1, 0], [3, 1, 0], [0, 0, 2]])
    sign = np.array([-1.0, 1, 1, 1, 1])
    out = _merge_negative(F, sign)
    assert out is not None and out.shape == (3, 3)
    np.testing.assert_array_equal(out[0], [0.0, 0.0, 2.0])       # r4 kept as it was
    K = np.array([[10.0, 4, 0], [4, 2, 0], [0, 0, 4]])
    np.testing.assert_allclose(out.T @ out, K, rtol=0, atol=1e-13 * 10)
