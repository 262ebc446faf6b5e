"""Value tests that kill mutants of cranefe/analysis/damping/modal.py that
tests/test_values.py and tests/test_damping.py left alive (tools/mutation.py
damping_modal; docs/testing.md, "Mutation testing"): no beam carried an absorption, and
the per-element shares of H_ii were never checked by value, and the predicted error of
the decoupled estimate was checked by no fast test.
"""

import math

import mpmath as mp
import numpy as np

from cranefe.analysis.damping.modal import modal_damping
from cranefe.analysis.modal import modes
from cranefe.model import load
from cranefe.system import assemble

BEAM = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {O: [0, 0, 0], T: [4, 0, 0]}
ground: [O]
masses: {T: 100.0}
members:
  arm: {type: beam, nodes: [O, T], E: 2.1e11, A: 1.0e-3, Iy: 1.0e-6, rho: 0,
        elements: 2, psi: 0.3}
effects: {structure: flexible}
"""

PAIR = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {G: [0, 0, 0], N0: [1, 0, 0], G2: [2, 0, 0]}
ground: [G, G2]
masses: {N0: 10}
springs:
  - {name: a, type: axial, nodes: [G, N0], stiffness: 1000, psi: 0.2}
  - {name: b, type: axial, nodes: [N0, G2], stiffness: 3000, psi: 0.1}
effects: {sway: false}
"""


def test_uniform_beam_absorption_gives_psi_over_4_pi_in_every_mode():
    """Every element with the same psi: K_psi = psi K, so H = psi V^T K V / (2 pi) =
    psi diag(w^2) / (2 pi) for mass-normalised modes: zeta_i = H_ii / (2 w_i^2) =
    psi / (4 pi) = 0.3 / (4 pi) in every mode, no coupling, the whole share in the
    member. Tolerance 1e-9: off-diagonal round-off of V^T K V relative to w_max^2."""
    model = load("beam.yaml", BEAM)
    s = assemble(model)
    md = modal_damping(s, modes(model, system=s))
    assert len(md.zeta) >= 2
    assert np.allclose(md.zeta, 0.3 / (4 * math.pi), rtol=1e-9)
    assert np.all(md.coupling < 1e-9)
    assert md.element_names == ("member arm",)
    assert np.allclose(md.shares, 1.0, rtol=1e-12)


def test_shares_of_two_springs_on_one_mass():
    """One mass m = 10 kg between springs k_a = 1000 (psi 0.2) and k_b = 3000 (psi 0.1):
    w^2 = 4000 / m, both springs stretch by the mode's amplitude, so the share of each in
    H_ii is c psi / sum c psi = 200 / 500 and 300 / 500, and zeta = (500 / (2 pi m)) /
    (2 w^2) = 1 / (32 pi)."""
    model = load("pair.yaml", PAIR)
    s = assemble(model)
    md = modal_damping(s, modes(model, system=s))
    assert np.allclose(md.omega, [math.sqrt(400.0)], rtol=1e-12)
    assert np.allclose(md.zeta, [1.0 / (32.0 * math.pi)], rtol=1e-12)
    assert md.element_names == ("spring a", "spring b")
    assert np.allclose(md.shares, [[0.4, 0.6]], rtol=1e-12)


# ------------------------------------------------- the predicted error (_predicted_error)
#
# Three modes w = (1, 1.3, 2) rad/s with a full modal absorption H (the one-absorber
# situation of docs/damping.md: every pair coupled). Written out for mode i with
# g_ij(c) = w_i^2 - w_j^2 + i c (H_ii - H_jj) and j, k the two other modes, the
# Rayleigh-Schroedinger expansion of the eigenvalue of diag(w^2) + i c H near
# w_i^2 + i c H_ii (V = i c H_off, V_ii = 0) is
#   second order: sum_j V_ij V_ji / g_ij = -c^2 sum_j H_ij^2 / g_ij,
#   third order:  sum_{j,k} V_ij V_jk V_ki / (g_ij g_ik) = (i c)^3 2 H_ij H_jk H_ki / (g_ij g_ik)
#                 (the two orderings (j, k) and (k, j); V_jj = 0 removes j = k).
# Complex stiffness: c = 1, zeta_h = Im mu / (2 Re mu). Viscous: c = sqrt(mu(c)) / w_i at
# its fixed point, lam = i w_i c, zeta_v = -Re lam / |lam|. predicted = zeta_decoupled /
# zeta - 1 (zeta_decoupled = H_ii / (2 w_i^2)), the larger in magnitude of the two.

