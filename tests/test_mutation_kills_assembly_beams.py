"""Kill tests for cranefe/assembly/ (inertia.py's `_beams` and `_point_masses`, beams.py's
end releases; tools/mutation.py assembly; docs/testing.md, "Mutation testing"): beams
with mass, Timoshenko beams, released ends and a free node's rotary inertia, through the
public API (cranefe.load + cranefe.modes on small models), against closed forms:

- a massless cantilever with a tip mass m and rotary inertia J: the 2x2 eigenproblem of
  the tip's (w, theta) with the exact end stiffness EI/L^3 [[12, 6L], [6L, 4L^2]];
- a thick Timoshenko cantilever with mass: its first two bending frequencies against the
  roots of the Timoshenko equations (shear and rotary inertia) integrated exactly
  (matrix exponential of the constant-coefficient system, written here);
- a beam with mass clamped at both ends but released (ry) there: a simply supported
  beam, w_n = (n pi / L)^2 sqrt(EI / rho A);
- a massless beam with a centre mass, clamped at both ends (k = 192 EI / L^3) and with
  one end released (a propped cantilever, k = 768 EI / (7 L^3));
- a lumped-mass pinned beam against the exact dispersion of cubic elements;
- an Euler-Bernoulli beam with mass next to a Timoshenko member (no rotary inertia).
"""

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.optimize import brentq

import cranefe

E, G_MOD = 2.1e11, 8.1e10


def _modes(tmp_path, text):
    p = tmp_path / "m.yaml"
    p.write_text(text)
    return np.sort(np.asarray(cranefe.modes(cranefe.load(p)).omega))


TIP = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 0], T: [2, 0, 0]}
ground: [O]
masses: {T: {mass: 100, inertia: 5}}
members:
  arm: {type: beam, nodes: [O, T], E: 2.1e11, A: 1.0e-2, Iy: 1.0e-6, rho: 0}
