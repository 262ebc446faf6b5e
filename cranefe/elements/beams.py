"""3D truss and beam (Euler-Bernoulli or Timoshenko) kernels (local dofs u v w tx ty tz, twice).

Pure and batched: section arrays and element lengths in, (ne, 12, 12) local matrices out;
`beam_axes` and `to_global` rotate them for the current member directions.
"""

import numpy as np


def beam_axes(e, orientation):
    """Rotation matrices (ne, 3, 3) whose rows are the local x, y, z axes.

    Local x runs along the member (e); the orientation vector lies in the local x-z
    plane: z = its part normal to x, y = z cross x.
    """
    z = orientation - np.einsum("ki,ki->k", orientation, e)[:, None] * e
    z /= np.linalg.norm(z, axis=1)[:, None]
    y = np.cross(z, e)
    return np.stack([e, y, z], axis=1)


def _bending(cols, k4, out, flip):
    """Scatter 4x4 bending blocks k4 (ne, 4, 4) into out at cols (v1, r1, v2, r2).

    flip=True for bending in the local x-z plane, where the rotation about y is -dw/dx
    (the coupling terms change sign)."""
    s = np.array([1.0, -1.0, 1.0, -1.0]) if flip else np.ones(4)
    out[:, np.ix_(cols, cols)[0], np.ix_(cols, cols)[1]] += k4 * np.outer(s, s)


def _pattern4(a, b, c, d, e, f, g, h, i, j):
    """Symmetric 4x4 from its upper triangle, batched: rows (a b c d)(. e f g)(. . h i)(. . . j)."""
    return np.stack([np.stack([a, b, c, d], -1), np.stack([b, e, f, g], -1),
                     np.stack([c, f, h, i], -1), np.stack([d, g, i, j], -1)], -2)


def shear_factors(E, G, Iy, Iz, Asy, Asz, l):
    """Shear-deformation parameters (phi_y, phi_z), each (ne,), of Timoshenko beams:
    phi = 12 E I / (G As l^2) for bending in the local x-y plane (Iz, shear area Asy)
    and in the x-z plane (Iy, Asz) (Przemieniecki, eq. 5.116). A shear area of 0 means
    no shear deformation: phi = 0, the Euler-Bernoulli beam."""
    def phi(I, As):
        As = np.asarray(As, dtype=float)
        safe = np.where(As > 0, As, 1.0)
        return np.where(As > 0, 12 * E * I / (np.where(As > 0, G, 1.0) * safe * l**2), 0.0)
    return phi(Iz, Asy), phi(Iy, Asz)


def beam_stiffness(E, G, A, Iy, Iz, J, l, phi_y=None, phi_z=None):
    """Local elastic stiffness of 3D beams, (ne, 12, 12): Euler-Bernoulli, or Timoshenko
    with shear parameters phi_y, phi_z (`shear_factors`; Przemieniecki, Theory of Matrix
    Structural Analysis, eq. 5.116: EI/((1+phi) l^3) [[12, 6l, -12, 6l],
    [6l, (4+phi) l^2, -6l, (2-phi) l^2], ...] in each bending plane)."""
    ne = len(l)
    k = np.zeros((ne, 12, 12))
    ax, tor = E * A / l, G * J / l
    for (i, j), v in (((0, 0), ax), ((0, 6), -ax), ((6, 6), ax),
                      ((3, 3), tor), ((3, 9), -tor), ((9, 9), tor)):
        k[:, i, j] = v
        k[:, j, i] = v
    for I, cols, flip, phi in ((Iz, [1, 5, 7, 11], False, phi_y),
                               (Iy, [2, 4, 8, 10], True, phi_z)):
        EI = E * I
        if phi is None or not np.any(phi):
            b4 = _pattern4(12 * EI / l**3, 6 * EI / l**2, -12 * EI / l**3, 6 * EI / l**2,
                           4 * EI / l, -6 * EI / l**2, 2 * EI / l,
                           12 * EI / l**3, -6 * EI / l**2, 4 * EI / l)
        else:
            c = EI / ((1 + phi) * l**3)
            b4 = _pattern4(12 * c, 6 * l * c, -12 * c, 6 * l * c, (4 + phi) * l**2 * c,
                           -6 * l * c, (2 - phi) * l**2 * c, 12 * c, -6 * l * c,
                           (4 + phi) * l**2 * c)
        _bending(cols, b4, k, flip)
    return k