mp.mp.dps = 30

W3 = (1.0, 1.3, 2.0)
H3 = ((0.040, 0.030, 0.025),
      (0.030, 0.150, 0.050),
      (0.025, 0.050, 0.080))


def _mu_by_hand(i, c, H=H3, w=W3):
    j, k = [n for n in range(3) if n != i]
    g = {n: mp.mpf(w[i])**2 - mp.mpf(w[n])**2 + 1j * c * (mp.mpf(H[i][i]) - H[n][n])
         for n in (j, k)}
    second = -c**2 * (mp.mpf(H[i][j])**2 / g[j] + mp.mpf(H[i][k])**2 / g[k])
    third = (1j * c)**3 * 2 * mp.mpf(H[i][j]) * H[j][k] * H[k][i] / (g[j] * g[k])
    return mp.mpf(w[i])**2 + 1j * c * H[i][i] + second + third


def _predicted_by_hand(i, H=H3, w=W3):
    z = mp.mpf(H[i][i]) / (2 * mp.mpf(w[i])**2)
    mu = _mu_by_hand(i, mp.mpf(1), H, w)
    e_h = z / (mp.im(mu) / (2 * mp.re(mu))) - 1
    c = mp.mpc(1)
    for _ in range(200):                  # a contraction by about zeta per step
        c = mp.sqrt(_mu_by_hand(i, c, H, w)) / w[i]
    lam = 1j * w[i] * c
    e_v = z / (-mp.re(lam) / abs(lam)) - 1
    return float(e_v if abs(e_v) > abs(e_h) else e_h), float(e_h), float(e_v)


def _kernel_inputs(H=H3, w=W3):
    from cranefe.analysis.damping.modal import _predicted_error
    H = np.array(H, dtype=float)
    w = np.array(w, dtype=float)
    h = np.diag(H).copy()
    return _predicted_error, w, h, h / (2 * w**2), H - np.diag(h)


def test_predicted_error_is_the_third_order_expansion_written_out():
    """`_predicted_error` against the expansion above evaluated at 30 digits, for the
    three modes asked in the order (2, 0, 1) (rows are positions, not a mask). Tolerance
    1e-10: the viscous fixed point stops at |dc| <= 1e-12 and e is a difference of O(1)
    numbers in double precision. The values are e = 7.54e-3, -1.98e-3, 6.71e-4 (the
    viscous estimate for mode 2, the complex-stiffness one for modes 0 and 1); dropping
    the third-order term, the c scaling of H or the fixed point moves them by far more
    than 1e-10 (next test). Before this test only tests/test_studies.py (not in the
    mutation preset) reached `_perturbed` and `_predicted_error`."""
    pe, w, h, zeta, off = _kernel_inputs()
    rows = [2, 0, 1]
    got = pe(w, h, zeta, off, np.array(rows))
    want = [_predicted_by_hand(i)[0] for i in rows]
    assert np.allclose(got, want, rtol=0, atol=1e-10), (got, want)