effects: {structure: flexible, sway: false}
"""


def test_tip_mass_with_rotary_inertia_on_a_massless_cantilever(tmp_path):
    """det(K - w^2 diag(m, J)) = 0 with K = EI/L^3 [[12, 6L], [6L, 4L^2]] (the exact
    end stiffness of a uniform Euler-Bernoulli cantilever, cubic deflection): w^2 =
    (k11 J + k22 m -+ sqrt((k11 J + k22 m)^2 - 4 m J det K)) / (2 m J); the axial mode
    EA / (L m). Without J the rotation is massless and only one bending mode is left.
    Tolerance 1e-9: an eigen-solve of 3 coordinates."""
    L, EI, m, J = 2.0, E * 1e-6, 100.0, 5.0
    k11, k12, k22 = 12 * EI / L**3, 6 * EI / L**2, 4 * EI / L
    s = k11 * J + k22 * m
    d = np.sqrt(s**2 - 4 * m * J * (k11 * k22 - k12**2))
    bend = np.sqrt([(s - d) / (2 * m * J), (s + d) / (2 * m * J)])
    axial = np.sqrt(E * 1e-2 / L / m)
    w = _modes(tmp_path, TIP)
    assert w == pytest.approx(np.sort(np.r_[bend, axial]), rel=1e-9)


def _timoshenko_roots(L, EI, kGA, rhoA, rhoI, count, w_max):
    """Clamped-free Timoshenko beam: kGA (w'' - psi') + rhoA w^2 w = 0,
    EI psi'' + kGA (w' - psi) + rhoI w^2 psi = 0 (harmonic amplitudes). State
    y = (w, w', psi, psi'), y(L) = expm(A L) y(0); clamped: w(0) = psi(0) = 0; free:
    EI psi'(L) = 0 and kGA (w'(L) - psi(L)) = 0: the 2x2 determinant of these rows on
    the columns of w'(0), psi'(0) vanishes at a natural frequency."""
    def det(om):
        A = np.array([[0, 1, 0, 0],
                      [-rhoA * om**2 / kGA, 0, 0, 1],
                      [0, 0, 0, 1],
                      [0, -kGA / EI, (kGA - rhoI * om**2) / EI, 0]])
        P = expm(A * L)[:, [1, 3]]
        rows = np.array([P[3], P[1] - P[2]])
        return np.linalg.det(rows)

    grid = np.linspace(1.0, w_max, 200)   # roots are > 1000 rad/s apart
    vals = [det(x) for x in grid]
    roots = [brentq(det, a, b, xtol=1e-12, rtol=1e-14)
             for a, b, fa, fb in zip(grid, grid[1:], vals, vals[1:]) if fa * fb < 0]
    return np.array(roots[:count])


THICK = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 0], T: [1, 0, 0]}
ground: [O]
members:
  arm: {type: beam, nodes: [O, T], E: 2.1e11, G: 8.1e10, A: 0.02, Iy: 6.6666666666666667e-5,
        Asz: 0.016666666666666667, rho: 7850, elements: 32}
effects: {structure: flexible, sway: false}
"""


def test_timoshenko_cantilever_with_mass_against_the_exact_equations(tmp_path):
    """A 0.1 x 0.2 m steel section, 1 m long (L / r = 17), shear area 5/6 A: shear and
    rotary inertia lower the first two bending frequencies by about 3 % and 17 % from
    Euler-Bernoulli. 32 elements: the discretisation error falls as h^2 here (measured:
    2.0e-5 and 5.4e-4 with 16 elements, 5e-6 and 1.4e-4 with 32); tolerances 2e-5 and
    4e-4, which the mutants of the mass's shear parameters exceed (checked; `rotary`
    defaults to everywhere, so its mutants need the mixed model below). The axial
    modes (about 8100 rad/s and above) lie between and are skipped by matching each exact
    root to the nearest computed frequency."""
    A, I, rho = 0.02, 0.2**3 * 0.1 / 12, 7850.0
    exact = _timoshenko_roots(1.0, E * I, G_MOD * A * 5 / 6, rho * A, rho * I, 2, 8000.0)
    assert len(exact) == 2
    w = _modes(tmp_path, THICK)
    got = [w[np.argmin(abs(w - r))] for r in exact]
    assert got[0] == pytest.approx(exact[0], rel=2e-5)
    assert got[1] == pytest.approx(exact[1], rel=4e-4)


SIMPLE = """cranefe: 1
plane: xz
nodes: {P: [0, 0, 0], Q: [4, 0, 0]}
ground: [P, Q]
members:
  b: {type: beam, nodes: [P, Q], E: 2.1e11, A: 1.0e-3, Iy: 1.0e-7, rho: 7850,
      elements: 16, releases: {P: [ry], Q: [ry]}}
effects: {structure: flexible, sway: false}
"""


def test_released_ends_make_a_simply_supported_beam(tmp_path):
    """Clamped ends released in ry are pins: w_n = (n pi / L)^2 sqrt(EI / rho A) = 31.9,
    127.6, 287 rad/s (axial modes from 4060 rad/s; clamped: 72.3 rad/s). 16 cubic
    elements: the error falls as h^4 (measured 1.7e-5, 2.8e-4, 1.4e-3 with 8 elements,
    1.0e-6, 1.7e-5, 8.5e-5 with 16); tolerances 3e-6, 5e-5, 2.5e-4."""
    L = 4.0
    c = np.sqrt(E * 1e-7 / (7850 * 1e-3))
    exact = (np.arange(1, 4) * np.pi / L) ** 2 * c
    w = _modes(tmp_path, SIMPLE)
    for k, tol in enumerate((3e-6, 5e-5, 2.5e-4)):
        assert w[k] == pytest.approx(exact[k], rel=tol)


CENTRE = """cranefe: 1
plane: xz
nodes: {{P: [0, 0, 0], C: [2, 0, 0], Q: [4, 0, 0]}}
ground: [P, Q]
masses: {{C: 500}}
members:
  b: {{type: beam, nodes: [P, C, Q], E: 2.1e11, A: 1.0e-3, Iy: 1.0e-6, rho: 0{rel}}}
effects: {{structure: flexible, sway: false}}
"""


@pytest.mark.parametrize("rel, factor", [("", 192.0), (", releases: {Q: [ry]}", 768 / 7)])
def test_centre_mass_on_a_clamped_and_a_propped_beam(tmp_path, rel, factor):
    """Massless beam, 500 kg at the centre (the rotation there is massless and
    condensed): bending w^2 = k / m with k = 192 EI / L^3 clamped-clamped, 768 EI /
    (7 L^3) with Q pinned (the propped cantilever's centre deflection 7 P L^3 /
    (768 EI)); axial w^2 = 2 EA / (L/2) / m. Exact for cubic elements under a point load;
    tolerance 1e-9 (eigen-solve)."""
    L, m = 4.0, 500.0
    bend = np.sqrt(factor * E * 1e-6 / L**3 / m)
    axial = np.sqrt(2 * E * 1e-3 / (L / 2) / m)
    w = _modes(tmp_path, CENTRE.format(rel=rel))
    assert w == pytest.approx(np.sort([bend, axial]), rel=1e-9)


def test_lumped_beam_mass_on_a_simply_supported_beam(tmp_path):
    """Lumped mass (m_n = rho A h at each interior node, translations only) on n cubic
    elements of a pinned-pinned beam: the sine modes w_j = sin(j theta), theta = k pi / n,
    are exact for the discrete system. Condensing the massless rotations of a wave
    (w_j, phi_j) = (W, Phi) e^(i j theta) from the assembled element stiffness
    EI/h^3 [[12, 6h, -12, 6h], [6h, 4h^2, -6h, 2h^2], ...]: the moment row gives
    Phi = 3 i W sin(theta) / (h (2 + cos theta)), the force row then
    w^2 = 12 EI (1 - cos theta)^2 / (m_n h^3 (2 + cos theta)) (-> (k pi / L)^4 EI / rho A
    as h -> 0). Tolerance 1e-9 (eigen-solve); the consistent mass differs from these by
    3.4e-5, 5.8e-4 and 3.3e-3."""
    n, L = 8, 4.0
    h, EI, mn = L / n, E * 1e-7, 7850 * 1e-3 * L / n
    th = np.arange(1, 4) * np.pi / n
    exact = np.sqrt(12 * EI * (1 - np.cos(th)) ** 2 / (mn * h**3 * (2 + np.cos(th))))
    w = _modes(tmp_path, SIMPLE.replace("elements: 16", "elements: 8, mass: lumped"))
    assert w[:3] == pytest.approx(exact, rel=1e-9)


MIXED = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 0], T: [1, 0, 0], P: [0, 0, 5], Q: [2, 0, 5]}
ground: [O, P]
members:
  thick: {type: beam, nodes: [O, T], E: 2.1e11, G: 8.1e10, A: 0.02, Iy: 6.6666666666666667e-5,
          Asz: 0.016666666666666667, rho: 7850, elements: 8}
  plain: {type: beam, nodes: [P, Q], E: 2.1e11, A: 0.02, Iy: 6.6666666666666667e-5,
          rho: 7850, elements: 16}
