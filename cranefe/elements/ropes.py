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
    e, l = span_geometry(x, span_a, span_b)
    falls = np.asarray(falls, dtype=float)
    L = np.bincount(rope, weights=falls * l, minlength=len(L0)) + extra
    taut = L > L0
    S, c = hencky_tension(EA, L, np.where(taut, L0, L))
    fe = falls[:, None] * e
    return RopeForce(L, np.where(taut, S, 0.0), e, l, np.hstack([-fe, fe]),
                     np.where(taut, c, 0.0))
