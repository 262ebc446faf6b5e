"""Structures as engineers model them (issue 19): Timoshenko beams, rotary inertia of
point masses on beam nodes, supports and member-end releases, self-weight buckling."""

import numpy as np
import pytest

from cranefe.analysis.modal import modes
from cranefe.cases import matched, timoshenko_simply_supported
from cranefe.elements import beam_mass, beam_stiffness, shear_factors
from cranefe.elements.beams import _timoshenko_mass4


# ------------------------------------------------------------------ Timoshenko beams

def _timoshenko_shapes(xi, l, phi):
    """Static Timoshenko shape functions of deflection v, rotation theta and their
    derivatives at xi = x / l (Friedman & Kosmatka 1993, eq. 13), independent of the
    kernel's closed forms."""
    mu = 1 / (1 + phi)
    v = mu * np.array([2 * xi**3 - 3 * xi**2 - phi * xi + 1 + phi,
                       l * (xi**3 - (2 + phi / 2) * xi**2 + (1 + phi / 2) * xi),
                       -2 * xi**3 + 3 * xi**2 + phi * xi,
                       l * (xi**3 - (1 - phi / 2) * xi**2 - phi / 2 * xi)])
    dv = mu / l * np.array([6 * xi**2 - 6 * xi - phi,
                            l * (3 * xi**2 - (4 + phi) * xi + 1 + phi / 2),
                            -6 * xi**2 + 6 * xi + phi,
                            l * (3 * xi**2 - (2 - phi) * xi - phi / 2)])
    t = mu * np.array([6 / l * (xi**2 - xi), 3 * xi**2 - (4 + phi) * xi + 1 + phi,
                       -6 / l * (xi**2 - xi), 3 * xi**2 - (2 - phi) * xi])
    dt = mu / l * np.array([6 / l * (2 * xi - 1), 6 * xi - 4 - phi, -6 / l * (2 * xi - 1),
                            6 * xi - 2 + phi])
    return v, dv, t, dt


def test_timoshenko_kernels_are_the_energies_of_their_shape_functions():
    # K = int EI t' t'^T + k G A (v' - t)(v' - t)^T, M = int rho A v v^T + rho I t t^T,
    # by 8-point Gauss (exact for these polynomials); round-off is the only difference
    E, G, A, I, rho, As, l = 2.0e11, 8.0e10, 0.02, 3.0e-4, 7850.0, 0.015, 0.9
    phi_y, phi_z = shear_factors(E, G, I, I, np.array([As]), np.array([As]), np.array([l]))
    phi = phi_y[0]
    assert phi == pytest.approx(12 * E * I / (G * As * l**2), rel=1e-15)
    xg, wg = np.polynomial.legendre.leggauss(8)
    K, M = np.zeros((4, 4)), np.zeros((4, 4))
    for xi, w in zip((xg + 1) / 2, wg / 2):
        v, dv, t, dt = _timoshenko_shapes(xi, l, phi)
        K += w * l * (E * I * np.outer(dt, dt) + G * As * np.outer(dv - t, dv - t))
        M += w * l * (rho * A * np.outer(v, v) + rho * I * np.outer(t, t))
    k12 = beam_stiffness(np.array([E]), np.array([G]), np.array([A]), np.array([I]),
                         np.array([I]), np.array([1e-4]), np.array([l]), phi_y, phi_z)[0]
    m12 = beam_mass(np.array([rho]), np.array([A]), np.array([I]), np.array([I]),
                    np.array([l]), False, phi_y, phi_z)[0]
    xy = [1, 5, 7, 11]                       # (v, theta_z) in the local x-y plane
    assert k12[np.ix_(xy, xy)] == pytest.approx(K, rel=1e-13, abs=1e-13 * abs(K).max())
    assert m12[np.ix_(xy, xy)] == pytest.approx(M, rel=1e-13, abs=1e-13 * abs(M).max())
    # x-z plane: w and theta_y = -w', the same blocks with the coupling signs flipped
    s = np.array([1, -1, 1, -1])
    xz = [2, 4, 8, 10]
    assert k12[np.ix_(xz, xz)] == pytest.approx(K * np.outer(s, s), rel=1e-13,
                                                abs=1e-13 * abs(K).max())


