"""The result of a damping analysis."""

from dataclasses import dataclass, field

import numpy as np


from .constants import ERROR_TOL, KAPPA


@dataclass
class DampingResult:
    """Damping of the modes of one model; rigid (quasi-cyclic) modes first, undamped.

    Arrays are per mode (m,) in the order of `cranefe modes`; the exact ones are NaN
    where not computed (all None with method modal)."""

    model_name: str
    effects: dict
    method: str                   # modal | exact | both | auto
    omega: np.ndarray             # (m,) undamped, rad/s
    rigid: np.ndarray             # (m,) quasi-cyclic: no element deforms, no damping
    zeta: np.ndarray              # (m,) decoupled damping ratios (Hasselman), eq. 16
    damped_omega: np.ndarray      # (m,) decoupled damped frequencies, eq. 17
    log_decrement: np.ndarray     # (m,) 2 pi zeta / sqrt(1 - zeta^2); NaN for rigid
    coupling: np.ndarray          # (m,) largest coupling coefficient eps_ij of the mode
    coupled_with: np.ndarray      # (m,) 0-based mode index of that partner, -1 if none
    coupling_matrix: np.ndarray   # (m, m) eps_ij among the reported modes
    predicted_error: np.ndarray   # (m,) estimated relative error of zeta (perturbation)
    D: np.ndarray                 # (m, m) modal damping matrix V^T B V (eq. 15)
    dominant_element: tuple       # (m,) element absorbing most in each mode ("" if none)
    dominant_share: np.ndarray    # (m,) its share of the mode's absorption
    exact_zeta: np.ndarray = None              # (m,) viscous, each mode's own B
    exact_damped_omega: np.ndarray = None
    hysteretic_zeta: np.ndarray = None         # (m,) complex stiffness
    hysteretic_damped_omega: np.ndarray = None
    dofs: int = 0
    quasi_cyclic: tuple = ()
    timings: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)
    status: int = 0
    message: str = "ok"

    @property
    def frequency_hz(self):
        return self.omega / (2 * np.pi)

    @property
    def criterion_holds(self):
        """Hasselman's weak coupling: every coupling coefficient of the mode < KAPPA."""
        return self.coupling < KAPPA

    @property
    def trusted(self):
        """Weak coupling and a predicted error of zeta below ERROR_TOL."""
        return self.criterion_holds & (np.abs(self.predicted_error) < ERROR_TOL)

    @property
    def exact_log_decrement(self):
        return None if self.exact_zeta is None else _log_decrement(self.exact_zeta)

    @property
    def hysteretic_log_decrement(self):
        """Free vibration e^{i sqrt(mu) t}: 2 pi Im sqrt(mu) / Re sqrt(mu)
        = 2 pi tan(atan(2 zeta) / 2)."""
        if self.hysteretic_zeta is None:
            return None
        return 2 * np.pi * np.tan(np.arctan(2 * self.hysteretic_zeta) / 2)

    @property
    def error_viscous(self):
        """Relative error of the decoupled zeta against the exact viscous one."""
        return None if self.exact_zeta is None else _rel(self.zeta, self.exact_zeta)

    @property
    def error_hysteretic(self):
        """Relative error of the decoupled zeta against the complex-stiffness one."""
        return None if self.hysteretic_zeta is None else _rel(self.zeta,
                                                             self.hysteretic_zeta)


def _log_decrement(zeta):
    """Log decrement over one damped period, 2 pi zeta / sqrt(1 - zeta^2) (inf if
    overdamped); psi = 2 delta sqrt(1 - zeta^2) exactly for one degree of freedom."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(zeta < 1, 2 * np.pi * zeta / np.sqrt(np.abs(1 - zeta**2)), np.inf)


def _rel(estimate, exact):
    """(estimate - exact) / exact; 0 where both are zero to round-off, NaN if unknown."""
    floor = 1e-9 * max(np.nanmax(np.abs(exact), initial=0.0), 1e-300)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(np.abs(exact) > floor, (estimate - exact) / exact,
                        np.where(np.abs(estimate - exact) <= floor, 0.0, np.nan))


