"""Sway-free motion (issue 17): input shapers (`shapers`), shaped motion profiles and
their residual sway in closed form (`motion`), and the minimum-time swing-free trolley
move (`swingfree`). Linear theory throughout; docs/loads.md "Input shaping" derives it.
"""

from .motion import (AccelSteps, JerkSteps, double_pendulum_omegas, nonlinear_residual_sway,
                     pendulum_omega, residual_amplitude, residual_sway, s_curve, shape,
                     trapezoid)
from .shapers import SHAPERS, Shaper, convolve, ei, make, unshaped, zv, zvd, zvdd
from .swingfree import energy_optimal_swing_free, min_time_swing_free

__all__ = ["AccelSteps", "JerkSteps", "SHAPERS", "Shaper", "convolve",
           "double_pendulum_omegas", "ei", "energy_optimal_swing_free", "make", "min_time_swing_free",
           "nonlinear_residual_sway", "pendulum_omega", "residual_amplitude",
           "residual_sway", "s_curve", "shape", "trapezoid", "unshaped", "zv", "zvd",
           "zvdd"]