def test_no_shear_area_is_the_euler_bernoulli_kernel_exactly():
    ne = 3
    E, G, A, Iy, Iz, J = (np.full(ne, x) for x in (2e11, 8e10, 0.01, 2e-4, 3e-4, 1e-4))
    l = np.array([0.5, 1.0, 2.0])
    phi_y, phi_z = shear_factors(E, G, Iy, Iz, np.zeros(ne), np.zeros(ne), l)
    assert not phi_y.any() and not phi_z.any()
    eb = beam_stiffness(E, G, A, Iy, Iz, J, l)
    assert np.array_equal(beam_stiffness(E, G, A, Iy, Iz, J, l, phi_y, phi_z), eb)
    # without rotary inertia the Timoshenko mass at phi = 0 is the cubic one (to round-off)
    m_eb = beam_mass(np.full(ne, 7850.0), A, Iy, Iz, l)
    m_t = beam_mass(np.full(ne, 7850.0), A, Iy, Iz, l, False, phi_y, phi_z,
                    rotary=np.zeros(ne))
    assert m_t == pytest.approx(m_eb, rel=1e-14, abs=1e-14 * abs(m_eb).max())
    rot = _timoshenko_mass4(np.zeros(1), np.ones(1), np.ones(1), np.zeros(1))[0]
    # rotary inertia alone: the Rayleigh term rho I / (30 l) [36, 3l, -36, 3l; ...]
    assert rot * 30 == pytest.approx(np.array([[36, 3, -36, 3], [3, 4, -3, -1],
                                               [-36, -3, 36, -3], [3, -1, -3, 4]]), rel=1e-14)


def test_timoshenko_cantilever_tip_deflection_is_exact_with_one_element():
    # P L^3 / (3 E I) + P L / (G As): the static shape functions are exact for end loads
    E, G, I, As, L, P = 2.0e11, 8.0e10, 2.0e-4, 0.01, 2.0, 1.0e4
    phi_y, _ = shear_factors(E, G, I, I, np.array([As]), np.array([As]), np.array([L]))
    k = beam_stiffness(*(np.array([x]) for x in (E, G, 0.02, I, I, 1e-4, L)), phi_y,
                       phi_y)[0]
    free = [7, 11]
    d = np.linalg.solve(k[np.ix_(free, free)], [P, 0.0])
    assert d[0] == pytest.approx(P * L**3 / (3 * E * I) + P * L / (G * As), rel=1e-13)


def _run(model_from, text, name):
    return modes(model_from(text, name))


def test_fv5_deep_beam_timoshenko_within_half_a_percent(model_from):
    # NAFEMS FV5 (square 2 m x 2 m, L = 10 m, pinned ends): 42.65 and 148.15 Hz published;
    # Cowper's shear coefficient of a rectangle, 32 elements (discretisation 4e-4 on the
    # second frequency, see the convergence test)
    text, exact = timoshenko_simply_supported(elements=32)
    f = matched(_run(model_from, text, "fv5.yaml").omega, exact["omega"][:2]) / (2 * np.pi)
    err = f / exact["published_hz"] - 1
    assert np.all(np.abs(err) < 5e-3), err
    assert np.all(np.abs(err) < 5e-4)         # measured: -8.4e-5 and +4.1e-4


def test_fv5_euler_bernoulli_limit_overestimates_as_known(model_from):
    # without shear areas the members are Euler-Bernoulli: +6.3 % and +22 % on FV5
    text, exact = timoshenko_simply_supported(elements=32, shear=False)
    w = matched(_run(model_from, text, "fv5eb.yaml").omega, exact["omega_euler_bernoulli"][:2])
    assert w == pytest.approx(exact["omega_euler_bernoulli"][:2], rel=2e-6)  # h^4, 32 el.
    over = w / (2 * np.pi) / exact["published_hz"] - 1
    assert over == pytest.approx([0.063, 0.224], abs=1.5e-3)


def test_simply_supported_timoshenko_beam_converges_at_order_two(model_from):
    # the element's shear force is constant (static shape functions), so the shear
    # energy converges at O(h) in the energy norm and the frequencies at O(h^2), from
    # above (consistent mass); the Euler-Bernoulli limit has O(h^4)
    Ns = [4, 8, 16, 32]
    err = []
    for N in Ns:
        text, exact = timoshenko_simply_supported(elements=N)
        w = matched(_run(model_from, text, f"ss{N}.yaml").omega, exact["omega"])
        err.append(w / exact["omega"] - 1)
    err = np.array(err)
    assert np.all(err > 0)
    for mode in range(3):
        slope = -np.polyfit(np.log(Ns[1:]), np.log(err[1:, mode]), 1)[0]
        assert slope == pytest.approx(2.0, abs=0.05), (mode, slope)
    assert err[-1, 0] < 4e-5


@pytest.mark.parametrize("keys, message", [
    ("Asy: 0.01, Asz: 0.01, shear_coefficient: 0.8", "not both"),
    ("Asz: 0.01", "needs the shear modulus 'G'"),
    ("G: 8e10, Asz: -1", "Asz"),
])
def test_bad_shear_areas_name_the_entry(model_from, keys, message):
    from cranefe.errors import ModelError
    text = f"""
    cranefe: 1
    plane: xz
    nodes: {{O: [0, 0, 0], T: [10, 0, 0]}}
    ground: [O]
    members:
      b: {{type: beam, nodes: [O, T], E: 2e11, A: 0.01, Iy: 2e-4, {keys}}}
    effects: {{structure: flexible}}
    """
    with pytest.raises(ModelError, match=message) as info:
        model_from(text)
    assert "members.b" in str(info.value)


