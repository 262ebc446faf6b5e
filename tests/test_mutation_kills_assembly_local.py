"""Kill tests for cranefe/assembly/beams.py's `beam_local_matrices` (issue 20, mutation
testing; tools/mutation.py assembly): the local stiffness, mass and axes of beam elements
as the member-force output uses them (`cranefe.outputs.member_forces`: K_e u_e - M_e g),
written out by hand for one element of each kind on one 3D model:

- an Euler-Bernoulli element with consistent mass (Iy != Iz, so the two bending planes
  differ): the textbook 12 x 12 matrices (McGuire, Gallagher & Ziemian, Matrix
  Structural Analysis, eq. 4.34 and the consistent mass of the cubic and linear shape
  functions, Przemieniecki eq. 11.24), entry by entry;
- a lumped element: rho A l / 2 on each end's translations, nothing else;
- a Timoshenko element (shear areas): its end-2 flexibility with end 1 clamped is the
  cantilever's l^3 / (3 EI) + l / (G As), l^2 / (2 EI), l / (EI) (beam theory, not the
  element's formula); its mass gives the rigid translation's rho A l and the rigid
  rotation's kinetic energy rho A l^3 / 3 + rho I l (the static Timoshenko shape
  functions contain the rigid modes exactly), and the end entries of Przemieniecki's
  eq. 11.41-11.42;
- an element with its second end's rotation about local y released (`releases`): its
  condensed stiffness is the propped cantilever's (3 EI / l^3, 3 EI / l; the released
  row and column zero) and its condensed mass the fixed-pinned element's 204 / 420 and
  99 / 420 of rho A l, both derived below.

The model also has a truss listed first (so the beam elements are not elements 0..3)
and the Euler-Bernoulli element beside the Timoshenko one (it must get no rotary
inertia). Tolerances: 1e-12 relative to each matrix's largest entry (round-off of a
few products and one 2 x 2 solve).
"""

import numpy as np
import pytest

from cranefe.assembly.beams import beam_local_matrices
from cranefe.coordinates import build_dofs
from cranefe.model import load

E, G = 2.0e11, 8.0e10
A, IY, IZ, J, RHO = 0.01, 2.0e-5, 5.0e-5, 3.0e-5, 7800.0
ASY, ASZ = 0.004, 0.006

MODEL = f"""cranefe: 1
nodes: {{O: [0, 0, 0], P: [2, 1, 2], Q: [2, 4, 6], R: [5, 4, 6], S: [5, 4, 2],
        T: [0, 0, 4]}}
ground: [O]
members:
  tie: {{type: truss, nodes: [T, Q], E: {E}, A: 0.001, rho: 0}}
  eb: {{type: beam, nodes: [O, P], E: {E}, G: {G}, A: {A}, Iy: {IY}, Iz: {IZ}, J: {J},
       rho: {RHO}, orientation: [0, 0, 1], elements: 1}}
  lump: {{type: beam, nodes: [P, Q], E: {E}, G: {G}, A: {A}, Iy: {IY}, Iz: {IZ}, J: {J},
         rho: {RHO}, orientation: [1, 0, 0], elements: 1, mass: lumped}}
  timo: {{type: beam, nodes: [Q, R], E: {E}, G: {G}, A: {A}, Iy: {IY}, Iz: {IZ}, J: {J},
         rho: {RHO}, Asy: {ASY}, Asz: {ASZ}, orientation: [0, 0, 1], elements: 1}}
  pin: {{type: beam, nodes: [R, S], E: {E}, G: {G}, A: {A}, Iy: {IY}, Iz: {IZ}, J: {J},
        rho: {RHO}, orientation: [1, 1, 0], elements: 1, releases: {{S: [ry]}}}}
masses: {{S: 100, T: 10}}
effects: {{structure: flexible}}
"""

ENDS = {"eb": ("O", "P"), "lump": ("P", "Q"), "timo": ("Q", "R"), "pin": ("R", "S")}
ORIENT = {"eb": [0, 0, 1], "lump": [1, 0, 0], "timo": [0, 0, 1], "pin": [1, 1, 0]}
XYZ = {"O": [0, 0, 0], "P": [2, 1, 2], "Q": [2, 4, 6], "R": [5, 4, 6], "S": [5, 4, 2],
       "T": [0, 0, 4]}


@pytest.fixture
def local(tmp_path):
    """{member name: (k, m, axes, l)} of the model's beam elements, one each. Built in
    every test (a few ms), not once per module: mutmut runs for a mutant only the tests
    during which the mutated function was called."""
    p = tmp_path / "m.yaml"
    p.write_text(MODEL)
    model = load(p)
    dofs = build_dofs(model)
    mm = dofs.members
    b = np.flatnonzero(mm.beam)
    k, m, axes = beam_local_matrices(model, dofs.layout, mm, b)
    names = [model.members[i].name for i in mm.member[b]]
    assert sorted(names) == sorted(ENDS) and len(b) == 4 and list(b) != [0, 1, 2, 3]
    out = {}
    for i, name in enumerate(names):
        a, c = (np.array(XYZ[n], float) for n in ENDS[name])
        out[name] = (k[i], m[i], axes[i], np.linalg.norm(c - a))
    return out


