"""Pure, batched element kernels: geometry and element data in, local rows/blocks out.

No global state, no I/O. Degrees of freedom are *primitive* indices (see
`cranefe.dofs.Layout`): three translations per node, six per body (at its centre of
mass), one rotation per drum. Assembly (`cranefe.assemble`) maps them to the
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
