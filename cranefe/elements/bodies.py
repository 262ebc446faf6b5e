"""Rigid-body kernels: cross-product matrices, rigid mass, load (gravity) stiffness."""

import numpy as np


def skew(c):
    """Cross-product matrices: skew(c) @ v == cross(c, v). c: (..., 3) -> (..., 3, 3)."""
    c = np.asarray(c, dtype=float)
    z = np.zeros(c.shape[:-1])
    return np.stack([np.stack([z, -c[..., 2], c[..., 1]], -1),
                     np.stack([c[..., 2], z, -c[..., 0]], -1),
                     np.stack([-c[..., 1], c[..., 0], z], -1)], -2)


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
