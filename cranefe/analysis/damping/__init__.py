"""Damping from absorption coefficients (Heletiy 2016, eq. 11-17; docs/damping.md).

An element of stiffness c and absorption coefficient psi (energy absorbed per cycle over
the peak strain energy; psi = 2 delta for light damping) gets the equivalent viscous
coefficient ``b = psi c / (2 pi w)`` at the frequency w of the mode concerned (eq. 12),
so ``B(w) = K_psi / (2 pi w)`` with ``K_psi = (R T)^T diag(psi c) (R T) + sum psi_e K_e``
(beams). With the mass-normalised undamped modes V (eq. 14, corrected) everything
follows from ``H = V^T K_psi V / (2 pi)``:

- modal damping matrix ``D_ij = H_ij / sqrt(w_i w_j)`` (eq. 15; its diagonal is
  ``V_i^T B(w_i) V_i``, the off-diagonal terms take the geometric mean of the two
  frequencies, which keeps D symmetric and positive semi-definite);
- decoupled estimate (eq. 16-17): ``zeta_i = d_ii / (2 w_i) = H_ii / (2 w_i^2)``, damped
  frequency ``sqrt(w_i^2 - (d_ii/2)^2)``, log decrement ``2 pi zeta / sqrt(1 - zeta^2)``;
- Hasselman coupling coefficient of modes i, j: the off-diagonal element of the modal
  complex dynamic matrix ``diag(w^2) + i H`` over the difference of its diagonal ones,
  ``eps_ij = |H_ij| / |w_i^2 - w_j^2 + i (H_ii - H_jj)|`` (the size of mode j in the
  complex mode i);
- perturbation estimates (third order) of the exact eigenvalues, hence of the error of
  the decoupled zeta (to leading order ``-sum_j eps_ij^2 [(1 - H_jj/H_ii) +
  (1 - w_j^2/w_i^2)]`` against the complex-stiffness answer for two coupled modes);
  the estimate is trusted while every eps_ij < KAPPA and that error < ERROR_TOL.

Exact answers, per elastic mode: the quadratic eigenproblem
``(lam^2 M + lam B(w_i) + K) x = 0`` with the mode's own B, in first-order form, and the
frequency-independent complex-stiffness problem ``(K + i K_psi / (2 pi)) x = mu M x``
(loss factor psi / (2 pi)): QZ for small systems, else one sparse n x n factorisation
per mode at the decoupled eigenvalue and a block shift-invert iteration started from
the undamped modes concerned. Eigenvalues are assigned to modes by their participation
``|V_i^T M x|^2 / x^H M x``.
"""

from .analysis import damping, first_modes, partner_modes, scene_method
from .constants import (DENSE_MAX, ERROR_TOL, EXTRA_MODES, KAPPA, METHODS, PARTNER_SPAN,
                        UNDAMPED)
from .element import (damping_matrix, element_frequencies, equivalent_viscous,
                      polyharmonic_k1, psi_stiffness)
from .exact import exact_hysteretic, exact_viscous
from .modal import ModalDamping, modal_damping, modal_damping_ratios
from .result import DampingResult

__all__ = ["damping", "scene_method", "first_modes", "partner_modes", "DENSE_MAX", "ERROR_TOL",
           "EXTRA_MODES", "KAPPA", "METHODS", "PARTNER_SPAN", "UNDAMPED", "damping_matrix",
           "element_frequencies", "equivalent_viscous", "polyharmonic_k1", "psi_stiffness",
           "exact_hysteretic", "exact_viscous", "ModalDamping", "modal_damping",
           "modal_damping_ratios", "DampingResult"]