def _timoshenko_mass4(m, rI, l, phi):
    """Consistent 4x4 bending mass (v1, r1, v2, r2) of Timoshenko beams, batched:
    translational inertia m = rho A l and rotary inertia rI = rho I, both from the
    static (exact) Timoshenko shape functions (Przemieniecki, eq. 11.41 with 11.42;
    Friedman & Kosmatka, Comput. Struct. 47 (1993) 473, eq. 18-19). phi = 0 with rI = 0
    is the cubic Euler-Bernoulli mass."""
    d = (1 + phi) ** 2
    t = m / d
    m11 = t * (13 / 35 + 7 / 10 * phi + phi**2 / 3)
    m12 = t * l * (11 / 210 + 11 / 120 * phi + phi**2 / 24)
    m13 = t * (9 / 70 + 3 / 10 * phi + phi**2 / 6)
    m14 = -t * l * (13 / 420 + 3 / 40 * phi + phi**2 / 24)
    m22 = t * l**2 * (1 / 105 + phi / 60 + phi**2 / 120)
    m24 = -t * l**2 * (1 / 140 + phi / 60 + phi**2 / 120)
    r = rI / (d * l)
    r11 = r * 6 / 5
    r12 = r * l * (1 / 10 - phi / 2)
    r22 = r * l**2 * (2 / 15 + phi / 6 + phi**2 / 3)
    r24 = r * l**2 * (-1 / 30 - phi / 6 + phi**2 / 6)
    return (_pattern4(m11, m12, m13, m14, m22, -m14, m24, m11, -m12, m22)
            + _pattern4(r11, r12, -r11, r12, r22, -r12, r24, r11, -r12, r22))


def beam_mass(rho, A, Iy, Iz, l, lumped=False, phi_y=None, phi_z=None, rotary=None):
    """Local mass of beams, (ne, 12, 12): consistent (cubic bending, linear axial and
    torsion with polar inertia Iy + Iz) or lumped (half the mass at each end,
    translations only). With shear parameters (`shear_factors`) the bending mass is the
    consistent mass of the Timoshenko shape functions (`_timoshenko_mass4`), with the
    sections' rotary inertia rho I where `rotary` (ne,) is true (default: everywhere);
    phi = 0 without rotary inertia is the Euler-Bernoulli mass."""
    ne = len(l)
    m = rho * A * l
    out = np.zeros((ne, 12, 12))
    if lumped:
        for i in (0, 1, 2, 6, 7, 8):
            out[:, i, i] = m / 2
        return out
    jt = rho * (Iy + Iz) * l
    for (i, j), v in (((0, 0), m / 3), ((0, 6), m / 6), ((6, 6), m / 3),
                      ((3, 3), jt / 3), ((3, 9), jt / 6), ((9, 9), jt / 3)):
        out[:, i, j] = v
        out[:, j, i] = v
    c = m / 420
    b4 = _pattern4(156 * c, 22 * l * c, 54 * c, -13 * l * c, 4 * l**2 * c, 13 * l * c,
                   -3 * l**2 * c, 156 * c, -22 * l * c, 4 * l**2 * c)
    if phi_y is None and phi_z is None:
        _bending([1, 5, 7, 11], b4, out, False)
        _bending([2, 4, 8, 10], b4, out, True)
        return out
    rot = np.ones(ne) if rotary is None else np.asarray(rotary, dtype=float)
    for I, cols, flip, phi in ((Iz, [1, 5, 7, 11], False, phi_y),
                               (Iy, [2, 4, 8, 10], True, phi_z)):
        phi = np.zeros(ne) if phi is None else phi
        _bending(cols, _timoshenko_mass4(m, rho * I * rot, l, phi), out, flip)
    return out