# ------------------------------------------------- rotary inertia of a point mass on a beam

def test_cantilever_with_tip_mass_and_rotary_inertia_is_the_closed_form(model_from):
    # J = 2e4 kg m^2 lowers the first two frequencies by 16 % and 72 % (8.683 vs 10.31,
    # 32.41 vs 117.7 rad/s): ignoring it cannot pass. Cubic elements: O(h^4) on modes 2, 3;
    # mode 1 reaches the eigensolver's floor of this graded problem (~5e-9) by 16 elements
    from cranefe.cases import cantilever_tip_mass
    Ns = [2, 4, 8, 16]
    err = []
    for N in Ns:
        text, exact = cantilever_tip_mass(elements=N)
        w = matched(_run(model_from, text, f"tip{N}.yaml").omega, exact["omega"])
        err.append(w / exact["omega"] - 1)
    err = np.array(err)
    assert np.all(err > 0)                                  # consistent mass: from above
    assert abs(err[-1, 0]) < 1e-8
    for mode in (1, 2):
        slope = -np.polyfit(np.log(Ns[1:]), np.log(err[1:, mode]), 1)[0]
        assert slope == pytest.approx(4.0, abs=0.1), (mode, slope)
    _, no_j = cantilever_tip_mass(J=0.0)
    assert exact["omega"][:2] / no_j["omega"][:2] == pytest.approx([0.842, 0.275], abs=1e-3)


def test_check_warns_of_rotary_inertia_only_where_nothing_rotates(tmp_path, capsys):
    import json

    from cranefe.cases import cantilever_tip_mass
    from cranefe.cli import main
    beam, _ = cantilever_tip_mass(elements=2)
    rope = """cranefe: 1
plane: xz
nodes: {S: [0, 0, 10], T: [0, 0, 0]}
ground: [S]
masses: {T: {mass: 1000, inertia: 2.0e4}}
ropes:
  r: {EA: 1.0e8, path: [S, T]}
"""
    for name, text, warned in (("beam", beam, False), ("rope", rope, True)):
        path = tmp_path / f"tip_{name}.yaml"
        path.write_text(text)
        assert main(["check", str(path), "--json"]) == 0
        warnings = json.loads(capsys.readouterr().out)["warnings"]
        assert any("rotary inertia" in w for w in warnings) == warned, warnings


# ------------------------------------------------------------------------------ supports

def test_fv2_double_cross_with_pinned_supports(model_from):
    # 16 elements per arm: O(h^4) discretisation error below 3e-5 of the exact family
    from cranefe.cases import nafems_fv2
    text, exact = nafems_fv2(elements=16)
    w = _run(model_from, text, "fv2.yaml").omega[:16]
    moves = np.zeros(16, dtype=bool)
    moves[exact["centre_translates"]] = True
    err = w / exact["omega"] - 1
    assert np.all(np.abs(err[~moves]) < 3e-5), err      # measured <= 2.6e-5
    published = w / (2 * np.pi) / exact["published_hz"] - 1
    assert np.all(np.abs(published[~moves]) < 5e-5)     # 5 digits published
    # where the centre translates (axially flexible arms carry their axial inertia with
    # it) the pairs are lower: -1.6e-3 and -5.5e-3 at 17.709 and 57.390 Hz
    assert err[moves] == pytest.approx([-1.62e-3, -1.62e-3, -5.49e-3, -5.49e-3], abs=1e-4)
    # with arms 1000 times stiffer axially (same rho A, E I) the centre stays put; 8
    # elements (their discretisation error is below 4.2e-4, the shift 1.6e-3 and 5.5e-3)
    text, _ = nafems_fv2(elements=8, axial_factor=1000.0)
    w = _run(model_from, text, "fv2_stiff.yaml").omega[:16]
    assert np.all(np.abs(w / exact["omega"] - 1) < 5e-4)


def _fv5_3d(e_x, e_y, elements=16, shear=True, axes=True):
    """NAFEMS FV5 in 3D along the unit vector e_x (local y along e_y): end A restrained in
    ux, uy, uz, rx and end B in uy, uz, in the beam's axes (given `axes` when skew)."""
    E, nu, rho, L, h = 200.0e9, 0.3, 8000.0, 10.0, 2.0
    G = E / (2 * (1 + nu))
    k = 10 * (1 + nu) / (12 + 11 * nu)
    e_x, e_y = np.asarray(e_x, float), np.asarray(e_y, float)
    e_z = np.cross(e_x, e_y)
    ax = f"axes: {[list(map(float, v)) for v in (e_x, e_y, e_z)]}" if axes else ""
    B = list(map(float, L * e_x))
    shear_key = f", shear_coefficient: {k!r}" if shear else ""
    return f"""
    cranefe: 1
    gravity: [0, 0, 0]
    nodes: {{A: [0, 0, 0], B: {B}}}
    supports:
      A: {{fix: [ux, uy, uz, rx], {ax}}}
      B: {{fix: [uy, uz], {ax}}}
    members:
      beam: {{type: beam, nodes: [A, B], E: {E!r}, G: {G!r}, A: {h * h!r},
             Iy: {h**4 / 12!r}, Iz: {h**4 / 12!r}, J: {0.1406 * h**4!r}, rho: {rho!r},
             orientation: {list(map(float, e_z))}, elements: {elements}{shear_key}}}
    effects: {{structure: flexible}}
    """


