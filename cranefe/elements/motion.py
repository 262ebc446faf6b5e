"""Rigid motions of joints at any angle or stroke, with their first and second time
derivatives: X -> R X + p for a body turned about a hinge or moved along a slider, and
their composition along a chain of bodies (the large-motion engine's kinematics)."""

import numpy as np

from .bodies import skew


def hinge_motion(axis, point, phi, dphi, ddphi):
    """Rigid motion X -> R X + p of a turn by phi about `axis` through `point`, with its
    first and second time derivatives (Rodrigues: R = I + sin(phi) K + (1 - cos(phi)) K^2,
    K = skew(axis); dR = phi' (cos K + sin K^2); ddR = phi'' (cos K + sin K^2) +
    phi'^2 (-sin K + cos K^2)). Returns (R, dR, ddR, p, dp, ddp); p = point - R point."""
    K = skew(axis)
    K2 = K @ K
    s, c = np.sin(phi), np.cos(phi)
    R = np.eye(3) + s * K + (1 - c) * K2
    A = c * K + s * K2
    dR = dphi * A
    ddR = ddphi * A + dphi**2 * (-s * K + c * K2)
    return R, dR, ddR, point - R @ point, -dR @ point, -ddR @ point


def slider_motion(axis, s, ds, dds):
    """Rigid motion X -> X + s axis (a slider), with its derivatives (as hinge_motion)."""
    Z = np.zeros((3, 3))
    return np.eye(3), Z, Z, s * axis, ds * axis, dds * axis


def compose(parent, joint):
    """The motion of a child body, parent o joint, with derivatives by the product rule:
    R = Rp Rj, p = Rp pj + pp (and their first and second derivatives)."""
    Rp, dRp, ddRp, pp, dpp, ddpp = parent
    Rj, dRj, ddRj, pj, dpj, ddpj = joint
    return (Rp @ Rj, dRp @ Rj + Rp @ dRj, ddRp @ Rj + 2 * dRp @ dRj + Rp @ ddRj,
            Rp @ pj + pp, dRp @ pj + Rp @ dpj + dpp,
            ddRp @ pj + 2 * dRp @ dpj + Rp @ ddpj + ddpp)


IDENTITY_MOTION = (np.eye(3), np.zeros((3, 3)), np.zeros((3, 3)),
                   np.zeros(3), np.zeros(3), np.zeros(3))
