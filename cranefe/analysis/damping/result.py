"""The result of a damping analysis."""

import math
from dataclasses import dataclass, field

import numpy as np


from ..jsonable import num, timings
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

    def to_dict(self):
        """The JSON document of ``cranefe damping --json``: the keys of ``cranefe modes``
        (index as there, rigid modes included) plus, per mode, the decoupled estimate
        (``damping_ratio``, ``damped_frequency_hz``, ``log_decrement``), Hasselman's
        ``coupling`` (largest coefficient, ``coupled_with`` that mode), ``weak_coupling``,
        ``predicted_error``, and where solved ``exact`` (viscous) and ``hysteretic``
        (complex stiffness) objects with their relative error."""
        err_v, err_h = self.error_viscous, self.error_hysteretic
        dec_v, dec_h = self.exact_log_decrement, self.hysteretic_log_decrement
        modes = []
        for k in range(len(self.omega)):
            w, rigid = float(self.omega[k]), bool(self.rigid[k])
            m = {"index": k + 1, "frequency_hz": num(w / (2 * math.pi)),
                 "omega_rad_s": num(w), "period_s": None if rigid else num(2 * math.pi / w),
                 "rigid": rigid,
                 "damping_ratio": num(self.zeta[k]),
                 "damped_frequency_hz": num(self.damped_omega[k] / (2 * math.pi)),
                 "log_decrement": num(self.log_decrement[k]),
                 "coupling": num(self.coupling[k]),
                 "coupled_with": (int(self.coupled_with[k]) + 1
                                  if self.coupled_with[k] >= 0 else None),
                 "weak_coupling": bool(self.criterion_holds[k]),
                 "predicted_error": num(self.predicted_error[k]),
                 "absorbed_most_by": ({"element": self.dominant_element[k],
                                       "share": num(self.dominant_share[k])}
                                      if self.dominant_element[k] else None)}
            if self.exact_zeta is not None and not np.isnan(self.exact_zeta[k]):
                m["exact"] = {"damping_ratio": num(self.exact_zeta[k]),
                              "damped_frequency_hz":
                                  num(self.exact_damped_omega[k] / (2 * math.pi)),
                              "log_decrement": None if rigid else num(dec_v[k]),
                              "relative_error": _finite_or_none(err_v, k)}
                m["hysteretic"] = {"damping_ratio": num(self.hysteretic_zeta[k]),
                                   "damped_frequency_hz":
                                       num(self.hysteretic_damped_omega[k] / (2 * math.pi)),
                                   "log_decrement": None if rigid else num(dec_h[k]),
                                   "relative_error": _finite_or_none(err_h, k)}
            modes.append(m)
        return {"model": self.model_name, "effects": self.effects, "dofs": self.dofs,
                "quasi_cyclic": list(self.quasi_cyclic), "method": self.method,
                "criterion": {"coupling_limit": KAPPA, "error_limit": ERROR_TOL,
                              "holds": bool(np.all(self.trusted))},
                "modes": modes,
                "timings_s": timings(self.timings),
                "warnings": list(self.warnings)}


def _finite_or_none(values, k):
    return None if values is None else num(values[k])


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