effects: {structure: flexible, sway: false}
"""


def test_an_euler_bernoulli_beam_next_to_a_timoshenko_one_has_no_rotary_inertia(tmp_path):
    """The Euler-Bernoulli cantilever `plain` (2 m, the same thick section, L / r = 35)
    shares the model with a Timoshenko member: its mass must stay Euler-Bernoulli (no
    rotary inertia rho I). Exact: w_k = (beta_k L)^2 sqrt(EI / (rho A L^4)) with
    beta_1 L = 1.8751040687, beta_2 L = 4.6940911330 (roots of 1 + cos x cosh x = 0,
    solved here). 16 cubic elements: errors 1.3e-7 and 5.1e-6 (h^4); tolerance 1e-5,
    which the rotary inertia exceeds (checked with `rotary` dropped)."""
    roots = [brentq(lambda x: 1 + np.cos(x) * np.cosh(x), a, b, xtol=1e-14)
             for a, b in ((1.5, 2.5), (4.0, 5.0))]
    c = np.sqrt(E * 6.6666666666666667e-5 / (7850 * 0.02 * 2.0**4))
    exact = np.array(roots) ** 2 * c
    w = _modes(tmp_path, MIXED)
    got = [w[np.argmin(abs(w - r))] for r in exact]
    assert got == pytest.approx(exact, rel=1e-5)


CHAIN = """cranefe: 1
plane: xz
nodes: {S: [0, 0, 10], B: [0, 0, 0]}
ground: [S]
members:
  c: {type: beam, nodes: [S, B], E: 2.1e11, A: 1.0e-4, Iy: 1.0e-14, rho: 7850,
      elements: 16, releases: {S: [ry]}}
effects: {structure: flexible, sway: true}
"""


def test_a_hanging_beam_without_bending_stiffness_swings_as_a_chain(tmp_path):
    """A 10 m beam pinned at the top, hanging under its own weight, with a negligible EI
    (EI / (T L^2) = 2.7e-7, T = rho A g L the top tension): its lateral modes are the
    hanging chain's, w_n = (j_0,n / 2) sqrt(g / L) (j_0,n the zeros of J_0). Only the
    geometric stiffness of the tension varying along each element (-rho A g per metre)
    holds it. 16 consistent elements: errors 1.0e-6 and 2.3e-5 (mostly the bending
    stiffness, which grows with the mode number); tolerances 5e-6 and 1e-4. A tension
    taken as constant along each element, or the geometric stiffness mis-scaled, moves
    them by 1e-3 and more."""
    from scipy.special import jn_zeros
    exact = jn_zeros(0, 2) / 2 * np.sqrt(9.81 / 10)
    w = _modes(tmp_path, CHAIN)
    assert w[0] == pytest.approx(exact[0], rel=5e-6)
    assert w[1] == pytest.approx(exact[1], rel=1e-4)


# the static solve sees the lateral stiffness 3 EI / L^3 next to EA / L (rcond ~1e-27);
# gravity does not load that direction, so its solution (0) is exact
@pytest.mark.filterwarnings("ignore:An ill-conditioned matrix")
def test_a_lumped_hanging_element_is_a_pendulum(tmp_path):
    """One element of the hanging beam above with lumped mass: its bottom node carries
    m/2 (the top half is on the ground node), the element a constant tension m g / 2
    (lumped weights act at the nodes: no variation along the element). With EI -> 0
    the condensed geometric stiffness of the element is N / L (its cubic shape with free
    end rotations minimising the integral of N w'^2 is straight), so the lateral mode is
    a pendulum, w^2 = (m g / 2 / L) / (m / 2) = g / L. Tolerance 1e-6 (EI / (N L^2) =
    5.4e-7)."""
    text = CHAIN.replace("elements: 16", "elements: 1, mass: lumped")
    w = _modes(tmp_path, text)
    assert w[0] == pytest.approx(np.sqrt(9.81 / 10), rel=1e-6)