def _sym(n, entries):
    """Symmetric n x n from {(i, j): v} given once (upper triangle)."""
    out = np.zeros((n, n))
    for (i, j), v in entries.items():
        out[i, j] = out[j, i] = v
    return out


def _eb_stiffness(l, Iy=IY, Iz=IZ):
    """Euler-Bernoulli 3D frame element, local dofs (u, v, w, rx, ry, rz) x 2 (McGuire
    eq. 4.34): bending in x-y with Iz (v, rz), in x-z with Iy (w, ry), where ry = -w'."""
    a, t = E * A / l, G * J / l
    z1, z2, z3, z4 = 12 * E * Iz / l**3, 6 * E * Iz / l**2, 4 * E * Iz / l, 2 * E * Iz / l
    y1, y2, y3, y4 = 12 * E * Iy / l**3, 6 * E * Iy / l**2, 4 * E * Iy / l, 2 * E * Iy / l
    return _sym(12, {(0, 0): a, (0, 6): -a, (6, 6): a, (3, 3): t, (3, 9): -t, (9, 9): t,
                     (1, 1): z1, (1, 5): z2, (1, 7): -z1, (1, 11): z2, (5, 5): z3,
                     (5, 7): -z2, (5, 11): z4, (7, 7): z1, (7, 11): -z2, (11, 11): z3,
                     (2, 2): y1, (2, 4): -y2, (2, 8): -y1, (2, 10): -y2, (4, 4): y3,
                     (4, 8): y2, (4, 10): y4, (8, 8): y1, (8, 10): y2, (10, 10): y3})


def _eb_mass(l):
    """Consistent mass of the same element: axial rho A l [1/3, 1/6], torsion rho (Iy +
    Iz) l [1/3, 1/6], bending rho A l / 420 [156, 22 l, 54, -13 l; 4 l^2, 13 l, -3 l^2;
    156, -22 l; 4 l^2] (Przemieniecki eq. 11.24), the x-z plane's rotations with -."""
    m = RHO * A * l
    c = m / 420
    jt = RHO * (IY + IZ) * l
    return _sym(12, {(0, 0): m / 3, (0, 6): m / 6, (6, 6): m / 3,
                     (3, 3): jt / 3, (3, 9): jt / 6, (9, 9): jt / 3,
                     (1, 1): 156 * c, (1, 5): 22 * l * c, (1, 7): 54 * c,
                     (1, 11): -13 * l * c, (5, 5): 4 * l**2 * c, (5, 7): 13 * l * c,
                     (5, 11): -3 * l**2 * c, (7, 7): 156 * c, (7, 11): -22 * l * c,
                     (11, 11): 4 * l**2 * c,
                     (2, 2): 156 * c, (2, 4): -22 * l * c, (2, 8): 54 * c,
                     (2, 10): 13 * l * c, (4, 4): 4 * l**2 * c, (4, 8): -13 * l * c,
                     (4, 10): -3 * l**2 * c, (8, 8): 156 * c, (8, 10): 22 * l * c,
                     (10, 10): 4 * l**2 * c})


def _close(x, ref):
    assert np.allclose(x, ref, rtol=0, atol=1e-12 * np.abs(ref).max())


@pytest.mark.parametrize("name", list(ENDS))
def test_local_axes(local, name):
    """Rows x, y, z: x along the element, z the orientation's part normal to x, y = z x
    x (docs/model-format.md, `orientation`)."""
    a, c = (np.array(XYZ[n], float) for n in ENDS[name])
    x = (c - a) / np.linalg.norm(c - a)
    z = np.array(ORIENT[name], float)
    z = z - (z @ x) * x
    z /= np.linalg.norm(z)
    assert np.allclose(local[name][2], [x, np.cross(z, x), z], rtol=0, atol=1e-15)


def test_euler_bernoulli_element_with_consistent_mass(local):
    k, m, _, l = local["eb"]
    assert l == 3.0
    _close(k, _eb_stiffness(l))
    _close(m, _eb_mass(l))          # no rotary inertia beside a Timoshenko member


def test_lumped_element(local):
    k, m, _, l = local["lump"]
    _close(k, _eb_stiffness(l))
    ref = np.zeros((12, 12))
    ref[[0, 1, 2, 6, 7, 8], [0, 1, 2, 6, 7, 8]] = RHO * A * l / 2
    _close(m, ref)


