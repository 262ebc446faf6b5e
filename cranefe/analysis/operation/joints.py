"""Joint coordinates of an operation scene: the inertia of the rigid subtree a torque,
force, motor or free joint carries (docs/operations.md, "Joint coordinates").

Every point of the subtree moves as x = R X + p (X its reference position, R, p the
child body's motion composed along the tree). Its mass properties in the reference
frame are the mass m, the first moment s = int X dm and the second moment
Theta = int X X^T dm; for a body of mass m_b, com c and inertia I_c about the com
(global axes) int (X - c)(X - c)^T dm = tr(I_c)/2 I - I_c, so
Theta_b = tr(I_c)/2 I - I_c + m_b c c^T; a point mass adds m X X^T (and its rotary
inertia as a body of zero size). Integrals of two affine fields over the subtree are then

    int (A X + a) . (B X + b) dm = tr(A Theta B^T) + a . (B s) + b . (A s) + m a . b

(`pair`), which gives the generalised mass M = int |dx/dq|^2 dm, the inertial force of
the velocity-dependent accelerations (Kane's method: Q = -int dx/dq . x''|_{q''=0} dm),
gravity's generalised force int dx/dq . g dm = g . (R_q s + m p_q) and the kinetic energy
T = 1/2 int |R' X + p'|^2 dm exactly, at any angle.
"""

import numpy as np


def subtree_mass(model, bodies, nodes):
    """(m, s (3,), Theta (3, 3)) of the bodies (indices) and the point masses at
    `nodes` (node indices carried by those bodies), reference frame."""
    m, s, Th = 0.0, np.zeros(3), np.zeros((3, 3))
    I3 = np.eye(3)
    for bi in bodies:
        b = model.bodies[bi]
        if b.mass <= 0:
            continue
        c = np.asarray(b.com, float)
        Ic = np.asarray(b.inertia, float)
        m += b.mass
        s += b.mass * c
        Th += 0.5 * np.trace(Ic) * I3 - Ic + b.mass * np.outer(c, c)
    ms = model.masses
    on = set(int(i) for i in nodes)
    for k, i in enumerate(ms.nodes):
        if int(i) not in on:
            continue
        X = np.asarray(model.coords[i], float)
        mk = float(ms.mass[k])
        Ic = np.asarray(ms.inertia[k], float) if ms.inertia is not None else np.zeros((3, 3))
        m += mk
        s += mk * X
        Th += 0.5 * np.trace(Ic) * I3 - Ic + mk * np.outer(X, X)
    return m, s, Th


def pair(A, a, B, b, m, s, Th):
    """int (A X + a) . (B X + b) dm over a rigid set with mass properties (m, s, Th)."""
    return float(np.einsum("ij,jk,ik->", A, Th, B) + a @ (B @ s) + b @ (A @ s)
                 + m * (a @ b))


def joint_jacobian(parent, hinge, K, K2, point, axis, sign, s):
    """d/ds and d^2/ds^2 of the child's (R, p) when the joint's drive variable s moves
    (the parent's motion does not depend on s): R = R_p R_j(sign s),
    p = R_p p_j + p_p; hinge R_j = I + sin K + (1 - cos) K^2, p_j = a - R_j a
    (elements.motion.hinge_motion); slider R_j = I, p_j = sign s n."""
    Rp = parent[0]
    if hinge:
        ang = sign * s
        sn, cs = np.sin(ang), np.cos(ang)
        dRj = sign * (cs * K + sn * K2)
        ddRj = -sn * K + cs * K2
        Rq, Rqq = Rp @ dRj, Rp @ ddRj
        return Rq, -Rq @ point, Rqq, -Rqq @ point
    Z = np.zeros((3, 3))
    return Z, sign * (Rp @ axis), Z, np.zeros(3)