def test_fv5_in_3d_with_per_direction_supports(model_from):
    from cranefe.cases import timoshenko_simply_supported
    _, exact = timoshenko_simply_supported()
    E, nu, rho, L, h = 200.0e9, 0.3, 8000.0, 10.0, 2.0
    G = E / (2 * (1 + nu))
    w = _run(model_from, _fv5_3d([1, 0, 0], [0, 1, 0], elements=32), "fv5_3d.yaml").omega
    # the flexural family in both planes (pairs), torsion and extension fixed-free
    torsion = np.pi / (2 * L) * np.sqrt(G * 0.1406 * h**4 / (rho * h**4 / 6))
    extension = np.pi / (2 * L) * np.sqrt(E / rho)                   # 125 Hz
    expect = np.sort(np.r_[np.repeat(exact["omega"][:2], 2), torsion, extension])
    got = w[:6]
    assert got == pytest.approx(expect, rel=5e-4)        # Timoshenko discretisation, 32 el.
    assert extension / (2 * np.pi) == pytest.approx(125.0, rel=1e-12)
    # the same beam along a skew direction, restrained in its own axes: the same modes
    ex = np.array([1.0, 2.0, 2.0]) / 3
    ey = np.array([2.0, 1.0, -2.0]) / 3
    skew = _run(model_from, _fv5_3d(ex, ey, elements=32), "fv5_skew.yaml").omega
    assert skew[:8] == pytest.approx(w[:8], rel=1e-9)    # round-off of the rotation


def test_supports_in_global_axes_and_pinned_shorthand(model_from):
    # an Euler-Bernoulli beam along x with supports in global axes, fixed and pinned,
    # in both planes
    E, A, I, rho, L = 2.1e11, 1.0e-2, 2.0e-4, 7850.0, 10.0
    text = f"""
    cranefe: 1
    gravity: [0, 0, 0]
    nodes: {{A: [0, 0, 0], B: [{L}, 0, 0]}}
    supports: {{A: fixed, B: pinned}}
    members:
      b: {{type: beam, nodes: [A, B], E: {E}, G: 8.1e10, A: {A}, Iy: {I}, Iz: {I},
          J: 1.0e-4, rho: {rho}, orientation: [0, 0, 1], elements: 16}}
    effects: {{structure: flexible}}
    """
    w = _run(model_from, text, "pp.yaml").omega
    # A fixed, B pinned: a propped cantilever, beta L = 3.9266, 7.0686 (tan = tanh)
    import scipy.optimize as so
    bl = np.array([so.brentq(lambda b: np.tan(b) - np.tanh(b), k * np.pi + 0.1,
                             k * np.pi + 1.5, xtol=1e-15) for k in (1, 2)])
    exact = bl**2 / L**2 * np.sqrt(E * I / (rho * A))
    # cubic elements, 16: O(h^4) discretisation, measured +2.5e-6 and +2.6e-5
    assert matched(w, exact) / exact - 1 == pytest.approx([2.5e-6, 2.6e-5], rel=0.05)
    assert np.sum(np.abs(w / exact[0] - 1) < 1e-5) == 2     # in both planes


@pytest.mark.parametrize("entry, message", [
    ("O: pinned", "is in ground"),
    ("T: [ux, ux]", "at most once"),
    ("T: [uw]", "at most once"),
    ("T: hinged", "'pinned' or 'fixed'"),
    ("T: {fix: [ux], axes: [[1, 0, 0], [1, 1, 0], [0, 0, 1]]}", "orthogonal"),
    ("X: pinned", "unknown node"),
])
def test_bad_supports_name_the_entry(model_from, entry, message):
    from cranefe.errors import ModelError
    text = f"""
    cranefe: 1
    nodes: {{O: [0, 0, 0], T: [10, 0, 0]}}
    ground: [O]
    supports: {{{entry}}}
    """
    with pytest.raises(ModelError, match=message) as info:
        model_from(text)
    assert "supports." in str(info.value)


# ------------------------------------------------------------------ member-end releases