def _geometric4(N, l, dN, phi):
    """4x4 geometric stiffness (v1, r1, v2, r2) of beams, batched: int N(x) v' v'^T dx
    with the element's own (static, exact) shape functions v(x) of shear parameter phi,
    N(x) = N + dN (x/l - 1/2) (dN None: constant). Derived symbolically (sympy) from the
    Timoshenko beam's equilibrium EI psi'' + kGA (v' - psi) = 0, v'' = psi' with the
    nodal rotations psi; N works on the total slope v' (so P-delta converges to Engesser's
    shear-buckling load). With d = (1 + phi)^2:
    N/(l d) [[6/5 + 2 phi + phi^2, l/10, -(..), l/10],
             [l/10, l^2 (2/15 + phi/6 + phi^2/12), -l/10, -l^2 (1/30 + phi/6 + phi^2/12)],
             ...] plus dN/d [[0, c, 0, -c], [c, -l (1+phi)/30, -c, 0], [0, -c, 0, c],
    [-c, 0, c, l (1+phi)/30]], c = 1/20 + 2 phi/15 + phi^2/12; phi = 0: the cubic
    N/(30 l) [[36, 3l, -36, 3l], ...] and dN/l [[0, l/20, 0, -l/20], ...]."""
    d = (1 + phi) ** 2
    s = N / (l * d)
    a = s * (6 / 5 + 2 * phi + phi**2)
    e = s * l**2 * (2 / 15 + phi / 6 + phi**2 / 12)
    g = -s * l**2 * (1 / 30 + phi / 6 + phi**2 / 12)
    bl = s * l / 10
    k = _pattern4(a, bl, -a, bl, e, -bl, g, a, -bl, e)
    if dN is not None:
        c = dN / d * (1 / 20 + 2 * phi / 15 + phi**2 / 12)
        r = dN * l / (30 * (1 + phi))
        z = np.zeros_like(c)
        k = k + _pattern4(z, c, z, -c, -r, -c, z, z, c, r)
    return k


def beam_geometric(N, l, dN=None, phi_y=None, phi_z=None):
    """Local geometric stiffness of beams under axial force N (tension +), (ne, 12, 12):
    int N(x) v'(x) v'(x)^T dx in each bending plane (`_geometric4`) with the element's
    shape functions: cubic (Hermite) for Euler-Bernoulli beams, those of the Timoshenko
    element for shear parameters phi_y (x-y plane), phi_z (x-z plane). N: the mean axial
    force, giving N/(30 l) [[36, 3l, -36, 3l], ...] for phi = 0; dN (or None): its change
    from the first end to the second when it varies linearly along the element (an axial
    distributed load, e.g. the element's own weight), adding dN/l [[0, l/20, 0, -l/20],
    [l/20, -l^2/30, -l/20, 0], [0, -l/20, 0, l/20], [-l/20, 0, l/20, l^2/30]] for phi = 0
    (the integral with N(x) = N + dN (x/l - 1/2))."""
    ne = len(l)
    out = np.zeros((ne, 12, 12))
    zero = np.zeros(ne)
    for cols, flip, phi in (([1, 5, 7, 11], False, phi_y), ([2, 4, 8, 10], True, phi_z)):
        _bending(cols, _geometric4(N, l, dN, zero if phi is None else phi), out, flip)
    return out


def to_global(local, axes):
    """T^T k T with T = blockdiag(axes x 4), (ne, 12, 12)."""
    T = np.zeros((len(axes), 12, 12))
    for b in range(4):
        T[:, 3 * b:3 * b + 3, 3 * b:3 * b + 3] = axes
    return np.einsum("kji,kjl,klm->kim", T, local, T)


def release_transforms(k, released):
    """Static condensation of released end dofs (a pinned end of a beam), batched.

    k : (ne, 12, 12) local stiffness; released : (ne, 12) bool, the dofs whose end force
    is zero. Returns T (ne, 12, 12) with u = T u: the released dofs follow the others,
    u_c = -k_cc^-1 k_cr u_r, and T's columns of released dofs are zero, so that
    T^T k T = k_rr - k_rc k_cc^-1 k_cr (the condensed stiffness, e.g. Przemieniecki
    section 6.6 / McGuire, Gallagher & Ziemian, Matrix Structural Analysis, eq. 7.2) and
    T^T m T, T^T k_g T are the mass and geometric stiffness of the same displacement
    field. Elements without releases get the identity.
    """
    ne = len(k)
    T = np.broadcast_to(np.eye(12), (ne, 12, 12)).copy()
    patterns, which = np.unique(released, axis=0, return_inverse=True)
    for p, mask in enumerate(patterns):
        if not mask.any():
            continue
        sel = np.flatnonzero(which.ravel() == p)
        c, r = np.flatnonzero(mask), np.flatnonzero(~mask)
        kcc = k[sel][:, c][:, :, c]
        kcr = k[sel][:, c][:, :, r]
        Tp = np.zeros((len(sel), 12, 12))
        Tp[:, r, r] = 1.0
        Tp[:, c[:, None], r[None, :]] = -np.linalg.solve(kcc, kcr)
        T[sel] = Tp
    return T


def transform(local, T):
    """T^T x T, batched (ne, 12, 12)."""
    return np.einsum("kji,kjl,klm->kim", T, local, T)
