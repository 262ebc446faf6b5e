"""Pure, batched kernels of the operation engine: rope and spring states and the rigid
motion of a joint, at ANY geometry (docs/operations.md, "Mechanics").

Nothing here sees a Model: inputs are arrays of node positions, element connectivity and
section data; outputs are arrays for all elements at once (style.md, item 13). The
linear core's rows r and stiffness `EA/L r r^T + S (f/l)(I - e e^T)` are what these
return at the reference geometry.
"""

import numpy as np


def hencky_tension(EA, L, L0):
    """Rope force S = EA ln(L / L0) (logarithmic strain), and dS/dL = EA / L.

    It equals the engineering law EA (L - L0) / L0 to a relative strain/2 (7.5e-4 of S at a
    0.15 % strain); its tangent EA / L in the *current* length is the linear core's
    `c = EA / length` exactly (docs/operations.md, "Mechanics")."""
    return EA * np.log(L / L0), EA / L


def hencky_energy(EA, L, L0):
    """Elastic energy of a rope with S = EA ln(L/L0): integral of S dL from L0 to L,
    U = EA (L ln(L/L0) - L + L0) (>= 0, zero at L = L0)."""
    return EA * (L * np.log(L / L0) - L + L0)


def rope_state(x, span_a, span_b, falls, rope, EA, L0, extra=None, taut=None):
    """Lengths, forces, gradient rows and tangent stiffness of all ropes at positions x.

    Parameters
    ----------
    x : (n, 3) node positions (current geometry).
    span_a, span_b : (ns,) node indices of each span's ends.
    falls : (ns,) multiplicity of each span (tackle falls).
    rope : (ns,) index of the rope each span belongs to (0 .. nr-1).
    EA : (nr,) axial rigidity of one fall.
    L0 : (nr,) unstretched length of each rope.
    extra : (nr,) length not in the spans (e.g. on the drum, terminations), or None.
    taut : (nr,) bool, which ropes carry force; None: those with L > L0.

    Returns
    -------
    L : (nr,) current length through all falls, `sum f |x_b - x_a| + extra`.
    S : (nr,) force, `EA ln(L/L0)` where taut, else 0 (tension only).
    r : (nr, n, 3) gradient dL/dx (the elongation row of the linear core).
    K : (3n, 3n) tangent stiffness `sum EA/L r r^T + S d r/dx`, the span blocks
        `S f / l (I - e e^T)` on (b, b), (a, a) and minus on (a, b), (b, a).
    """
    x = np.asarray(x, dtype=float)
    n, nr = len(x), len(EA)
    d = x[span_b] - x[span_a]
    l = np.sqrt(np.einsum("ij,ij->i", d, d))
    e = d / l[:, None]
    L = np.bincount(rope, weights=falls * l, minlength=nr)
    if extra is not None:
        L = L + extra
    if taut is None:
        taut = L > L0
    S, c = hencky_tension(EA, L, L0)
    S = np.where(taut, S, 0.0)
    c = np.where(taut, c, 0.0)
    fe = falls[:, None] * e
    r = np.zeros((nr, n, 3))
    np.add.at(r, (rope, span_b), fe)
    np.add.at(r, (rope, span_a), -fe)
    rf = r.reshape(nr, 3 * n)
    K = (rf.T * c) @ rf
    # span geometric blocks (f S / l)(I - e e^T)
    g = (falls * S[rope] / l)[:, None, None] * (np.eye(3) - e[:, :, None] * e[:, None, :])
    K4 = K.reshape(n, 3, n, 3)
    for (i, j, sgn) in ((span_a, span_a, 1.0), (span_b, span_b, 1.0),
                        (span_a, span_b, -1.0), (span_b, span_a, -1.0)):
        np.add.at(K4, (i, slice(None), j, slice(None)), sgn * g)
    return L, S, r, K


def spring_state(x, node_a, node_b, k, d_ref, N_ref):
    """Axial springs between nodes: force N = N_ref + k (d - d_ref) along the current
    direction (tension positive), gradient rows and tangent `k e e^T + N/d (I - e e^T)`.

    Returns d (m,), N (m,), r (m, n, 3), K (3n, 3n)."""
    n, m = len(x), len(k)
    dv = x[node_b] - x[node_a]
    d = np.sqrt(np.einsum("ij,ij->i", dv, dv))
    e = dv / d[:, None]
    N = N_ref + k * (d - d_ref)
    r = np.zeros((m, n, 3))
    idx = np.arange(m)
    r[idx, node_b] += e
    r[idx, node_a] -= e
    rf = r.reshape(m, 3 * n)
    K = (rf.T * k) @ rf
    g = (N / d)[:, None, None] * (np.eye(3) - e[:, :, None] * e[:, None, :])
    K4 = K.reshape(n, 3, n, 3)
    for (i, j, sgn) in ((node_a, node_a, 1.0), (node_b, node_b, 1.0),
                        (node_a, node_b, -1.0), (node_b, node_a, -1.0)):
        np.add.at(K4, (i, slice(None), j, slice(None)), sgn * g)
    return d, N, r, K


def skew(a):
    """(3, 3) cross-product matrix of a (3,) vector: skew(a) @ b = a x b."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


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


def rope_spans(x, span_a, span_b, falls, rope, EA, L0, extra, taut):
    """The span-level state of all ropes (the engine's hot path; `rope_state` assembles
    the same into node rows): span lengths l (ns,), unit vectors e (ns, 3), rope lengths
    L (nr,) through all falls plus `extra`, and forces S (nr,) (zero where not taut)."""
    d = x[span_b] - x[span_a]
    l = np.sqrt(np.einsum("ij,ij->i", d, d))
    e = d / l[:, None]
    L = np.bincount(rope, weights=falls * l, minlength=len(EA)) + extra
    S = np.where(taut, EA * np.log(L / L0), 0.0)
    return l, e, L, S


def projected_tangent(w, e, D):
    """sum_s w_s D_s^T (I - e_s e_s^T) D_s: the tension (geometric) stiffness of spans
    with weights w = f S / l, on coordinates whose span-end difference is D_s (3, n)."""
    eD = np.einsum("si,sia->sa", e, D)
    return np.einsum("s,sia,sib->ab", w, D, D) - np.einsum("s,sa,sb->ab", w, eD, eD)