def test_release_condenses_to_the_pinned_fixed_element():
    # one element released in rz at its second end: the x-y bending block is the classic
    # fixed-pinned element 3EI/l^3 [[1, l, -1, 0], [l, l^2, -l, 0], [-1, -l, 1, 0], 0]
    from cranefe.elements import release_transforms, transform
    E, I, l = 2.0e11, 3.0e-4, 2.5
    k = beam_stiffness(*(np.array([x]) for x in (E, 8e10, 0.01, I, I, 1e-4, l)))
    released = np.zeros((1, 12), dtype=bool)
    released[0, 11] = True
    ks = transform(k, release_transforms(k, released))[0]
    xy = [1, 5, 7, 11]
    ref = 3 * E * I / l**3 * np.array([[1, l, -1, 0], [l, l**2, -l, 0], [-1, -l, 1, 0],
                                       [0, 0, 0, 0]])
    assert ks[np.ix_(xy, xy)] == pytest.approx(ref, rel=1e-12, abs=1e-12 * ref.max())
    # the x-z plane, axial and torsion blocks are untouched
    rest = [0, 2, 3, 4, 6, 8, 9, 10]
    assert np.allclose(ks[np.ix_(rest, rest)], k[0][np.ix_(rest, rest)], rtol=1e-13, atol=0)


def _propped(model_from, how, N=8):
    E, A, I, rho, L = 2.1e11, 1.0e-2, 2.0e-4, 7850.0, 10.0
    ends = {"release": "ground: [O, T]",
            "support": "ground: [O]\n    supports: {T: pinned}"}[how]
    rel = ", releases: {T: [ry]}" if how == "release" else ""
    text = f"""
    cranefe: 1
    plane: xz
    gravity: [0, 0, 0]
    nodes: {{O: [0, 0, 0], T: [{L}, 0, 0]}}
    {ends}
    members:
      b: {{type: beam, nodes: [O, T], E: {E}, A: {A}, Iy: {I}, rho: {rho}, elements: {N}{rel}}}
    effects: {{structure: flexible}}
    """
    return _run(model_from, text, f"{how}{N}.yaml").omega


def test_propped_cantilever_by_a_released_end_is_the_closed_form(model_from):
    # clamped at O, pinned at T: beta L = 3.9266, 7.0686 (tan bL = tanh bL). The end
    # element, released at T, is the condensed (fixed-pinned) element with the mass of the
    # same displacement field: not the same mesh as a pinned node with its own rotation,
    # but converging to the same beam at O(h^4), from above
    import scipy.optimize as so
    E, A, I, rho, L = 2.1e11, 1.0e-2, 2.0e-4, 7850.0, 10.0
    bl = np.array([so.brentq(lambda b: np.tan(b) - np.tanh(b), k * np.pi + 0.1,
                             k * np.pi + 1.5, xtol=1e-15) for k in (1, 2)])
    exact = bl**2 / L**2 * np.sqrt(E * I / (rho * A))
    Ns = [2, 4, 8, 16]
    err = np.array([_propped(model_from, "release", N)[:2] / exact - 1 for N in Ns])
    assert np.all(err > 0)
    slope = -np.polyfit(np.log(Ns[1:]), np.log(err[1:, 1]), 1)[0]
    assert slope == pytest.approx(4.0, abs=0.15)
    assert err[-1, 0] < 5e-6
    # the pinned support with the node's rotation free: the same beam, a finer mesh error
    sup = _propped(model_from, "support", 16)[:2] / exact - 1
    assert np.all(sup > 0) and np.all(sup < 3e-5)


@pytest.mark.parametrize("rel, message", [
    ("{X: [ry]}", "not a node of this member"),
    ("{T: [rq]}", "at most once"),
    ("{O: [rx], T: [rx]}", "free to twist"),
])
def test_bad_releases_name_the_entry(model_from, rel, message):
    from cranefe.errors import ModelError
    text = f"""
    cranefe: 1
    nodes: {{O: [0, 0, 0], T: [10, 0, 0], X: [5, 5, 0]}}
    ground: [O]
    members:
      b: {{type: beam, nodes: [O, T], E: 2e11, G: 8e10, A: 0.01, Iy: 2e-4, Iz: 2e-4,
          J: 1e-4, orientation: [0, 0, 1], releases: {rel}}}
    """
    with pytest.raises(ModelError, match=message) as info:
        model_from(text)
    assert "members.b.releases" in str(info.value)


# ------------------------------------------------------------ buckling under self-weight

def test_geometric_stiffness_of_a_linearly_varying_axial_force_is_its_integral():
    from cranefe.elements import beam_geometric
    N1, N2, l = -3.0e5, 1.0e5, 1.7
    kg = beam_geometric(np.array([(N1 + N2) / 2]), np.array([l]), np.array([N2 - N1]))[0]
    xg, wg = np.polynomial.legendre.leggauss(6)
    ref = np.zeros((4, 4))
    for xi, w in zip((xg + 1) / 2, wg / 2):
        _, dv, _, _ = _timoshenko_shapes(xi, l, 0.0)       # phi = 0: Hermite cubics
        ref += w * l * (N1 * (1 - xi) + N2 * xi) * np.outer(dv, dv)
    xy = [1, 5, 7, 11]
    assert kg[np.ix_(xy, xy)] == pytest.approx(ref, rel=1e-13, abs=1e-13 * abs(ref).max())