def test_timoshenko_element(local):
    k, m, _, l = local["timo"]
    assert l == 3.0
    # axial and torsion as Euler-Bernoulli
    for i, j, v in ((0, 0, E * A / l), (0, 6, -E * A / l), (3, 3, G * J / l),
                    (3, 9, -G * J / l)):
        assert k[i, j] == pytest.approx(v, rel=1e-13)
    # end 2's flexibility, end 1 clamped: the cantilever under an end force P and moment
    # M, w = P l^3 / (3 EI) + P l / (G As) + M l^2 / (2 EI), theta = P l^2 / (2 EI) + M l
    # / EI (shear adds only to the deflection); in x-z the rotation is -w', hence the sign
    for I, As, dofs, s in ((IZ, ASY, [7, 11], 1.0), (IY, ASZ, [8, 10], -1.0)):
        flex = np.linalg.inv(k[np.ix_(dofs, dofs)])
        EI = E * I
        ref = np.array([[l**3 / (3 * EI) + l / (G * As), s * l**2 / (2 * EI)],
                        [s * l**2 / (2 * EI), l / EI]])
        assert np.allclose(flex, ref, rtol=1e-12, atol=0)
    # mass: the rigid translation carries rho A l, a rigid rotation about end 1
    # (w = x theta, the section turning with it) rho A l^3 / 3 + rho I l
    for I, dofs, s in ((IZ, [1, 5, 7, 11], 1.0), (IY, [2, 4, 8, 10], -1.0)):
        mb = m[np.ix_(dofs, dofs)]
        tr = np.array([1.0, 0, 1, 0])
        rot = np.array([0.0, s, l, s])
        assert tr @ mb @ tr == pytest.approx(RHO * A * l, rel=1e-13)
        assert rot @ mb @ rot == pytest.approx(RHO * A * l**3 / 3 + RHO * I * l, rel=1e-13)
        # Przemieniecki eq. 11.41 + 11.42 (translational + rotary inertia), phi = 12 E I /
        # (G As l^2): m11 = rho A l (13/35 + 7/10 phi + phi^2/3) / (1 + phi)^2 + rho I
        # 6 / (5 l (1 + phi)^2), m22 = rho A l^3 (1/105 + phi/60 + phi^2/120) / (1+phi)^2
        # + rho I l (2/15 + phi/6 + phi^2/3) / (1 + phi)^2
        As = ASY if I == IZ else ASZ
        phi = 12 * E * I / (G * As * l**2)
        d = (1 + phi) ** 2
        m11 = (RHO * A * l * (13 / 35 + 7 / 10 * phi + phi**2 / 3)
               + RHO * I * 6 / (5 * l)) / d
        m22 = (RHO * A * l**3 * (1 / 105 + phi / 60 + phi**2 / 120)
               + RHO * I * l * (2 / 15 + phi / 6 + phi**2 / 3)) / d
        assert mb[0, 0] == pytest.approx(m11, rel=1e-13)
        assert mb[1, 1] == pytest.approx(m22, rel=1e-13)
    assert m[0, 0] == pytest.approx(RHO * A * l / 3, rel=1e-13)
    assert m[3, 3] == pytest.approx(RHO * (IY + IZ) * l / 3, rel=1e-13)


def test_released_end_condenses_stiffness_and_mass(local):
    """ry at the element's end 2 free: with end 1 clamped in the x-z plane the end
    rotation follows from k's row 10 = 0: theta2 = -(6 l w1 + 2 l^2 theta1 - 6 l w2) /
    (4 l^2) (signs of the x-z plane cancel in the products below), so the condensed
    stiffness is the propped cantilever's: k_ww(end 1) = (12 - 36/4) EI / l^3 = 3 EI /
    l^3, k_theta1 = (4 - 4/4) EI / l = 3 EI / l; the mass: m(w1, w1) = (156 + 2 * 13 *
    3/2 + 4 * 9/4) rho A l / 420 = 204 / 420 rho A l, m(w2, w2) = (156 - 2 * 22 * 3/2 +
    9) / 420 = 99 / 420 rho A l. The x-y plane (rz kept) is unchanged."""
    k, m, _, l = local["pin"]
    assert l == 4.0
    EI = E * IY
    assert np.all(k[10] == 0) and np.all(k[:, 10] == 0)
    assert np.all(m[10] == 0) and np.all(m[:, 10] == 0)
    assert k[2, 2] == pytest.approx(3 * EI / l**3, rel=1e-12)
    assert k[4, 4] == pytest.approx(3 * EI / l, rel=1e-12)
    assert abs(k[2, 4]) == pytest.approx(3 * EI / l**2, rel=1e-12)
    assert m[2, 2] == pytest.approx(204 / 420 * RHO * A * l, rel=1e-12)
    assert m[8, 8] == pytest.approx(99 / 420 * RHO * A * l, rel=1e-12)
    kr, mr = _eb_stiffness(l), _eb_mass(l)
    xy = [0, 1, 3, 5, 6, 7, 9, 11]
    _close(k[np.ix_(xy, xy)], kr[np.ix_(xy, xy)])
    _close(m[np.ix_(xy, xy)], mr[np.ix_(xy, xy)])
