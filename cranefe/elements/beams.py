"""3D truss and Euler-Bernoulli beam kernels (local dofs u v w tx ty tz, twice).

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


def beam_stiffness(E, G, A, Iy, Iz, J, l):
    """Local elastic stiffness of 3D Euler-Bernoulli beams, (ne, 12, 12)
    (e.g. Przemieniecki, Theory of Matrix Structural Analysis, eq. 5.116)."""
    ne = len(l)
    k = np.zeros((ne, 12, 12))
    ax, tor = E * A / l, G * J / l
    for (i, j), v in (((0, 0), ax), ((0, 6), -ax), ((6, 6), ax),
                      ((3, 3), tor), ((3, 9), -tor), ((9, 9), tor)):
        k[:, i, j] = v
        k[:, j, i] = v
    for I, cols, flip in ((Iz, [1, 5, 7, 11], False), (Iy, [2, 4, 8, 10], True)):
        EI = E * I
        b4 = _pattern4(12 * EI / l**3, 6 * EI / l**2, -12 * EI / l**3, 6 * EI / l**2,
                       4 * EI / l, -6 * EI / l**2, 2 * EI / l,
                       12 * EI / l**3, -6 * EI / l**2, 4 * EI / l)
        _bending(cols, b4, k, flip)
    return k


def beam_mass(rho, A, Iy, Iz, l, lumped=False):
    """Local mass of beams, (ne, 12, 12): consistent (cubic bending, linear axial and
    torsion with polar inertia Iy + Iz) or lumped (half the mass at each end,
    translations only)."""
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
    _bending([1, 5, 7, 11], b4, out, False)
    _bending([2, 4, 8, 10], b4, out, True)
    return out


def beam_geometric(N, l):
    """Local geometric stiffness of beams under axial force N (tension +), (ne, 12, 12):
    the consistent cubic form N/(30 l) [[36, 3l, -36, 3l], ...] in each bending plane."""
    ne = len(l)
    out = np.zeros((ne, 12, 12))
    c = N / (30 * l)
    b4 = _pattern4(36 * c, 3 * l * c, -36 * c, 3 * l * c, 4 * l**2 * c, -3 * l * c,
                   -l**2 * c, 36 * c, -3 * l * c, 4 * l**2 * c)
    _bending([1, 5, 7, 11], b4, out, False)
    _bending([2, 4, 8, 10], b4, out, True)
    return out


def to_global(local, axes):
    """T^T k T with T = blockdiag(axes x 4), (ne, 12, 12)."""
    T = np.zeros((len(axes), 12, 12))
    for b in range(4):
        T[:, 3 * b:3 * b + 3, 3 * b:3 * b + 3] = axes
    return np.einsum("kji,kjl,klm->kim", T, local, T)