def test_column_buckles_under_its_own_weight_at_greenhill(model_from):
    # (q L^3 / EI)_cr = 7.8373 (first zero of J_-1/3); the static axial force varies
    # linearly along every element (consistent self-weight), the cubic elements converge
    # at O(h^4) from above: 8 elements give 1.3e-5
    from cranefe.analysis.buckling import gravity_buckling
    from cranefe.cases import self_weight_column
    Ns = [2, 4, 8, 16]
    err = []
    for N in Ns:
        text, exact = self_weight_column(elements=N)
        err.append(gravity_buckling(model_from(text, f"sw{N}.yaml")).factor
                   / exact["factor"] - 1)
    err = np.array(err)
    assert exact["critical"] == pytest.approx(7.837, abs=5e-4)
    assert np.all(err > 0)
    assert err[2] < 1e-4
    slope = -np.polyfit(np.log(Ns[1:]), np.log(err[1:]), 1)[0]
    assert slope == pytest.approx(4.0, abs=0.15)


def test_modes_see_the_self_weight_buckling_load(model_from):
    # the first frequency of the column at 0.99 and 0.999 of its critical weight (16
    # elements, critical 8.4e-7 above Greenhill's): w^2 falls linearly to zero at the
    # critical weight (to 9e-6 from the curvature of w^2 over that step)
    from cranefe.cases import self_weight_column
    crit = self_weight_column()[1]["critical"]
    w2 = []
    for f in (0.99, 0.999):
        text, _ = self_weight_column(parameter=crit * f)
        w2.append(_run(model_from, text, f"near{f}.yaml").omega[0] ** 2)
    zero = 0.99 + 0.009 * w2[0] / (w2[0] - w2[1])
    assert zero == pytest.approx(1.0, abs=3e-5)


# ----------------------------------------------------------------- sections from shapes

def _polygon_moments(outline):
    """A, Iy (about the centroidal axis parallel to the outline's first coordinate, i.e.
    of the second coordinate z: int z^2) and Iz (int y^2) of a polygon (y, z) by Green's
    theorem, independently of the section formulas."""
    y, z = np.asarray(outline, float).T
    y1, z1 = np.roll(y, -1), np.roll(z, -1)
    c = y * z1 - y1 * z
    A = c.sum() / 2
    cy = ((y + y1) * c).sum() / (6 * A)
    cz = ((z + z1) * c).sum() / (6 * A)
    Iyy = ((z**2 + z * z1 + z1**2) * c).sum() / 12 - A * cz**2
    Izz = ((y**2 + y * y1 + y1**2) * c).sum() / 12 - A * cy**2
    return np.array([A, Iyy, Izz])


def _i_outline(b, h, tw, tf, channel=False):
    """Outline (y, z) counter-clockwise of an I (web centred) or a channel (web at y=0)."""
    w0, w1 = (0.0, tw) if channel else ((b - tw) / 2, (b + tw) / 2)
    return [(0, 0), (b, 0), (b, tf), (w1, tf), (w1, h - tf), (b, h - tf), (b, h), (0, h),
            (0, h - tf), (w0, h - tf), (w0, tf), (0, tf)] if not channel else \
        [(0, 0), (b, 0), (b, tf), (tw, tf), (tw, h - tf), (b, h - tf), (b, h), (0, h)]


def test_section_areas_and_second_moments_are_those_of_their_outlines():
    from cranefe.model.sections import section_properties
    b, h, tw, tf, t = 0.15, 0.30, 0.0071, 0.0107, 0.008
    cases = {
        ("i", (b, h, tw, tf)): _polygon_moments(_i_outline(b, h, tw, tf)),
        ("channel", (0.09, h, tw, tf)): _polygon_moments(_i_outline(0.09, h, tw, tf, True)),
        ("box", (b, h, t)): _polygon_moments([(0, 0), (b, 0), (b, h), (0, h)])
        - _polygon_moments([(t, t), (b - t, t), (b - t, h - t), (t, h - t)]),
    }
    for (shape, dims), ref in cases.items():
        names = {"i": ("b", "h", "tw", "tf"), "channel": ("b", "h", "tw", "tf"),
                 "box": ("b", "h", "t")}[shape]
        got = section_properties(shape, dict(zip(names, dims)), 0.3)[:3]
        assert got == pytest.approx(ref, rel=1e-12), shape


