"""Pure, batched element kernels: geometry and element data in, local rows/blocks out.

No global state, no I/O. Degrees of freedom are *primitive* indices (see
`cranefe.coordinates.dofmap.Layout`): three translations per node, six per body (at its centre of
mass), one rotation per drum. Assembly (`cranefe.assembly.assemble`) maps them to the
generalised coordinates with one sparse transform.
"""

import numpy as np


def skew(c):
    """Cross-product matrices: skew(c) @ v == cross(c, v). c: (..., 3) -> (..., 3, 3)."""
    c = np.asarray(c, dtype=float)
    z = np.zeros(c.shape[:-1])
    return np.stack([np.stack([z, -c[..., 2], c[..., 1]], -1),
                     np.stack([c[..., 2], z, -c[..., 0]], -1),
                     np.stack([-c[..., 1], c[..., 0], z], -1)], -2)


def span_geometry(coords, a, b):
    """Unit vectors e (ns, 3) from node a to node b and lengths l (ns,)."""
    d = coords[b] - coords[a]
    l = np.linalg.norm(d, axis=1)
    return d / l[:, None], l


def elongation_rows(e, falls, dof_a, dof_b):
    """Linearised elongation of spans: dL = f e.(u_b - u_a) (Heletiy 2016, eq. 2-3).

    e : (ns, 3); falls : (ns,); dof_a, dof_b : (ns, 3) primitive translation indices.
    Returns (cols (ns, 6), vals (ns, 6)): one row of coefficients per span.
    """
    fe = falls[:, None] * e
    return np.hstack([dof_a, dof_b]), np.hstack([-fe, fe])


def string_stiffness(N, falls, e, l):
    """Tension (geometric) stiffness of straight spans, (ns, 6, 6).

    A span with axial force N (tension positive) and f parallel falls, second variation of
    N * (elongation) for end translations u_a, u_b:  (f N / l) (I - e e^T) [[1, -1], [-1, 1]].
    """
    g = (falls * N / l)[:, None, None] * (np.eye(3) - e[:, :, None] * e[:, None, :])
    return np.block([[g, -g], [-g, g]])


def load_stiffness(F, c):
    """Second variation of the work of constant forces on a rotating rigid body, (k, 3, 3).

    A point at offset c from the body's reference point moves, to second order in the
    rotation vector t, by t x c + 1/2 t x (t x c); the potential -F.x of a constant force F
    then contributes t^T H t / 2 with  H = (F.c) I - (F c^T + c F^T) / 2  (docs/theory.md,
    "gravity and load stiffness"). Summed over all forces on a body in equilibrium it does
    not depend on the reference point.
    """
    Fc = np.einsum("ki,ki->k", F, c)
    outer = F[:, :, None] * c[:, None, :]
    return Fc[:, None, None] * np.eye(3) - 0.5 * (outer + outer.transpose(0, 2, 1))


def rigid_mass(mass, inertia):
    """Rigid-body mass at the centre of mass, (nb, 6, 6): diag(m I, I_c)."""
    out = np.zeros((len(mass), 6, 6))
    out[:, :3, :3] = mass[:, None, None] * np.eye(3)
    out[:, 3:, 3:] = inertia
    return out


def rope_mass(mu, length, lumped=False):
    """Mass of two-node rope elements on [u_start; u_end] (3 + 3 translations), (ne, 6, 6).

    Consistent (linear shape functions): mu l / 6 [[2 I, I], [I, 2 I]];
    lumped: mu l / 2 at each end.
    """
    m = (mu * length)[:, None, None]
    if lumped:
        return m / 2 * np.eye(6)
    return m / 6 * np.kron(np.array([[2.0, 1.0], [1.0, 2.0]]), np.eye(3))


# --- members: 3D truss and Euler-Bernoulli beam (local dofs u v w tx ty tz, twice) ---

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
