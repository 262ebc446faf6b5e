"""Rope (and axial-spring, truss) kernels: spans between two points, at any geometry.

Pure and batched: current coordinates and element arrays in, element arrays out. A span
from point a to point b with f parallel falls has length l = |x_b - x_a|, unit vector e,
elongation row f [-e, e] on (u_a, u_b) (Heletiy 2016, eq. 2-3), and under a tension S the
tension stiffness (f S / l)(I - e e^T) (docs/theory.md). `rope_force` evaluates a whole
rope through all its spans at the current positions, as the large-motion engine needs.
"""

from dataclasses import dataclass

import numpy as np


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


def rope_mass(mu, length, lumped=False):
    """Mass of two-node rope elements on [u_start; u_end] (3 + 3 translations), (ne, 6, 6).

    Consistent (linear shape functions): mu l / 6 [[2 I, I], [I, 2 I]];
    lumped: mu l / 2 at each end.
    """
    m = (mu * length)[:, None, None]
    if lumped:
        return m / 2 * np.eye(6)
    return m / 6 * np.kron(np.array([[2.0, 1.0], [1.0, 2.0]]), np.eye(3))


@dataclass(frozen=True)
class RopeForce:
    """Ropes evaluated at one configuration (see `rope_force`)."""

    L: np.ndarray        # (nr,) current length through all falls (plus extra length)
    S: np.ndarray        # (nr,) tension, zero where slack (L <= L0)
    e: np.ndarray        # (ns, 3) unit vector of each span, from a to b
    l: np.ndarray        # (ns,) span lengths
    grad: np.ndarray     # (ns, 6) dL/d(x_a, x_b) of each span: f [-e, e]
    c: np.ndarray        # (nr,) axial stiffness dS/dL = EA / L of taut ropes, 0 if slack

    def span_force(self, rope):
        """(ns, 6) generalised force -S dL/dx on (x_a, x_b) of every span."""
        return -self.S[rope][:, None] * self.grad

    def geometric(self, rope, falls):
        """(ns, 6, 6) tension stiffness S dr/dx of every span (string_stiffness)."""
        return string_stiffness(self.S[rope], falls, self.e, self.l)


def hencky_tension(EA, L, L0):
    """Rope force S = EA ln(L / L0) (logarithmic strain) and its tangent dS/dL = EA / L.

    To first order in the strain this is EA (L - L0) / L0; its tangent in the current
    length, EA / L, is the stiffness c = EA / L that the linear core gives a rope whose
    reference (stretched) length is L (Heletiy 2016, eq. 5), so linearising the large-
    motion engine at the static state gives the linear core's K exactly
    (docs/operations.md, "Rope law")."""
    return EA * np.log(L / L0), EA / L


def hencky_energy(EA, L, L0):
    """Elastic energy of a rope with S = EA ln(L/L0): U = EA (L ln(L/L0) - L + L0) >= 0."""
    return EA * (L * np.log(L / L0) - L + L0)


def rope_force(x, span_a, span_b, falls, rope, EA, L0, extra=0.0):
    """Tension-only ropes through frictionless sheaves at the current positions x.

    x : (n, 3) positions of the points the spans join; span_a, span_b, falls, rope : (ns,)
    end points, multiplicity and rope index of every span; EA, L0 : (nr,) axial stiffness
    (per fall) and unstretched length of each rope; extra : (nr,) or scalar length that
    does not deform with the geometry (turns on a drum, terminations).

    The length of a rope is L(x) = sum_k f_k |x_b,k - x_a,k| + extra (design.md, "Large
    motions"; Heletiy 2016 eq. 2-3 is its linearisation); its tension is
    S = EA ln(L / L0) when L > L0 and 0 otherwise (a rope cannot push; `hencky_tension`);
    the gradient of L is the elongation row r(x), and the tangent stiffness
    c r r^T + S dr/dx splits into `c` (taut ropes) and `geometric` (the tension stiffness
    of every span). The linear core calls this at the reference positions for its rows
    and lengths; the large-motion engine at every step.
    """
    falls = np.asarray(falls, dtype=float)
    l, e, L, S = rope_spans(x, span_a, span_b, falls, rope, EA, L0, extra)
    taut = S > 0
    fe = falls[:, None] * e
    return RopeForce(L, S, e, l, np.hstack([-fe, fe]),
                     np.where(taut, hencky_tension(EA, L, L)[1], 0.0))


def rope_spans(x, span_a, span_b, falls, rope, EA, L0, extra=0.0, taut=None):
    """The span-level state of all ropes: span lengths l (ns,), unit vectors e (ns, 3),
    rope lengths L (nr,) through all falls plus `extra`, and tensions S (nr,),
    S = EA ln(L / L0) where `taut` (default: L > L0), else 0. The large-motion engine's
    hot path (it passes `taut` as its event logic decides); `rope_force` adds the rows."""
    d = x[span_b] - x[span_a]
    l = np.sqrt(np.einsum("ij,ij->i", d, d))
    e = d / l[:, None]
    L = np.bincount(rope, weights=falls * l, minlength=len(L0)) + extra
    if taut is None:
        taut = L > L0
    S = np.where(taut, EA * np.log(L / L0), 0.0)
    return l, e, L, S


def projected_tangent(w, e, D):
    """sum_s w_s D_s^T (I - e_s e_s^T) D_s: the tension (geometric) stiffness of spans
    with weights w = f S / l, on coordinates whose span-end difference is D_s (3, n)."""
    eD = np.einsum("si,sia->sa", e, D)
    return np.einsum("s,sia,sib->ab", w, D, D) - np.einsum("s,sa,sb->ab", w, eD, eD)


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
    _add_span_blocks(K, span_a, span_b, g)
    return L, S, r, K


def _add_span_blocks(K, a, b, g):
    """Add span blocks g (ns, 3, 3) of K (3n, 3n) as [[g, -g], [-g, g]] on the
    translations of each span's end points a, b (ns,)."""
    n = K.shape[0] // 3
    K4 = K.reshape(n, 3, n, 3)
    for (i, j, sgn) in ((a, a, 1.0), (b, b, 1.0), (a, b, -1.0), (b, a, -1.0)):
        np.add.at(K4, (i, slice(None), j, slice(None)), sgn * g)


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
    _add_span_blocks(K, node_a, node_b, g)
    return d, N, r, K