def test_sections_against_handbook_values():
    from cranefe.model.sections import section_properties
    # EN 10210-2 CHS 168.3 x 10: A = 49.7 cm^2, I = 1564 cm^4, It = 3128 cm^4 (tables
    # give 3-4 digits)
    A, Iy, Iz, J, Asy, _ = section_properties("tube", {"D": 0.1683, "t": 0.010}, 0.3)
    assert [A * 1e4, Iy * 1e8, Iz * 1e8, J * 1e8] == pytest.approx([49.7, 1564, 1564, 3128],
                                                                   rel=1.5e-3)
    # a thin tube's shear coefficient tends to Cowper's 2 (1 + nu) / (4 + 3 nu)
    *_, As, _ = section_properties("tube", {"D": 1.0, "t": 1e-5}, 0.3)
    assert As / (np.pi * 1e-5) == pytest.approx(2 * 1.3 / 4.9, rel=1e-4)
    # solid rectangle a x c: J = beta a c^3 with beta = 0.141, 0.229, 0.312 for a/c = 1,
    # 2, 10 (Timoshenko & Goodier, Theory of Elasticity, sec. 109, table; 3 digits)
    for ratio, beta in ((1, 0.141), (2, 0.229), (10, 0.312)):
        J = section_properties("rectangle", {"b": 1.0, "h": float(ratio)}, 0.3)[3]
        assert J / ratio == pytest.approx(beta, abs=1e-3)
    # a thin square box: Bredt's J = 4 A_m^2 t / s -> a^3 t for mid-line side a
    J = section_properties("box", {"b": 1.0, "h": 1.0, "t": 1e-4}, 0.3)[3]
    assert J == pytest.approx((1 - 1e-4) ** 3 * 1e-4, rel=1e-12)


def test_a_member_section_is_its_properties(model_from):
    # FV5 with its section given as a rectangle with timoshenko: true equals the member
    # with Cowper's shear coefficient given by hand (the same numbers, to round-off)
    text, exact = timoshenko_simply_supported(elements=8)
    by_hand = _run(model_from, text, "hand.yaml").omega
    import re
    shaped = re.sub(r"A: [^,]+, Iy: [^,]+,", "section: {shape: rectangle, b: 2.0, h: 2.0, "
                    "timoshenko: true},", text).replace(
        f", shear_coefficient: {10 * 1.3 / (12 + 11 * 0.3)!r}", "")
    assert "section" in shaped and "shear_coefficient" not in shaped
    assert _run(model_from, shaped, "shaped.yaml").omega == pytest.approx(by_hand, rel=1e-12)


@pytest.mark.parametrize("section, extra, message", [
    ("{shape: tube, D: 0.2, t: 0.1}", "", "twice the thickness t"),
    ("{shape: zed, b: 0.1}", "", "not one of"),
    ("{shape: tube, D: 0.2}", "", "'t'"),
    ("{shape: tube, D: 0.2, t: 0.01}", "A: 0.01, ", "not both"),
])
def test_bad_sections_name_the_entry(model_from, section, extra, message):
    from cranefe.errors import ModelError
    text = f"""
    cranefe: 1
    plane: xz
    nodes: {{O: [0, 0, 0], T: [10, 0, 0]}}
    ground: [O]
    members:
      b: {{type: beam, nodes: [O, T], E: 2e11, {extra}section: {section}}}
    """
    with pytest.raises(ModelError, match=message) as info:
        model_from(text)
    assert "members.b" in str(info.value)


# ------------------------------------------------------ member end forces in the static state

@pytest.mark.parametrize("case", ["cantilever", "propped", "column"])
def test_member_end_forces_under_self_weight_are_exact(tmp_path, capsys, case):
    # cubic elements with consistent loads give the exact end forces of a uniformly
    # loaded beam (q = rho A g): cantilever V = qL, M = qL^2/2 at the clamp; propped
    # cantilever (a released end on the ground) M = qL^2/8 at the clamp, V = 5qL/8 and
    # 3qL/8; a column N = -qL at its foot. Round-off only: 1e-9 of qL (of qL^2)
    import json
    import textwrap

    from cranefe.cli import main
    L, rho, A = 10.0, 7850.0, 0.01
    q = rho * A * 9.81
    geometry = {"cantilever": ("[10, 0, 0]", "ground: [O]", ""),
                "propped": ("[10, 0, 0]", "ground: [O, T]", ", releases: {T: [ry]}"),
                "column": ("[0, 0, 10]", "ground: [O]", "")}[case]
    text = f"""
    cranefe: 1
    plane: xz
    nodes: {{O: [0, 0, 0], T: {geometry[0]}}}
    {geometry[1]}
    members:
      b: {{type: beam, nodes: [O, T], E: 2.1e11, A: {A}, Iy: 2.0e-4, rho: {rho},
          elements: 4{geometry[2]}}}
    effects: {{structure: flexible}}
    """
    path = tmp_path / f"{case}.yaml"
    path.write_text(textwrap.dedent(text))
    assert main(["check", str(path), "--json"]) == 0
    (f,) = json.loads(capsys.readouterr().out)["member_forces"]
    s, e = f["start"], f["end"]
    assert (f["member"], f["from"], f["to"]) == ("b", "O", "T")
    if case == "cantilever":
        got = [s["Vz"], s["My"], e["Vz"], e["My"]]
        ref = [-q * L, q * L**2 / 2, 0.0, 0.0]
    elif case == "propped":
        got = [s["Vz"], s["My"], e["Vz"], e["My"]]
        ref = [-5 * q * L / 8, q * L**2 / 8, 3 * q * L / 8, 0.0]
    else:
        got = [s["N"], e["N"], s["My"], s["Vz"]]
        ref = [-q * L, 0.0, 0.0, 0.0]
    assert got == pytest.approx(ref, abs=1e-9 * q * L**2)


