"""Thresholds and choices of the damping analysis (docs/damping.md)."""

METHODS = ("modal", "exact", "both", "auto")
KAPPA = 0.1          # Hasselman's criterion: every coupling coefficient below this
ERROR_TOL = 0.02     # and the predicted relative error of zeta below this
DENSE_MAX = 40       # coordinates up to which the exact problems are solved by QZ
EXTRA_MODES = 4      # modes computed beyond --count, as coupling partners, and at least
PARTNER_SPAN = 2.0   # up to this multiple of the highest reported frequency
UNDAMPED = 1e-10     # H_ii below this fraction of psi_max w_i^2 / (2 pi): round-off