def test_predicted_error_parts_differ_so_the_choice_matters():
    """The complex-stiffness and viscous estimates differ by more than 1e-4 for every mode
    of the case (so a mutant that always takes one of them fails the test above); and the
    third-order term alone moves the estimate by more than 1e-5 (so dropping it does)."""
    for i in range(3):
        e, e_h, e_v = _predicted_by_hand(i)
        assert abs(e_h - e_v) > 1e-4
        mu3 = _mu_by_hand(i, mp.mpf(1))
        j, k = [n for n in range(3) if n != i]
        H0 = [list(r) for r in H3]
        H0[j][k] = H0[k][j] = 0.0          # kills the third-order term only
        assert abs(float(mp.im(mu3) - mp.im(_mu_by_hand(i, mp.mpf(1), H0)))) > 5e-7


def test_predicted_error_converges_at_fourth_order_to_the_exact_eigenvalues():
    """The estimate is the eigenvalue to third order, so its error against the exact
    answers (the complex-stiffness eigenvalue of diag(w^2) + i H and the viscous
    eigenvalue of lam^2 + lam H / w_i + diag(w^2), by mpmath's eig on the matrix and on
    the 6 x 6 companion form, nearest to w_i^2 resp. i w_i) falls as t^4 when the
    off-diagonal of H is scaled by t: from t = 1 to t = 1/2 by 16 (12 to 20 allowed:
    the fifth-order remainder). Checks the expansion against the eigenproblem it
    approximates, independently of the hand formula."""
    def exact_errors(t):
        H = mp.matrix(3, 3)
        for a in range(3):
            for b in range(3):
                H[a, b] = H3[a][b] * (1 if a == b else t)
        out = []
        for i in range(3):
            z = mp.mpf(H3[i][i]) / (2 * mp.mpf(W3[i])**2)
            S = mp.diag([mp.mpf(x)**2 for x in W3]) + 1j * H
            ev = mp.eig(S, left=False, right=False)
            mu = min(ev, key=lambda x: abs(x - W3[i]**2))
            e_h = z / (mp.im(mu) / (2 * mp.re(mu))) - 1
            A = mp.zeros(6, 6)
            for a in range(3):
                A[a, 3 + a] = 1
                A[3 + a, a] = -mp.mpf(W3[a])**2
                for b in range(3):
                    A[3 + a, 3 + b] -= H[a, b] / W3[i]
            lams = mp.eig(A, left=False, right=False)
            lam = min(lams, key=lambda x: abs(x - 1j * W3[i]))
            e_v = z / (-mp.re(lam) / abs(lam)) - 1
            out.append((e_h, e_v))
        return out

    def estimated(t):
        pe, w, h, zeta, off = _kernel_inputs()
        return pe(w, h, zeta, off * t, np.arange(3))

    miss = []
    for t in (1.0, 0.5):
        ex = exact_errors(t)
        est = estimated(t)
        # compare with the exact error of the kind the estimate reports
        miss.append([min(abs(est[i] - float(ex[i][0])), abs(est[i] - float(ex[i][1])))
                     for i in range(3)])
    ratio = np.array(miss[0]) / np.array(miss[1])
    assert np.all((ratio > 12) & (ratio < 20)), (miss, ratio)


def test_predicted_error_of_an_undamped_mode_is_zero_and_of_a_lone_mode_exact():
    """A mode with H_ii = 0 is reported 0 (not NaN, not inf), whatever its partners. A
    mode alone (no off-diagonal): the complex-stiffness zeta = H / (2 w^2) is the
    decoupled one (e_h = 0), and the viscous fixed point c^2 = 1 + 2 i z c solves
    lam^2 + 2 z w lam + w^2 = 0 exactly (lam = i w c), whose -Re lam / |lam| is z:
    e = 0 too. Tolerance 1e-12 (the fixed point's stop)."""
    pe, w, h, zeta, off = _kernel_inputs(H=((0.0, 0.0, 0.0), (0.0, 0.05, 0.0),
                                            (0.0, 0.0, 0.03)))
    got = pe(w, h, zeta, off, np.arange(3))
    assert got[0] == 0.0
    assert np.allclose(got[1:], 0.0, atol=1e-12)