def test_a_hinge_where_only_released_ends_meet(model_from):
    # two beams clamped at O and T, both released at M: the node M gets no rotation
    # (nothing would resist it). Symmetric modes: each half a cantilever of L/2
    # (beta L = 1.8751, zero moment and shear at M); antisymmetric: clamped-pinned
    # halves (beta L = 3.9266). 16 elements per half, O(h^4)
    E, A, I, rho, h = 2.1e11, 1.0e-2, 2.0e-4, 7850.0, 5.0
    text = f"""
    cranefe: 1
    plane: xz
    gravity: [0, 0, 0]
    nodes: {{O: [0, 0, 0], M: [{h}, 0, 0], T: [{2 * h}, 0, 0]}}
    ground: [O, T]
    members:
      a: {{type: beam, nodes: [O, M], E: {E}, A: {A}, Iy: {I}, rho: {rho}, elements: 16,
          releases: {{M: ry}}}}
      b: {{type: beam, nodes: [M, T], E: {E}, A: {A}, Iy: {I}, rho: {rho}, elements: 16,
          releases: {{M: [ry]}}}}
    effects: {{structure: flexible}}
    """
    from cranefe.coordinates import build_dofs
    model = model_from(text)
    labels = build_dofs(model).labels
    assert "node M ry" not in labels and "node M x" in labels
    r = modes(model)
    bl = np.array([1.875104068711961, 3.926602312047919])
    exact = bl**2 / h**2 * np.sqrt(E * I / (rho * A))
    # measured +1e-8 and +2.5e-6 (as the propped cantilever above at 16 elements)
    assert r.omega[:2] == pytest.approx(exact, rel=3e-6)


def test_mesh_members_take_sections_and_their_points_take_supports(model_from, tmp_path):
    # a simply supported tube as a mesh file of 16 line cells: its far end is the mesh's
    # own point 'beam.16', pinned by name; the same beam written as a chain of named
    # nodes gives the same frequencies
    meshio = pytest.importorskip("meshio")
    L, n = 10.0, 16
    pts = np.column_stack([np.linspace(0, L, n + 1), np.zeros(n + 1), np.zeros(n + 1)])
    cells = [("line", np.column_stack([np.arange(n), np.arange(1, n + 1)]))]
    meshio.write(tmp_path / "beam.vtu", meshio.Mesh(pts, cells))
    body = """E: 2.1e11, G: 8.1e10, rho: 7850, orientation: [0, 0, 1],
          section: {shape: tube, D: 0.1683, t: 0.01}}"""
    mesh = f"""
    cranefe: 1
    gravity: [0, 0, 0]
    nodes: {{A: [0, 0, 0]}}
    supports: {{A: [ux, uy, uz, rx], beam.16: [uy, uz]}}
    members:
      beam: {{type: beam, mesh: beam.vtu, {body}
    effects: {{structure: flexible}}
    """
    names = ", ".join(f"N{k}: [{float(x)!r}, 0, 0]" for k, x in enumerate(pts[:, 0]))
    chain = f"""
    cranefe: 1
    gravity: [0, 0, 0]
    nodes: {{{names}}}
    supports: {{N0: [ux, uy, uz, rx], N16: [uy, uz]}}
    members:
      beam: {{type: beam, nodes: [{", ".join(f"N{k}" for k in range(n + 1))}], {body}
    effects: {{structure: flexible}}
    """
    w_mesh = _run(model_from, mesh, "mesh.yaml").omega
    w_chain = _run(model_from, chain, "chain.yaml").omega
    assert w_mesh[:6] == pytest.approx(w_chain[:6], rel=1e-10)
    # pinned-pinned: w1 = (pi / L)^2 sqrt(E I / rho A) with the tube's I and A
    from cranefe.model.sections import section_properties
    A, I = section_properties("tube", {"D": 0.1683, "t": 0.01}, 0.3)[:2]
    w1 = (np.pi / L) ** 2 * np.sqrt(2.1e11 * I / (7850 * A))
    assert np.sum(np.abs(w_mesh / w1 - 1) < 1e-5) == 2          # both planes, 16 elements
