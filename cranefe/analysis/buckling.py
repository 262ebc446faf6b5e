"""Buckling under gravity: the factor on gravity at which the static state stops being
stable.

With sway on, the stiffness about the static state is ``K = K_e + K_g``: elastic, plus
the tension and load stiffness of the static forces (`cranefe.system`). The static state
is linear in gravity, so at gravity x lambda the stiffness is ``K_e + lambda K_g``, which
stops being positive definite at the smallest lambda > 0 with
``det(K_e + lambda K_g) = 0``: with ``K_e`` positive definite, the eigenvalues nu of the
symmetric-definite pair ``(-K_g, K_e)`` give ``lambda = 1 / nu`` and the critical factor
is ``1 / max(nu)`` (a linearised, "Euler" buckling analysis; e.g. Bathe, Finite Element
Procedures, section 6.8.2, eq. 6.244-6.245). The axial forces vary along members as the
static state gives them (self-weight).
"""

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from ..assembly import sum_blocks
from ..errors import AnalysisError
from ..system import assemble


@dataclass(frozen=True)
class BucklingResult:
    """The critical gravity factor and its mode (generalised coordinates)."""

    factor: float             # gravity x factor buckles the structure; inf: never
    mode: np.ndarray          # (n,) buckling mode, max |q| = 1
    labels: tuple             # (n,) names of the coordinates


def gravity_buckling(model, effects=None, system=None):
    """Critical factor on gravity of `model` (sway on), by the dense generalised
    eigenproblem of (-K_g, K_e); K_e (all elastic stiffness without the static forces)
    must be positive definite: every motion restrained elastically."""
    effects = (effects or model.effects)
    if not effects.sway:
        effects = type(effects)(**{**effects.as_dict(), "sway": True})
    system = system or assemble(model, effects)
    T = system.dofs.T
    Kg = (T.T @ sum_blocks(system.geometric, system.dofs.layout.size) @ T).toarray()
    Kg = 0.5 * (Kg + Kg.T)
    Ke = system.K.toarray() - Kg
    Ke = 0.5 * (Ke + Ke.T)
    try:
        nu, vec = sla.eigh(-Kg, Ke)
    except np.linalg.LinAlgError as exc:
        raise AnalysisError("buckling under gravity needs every motion restrained "
                            "elastically (the elastic stiffness is not positive "
                            f"definite: {exc})") from None
    k = int(np.argmax(nu))
    if nu[k] <= 0:
        return BucklingResult(np.inf, np.zeros(len(nu)), tuple(system.dofs.labels))
    v = vec[:, k] / np.abs(vec[:, k]).max()
    return BucklingResult(float(1.0 / nu[k]), v, tuple(system.dofs.labels))
