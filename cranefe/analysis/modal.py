"""Natural frequencies and mass-normalised modes.

Dense path (n <= DENSE_MAX): condense massless and quasi-cyclic coordinates
(`cranefe.condense`), then ``scipy.linalg.eigh`` on the positive-definite pair.
Sparse path: shift-invert Lanczos (``eigsh``) with a negative shift, so K - sigma M is
positive definite even with quasi-cyclic (zero-frequency) motions; massless coordinates
are condensed implicitly inside the factorised operator, never formed.
"""

import logging
import time
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse.linalg as spla

from ..system import assemble
from ..condense import DENSE_MAX, condense, massless_split, no_inertia
from ..errors import AnalysisError, ModelError
from ..model import plausibility
from .graded import element_energy, element_factor, graded_eigen
from .jsonable import num, timings

log = logging.getLogger(__name__)
SMALL = 300        # below this many coordinates the dense solution is the fastest


@dataclass
class ModalResult:
    """Modes of one model with one set of effects; zero-frequency (rigid) modes first."""

    model_name: str
    effects: dict
    labels: tuple             # (n,) generalised coordinates
    omega: np.ndarray         # (m,) rad/s
    shapes: np.ndarray        # (n, m) mass-normalised: shapes^T M shapes = I
    node_shapes: np.ndarray   # (m, nn, 3) node translations of each mode
    rigid: np.ndarray         # (m,) bool: quasi-cyclic (zero-frequency) motion
    quasi_cyclic: tuple
    massless: tuple
    solver: str
    timings: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)
    status: int = 0
    message: str = "ok"
    drive_reduction: dict = None   # with drive: reduced, the comparison of `drive_reduction`
    graded: str = ""          # how a graded problem was solved (and why not), else ""

    @property
    def frequency_hz(self):
        return self.omega / (2 * np.pi)

    @property
    def period_s(self):
        with np.errstate(divide="ignore"):
            return np.where(self.omega > 0, 2 * np.pi / np.where(self.omega > 0,
                                                                 self.omega, 1), np.inf)

    @property
    def dofs(self):
        return len(self.labels)

    def to_dict(self, comparison=None):
        """The JSON document of ``cranefe modes --json`` (design.md, "Command-line
        contract"); `comparison`: the drive-reduction comparison, if any."""
        doc = {
            "model": self.model_name,
            "effects": self.effects,
            "dofs": self.dofs,
            "quasi_cyclic": list(self.quasi_cyclic),
            "massless_condensed": len(self.massless),
            "solver": self.solver,
            "modes": [{"index": i + 1, "frequency_hz": num(f), "omega_rad_s": num(w),
                       "period_s": num(t), "rigid": bool(r)}
                      for i, (f, w, t, r) in enumerate(zip(self.frequency_hz, self.omega,
                                                           self.period_s, self.rigid))],
            "timings_s": timings(self.timings),
            "warnings": list(self.warnings),
        }
        comparison = self.drive_reduction if comparison is None else comparison
        if comparison is not None:
            doc["drive_reduction"] = comparison
        return doc


def modes(model, effects=None, count=None, solver="auto", system=None):
    """Natural modes of `model`. count=None: all (dense) or 10 (sparse); else >= 1."""
    if count is not None and (isinstance(count, bool) or int(count) != count or count < 1):
        raise ModelError(f"count {count}: ask for at least one mode (a whole number >= 1)",
                         getattr(model, "file", None), "count")
    t0 = time.perf_counter()
    system = system or assemble(model, effects)
    n = system.K.shape[0]
    if n == 0:
        raise AnalysisError("the model has no degrees of freedom for these effects: "
                            "nothing moves")
    if solver == "auto":       # dense when small, or when all modes are wanted
        solver = "dense" if n <= SMALL or (count is None and n <= DENSE_MAX) else "sparse"
    if solver != "dense" and not np.any(system.M.diagonal() > 0):
        raise no_inertia(model)
    t1 = time.perf_counter()
    warnings = []
    moving = int(np.sum(system.M.diagonal() > 0))
    if solver == "sparse" and (count or 10) >= moving:     # ARPACK finds k < n only
        warnings.append(f"--solver sparse finds fewer than all {moving} modes of this "
                        "model: solved densely")
        solver = "dense"
    if solver == "dense":
        omega, shapes, rigid, qc, ml, dense_warnings, graded = _dense(system, count)
        warnings += dense_warnings
    else:
        omega, shapes, rigid, qc, ml = _sparse(system, count or 10)
        graded = ""
    t2 = time.perf_counter()
    # sign convention: the largest component of each shape is positive
    big = np.argmax(np.abs(shapes), axis=0)
    shapes = shapes * np.where(shapes[big, np.arange(shapes.shape[1])] < 0, -1.0, 1.0)
    nn = len(model.node_names)
    nodes = (system.dofs.T[system.dofs.layout.translations(nn)] @ shapes).T
    result = ModalResult(
        model.name, system.effects.as_dict(), system.dofs.labels, omega, shapes,
        nodes.reshape(len(omega), -1, 3), rigid, qc, ml, solver,
        {**system.timings, "solve": t2 - t1, "total": time.perf_counter() - t0},
        list(warnings), graded=graded)
    if system.static is not None:
        slack = [f"rope {r.name} has no tension ({S:.3g} N) somewhere in the static state"
                 for r, (S, _) in zip(model.ropes, system.static.rope_tension()) if S <= 0]
        result.warnings.extend(slack)
    tension = system.static.rope_tension() if system.static is not None else None
    result.warnings.extend(plausibility.warnings(model, tension, omega[~np.asarray(rigid)]))
    return result


def _dense(system, count):
    c = condense(system)
    factor = element_factor(system)
    (lam, Y), graded = _eigh_accurate(c, factor)
    _check_stable(lam, c.quasi_cyclic)
    shapes = np.hstack([c.rigid, c.recover @ Y])
    _check_negative(lam, factor, shapes[:, c.rigid.shape[1]:])
    lam = np.maximum(lam, 0.0)
    omega = np.concatenate([np.zeros(c.rigid.shape[1]), np.sqrt(lam)])
    rigid = np.arange(len(omega)) < c.rigid.shape[1]
    rigid, qc = _zero_to_roundoff(factor, shapes, rigid, c.quasi_cyclic,
                                  system.dofs.labels)
    omega = np.where(rigid, 0.0, omega)
    if count is not None:
        omega, shapes, rigid = omega[:count], shapes[:, :count], rigid[:count]
    return omega, shapes, rigid, qc, c.massless, c.warnings, graded


def _zero_to_roundoff(factor, shapes, rigid, qc, labels):
    """Rigid modes: those of the null space, and any whose w^2 is zero to round-off of
    its element terms (`graded.element_energy`): a mechanism whose positive and negative
    tension stiffnesses cancel gives w^2 ~ -1e-30, not 0. They have the smallest w^2, so
    rigid modes still come first. -> (rigid, labels of rigid modes)"""
    _, zero = element_energy(factor, shapes)
    extra = ~rigid & zero
    qc = tuple(qc) + tuple(labels[int(np.argmax(np.abs(shapes[:, i])))]
                           for i in np.flatnonzero(extra))
    return rigid | extra, qc


GRADED = 1e6      # spread of Rayleigh quotients K_ii/M_ii, or of the element stiffnesses
                  # (squared row norms of the factor), above which the Jacobi SVD is used


def _eigh_accurate(c, factor):
    """All eigenpairs of K1 y = lam A1 y (A1-normalised), accurate where it matters,
    and how they were found.

    LAPACK's eigh works on A1^-1/2 K1 A1^-1/2 with absolute errors eps |lam_max|, so with
    stiffness or mass contrasts (a graded problem) the low modes lose relative accuracy
    (a rope of nearly zero mass on a 5 t hook lost 1e-2 of the hoist frequency). A graded
    problem is solved from the element factor (`graded.graded_eigen`: singular values of
    F1 L_A^-T by the preconditioned one-sided Jacobi SVD, never forming K) with high
    relative accuracy for every mode (negative parts, from compression or a body above
    its hinge, merged with the rows around them). When they cannot be merged locally, the
    Cholesky factor of the assembled K1 is used instead,
    B = L_A^-1 L_K (Jacobi SVD again; accurate only as far as K1 is). Otherwise, or when
    K1 is not positive definite (an unstable equilibrium, reported by the caller), eigh.
    """
    K, M = c.K, c.M
    n = K.shape[0]
    if not n:
        return (np.zeros(0), np.zeros((0, 0))), ""
    ratio = np.diag(K) / np.diag(M)
    if not (ratio.min() > 0 and max(ratio.max() / ratio.min(), factor.spread()) > GRADED):
        return sla.eigh(K, M), ""
    pairs, how = graded_eigen(factor, np.setdiff1d(np.arange(len(c.recover)), c.inertial),
                              c.positional, c.inertial, M, c.massless_map)
    if pairs is not None:
        return pairs, how
    log.info("graded problem: %s", how)
    try:
        LK, LM = np.linalg.cholesky(K), np.linalg.cholesky(M)
    except np.linalg.LinAlgError:
        return sla.eigh(K, M), how + "; K1 not positive definite: eigh"
    from scipy.linalg.lapack import dgejsv
    B = sla.solve_triangular(LM, LK, lower=True)
    sva, U, _, work, _, info = dgejsv(B, jobv=3)
    if info == 0:
        lam = (sva * work[0] / work[1]) ** 2
        order = np.argsort(lam)
        return (lam[order], sla.solve_triangular(LM, U[:, order], lower=True, trans="T")), how
    return sla.eigh(K, M), how + "; Jacobi SVD failed: eigh"


def _check_stable(lam, qc):
    if len(lam) and lam[0] < -1e-9 * max(abs(lam[-1]), 1e-300):
        _unstable(lam[0])


def _unstable(w2):
    raise AnalysisError(
        f"the reference geometry is not a stable equilibrium: a mode has w^2 = "
        f"{w2:.4g} s^-2 < 0 (e.g. a body balanced above its hinge with too weak a "
        "spring, a compressed rope or a member past its buckling load); check the "
        "supports, the loads and the geometry")


def _check_negative(lam, factor, shapes):
    """A w^2 below zero that is not round-off of its element terms (`element_energy`):
    the check above is relative to the largest w^2, which a fine mesh makes so large that
    a column 10 % past its buckling load passed as a 0 Hz mode."""
    neg = np.flatnonzero(lam < 0)
    if not len(neg):
        return
    w2, zero = element_energy(factor, shapes[:, neg])
    bad = (w2 < 0) & ~zero
    if np.any(bad):
        _unstable(w2[bad].min())


def _sparse(system, k):
    """Shift-invert eigsh on K, M with massless coordinates condensed inside the operator."""
    K, M = system.K.tocsc(), system.M.tocsc()
    a, b = massless_split(system.M)
    Ma = M[a][:, a]
    # shift: negative (K - sigma M is positive definite with quasi-cyclic motions), of
    # the order of the smallest Rayleigh quotient K_ii / M_ii rather than the mean one,
    # which would blur the low modes together (this sets the speed of convergence only)
    ratio = K.diagonal()[a] / Ma.diagonal()
    ratio = ratio[ratio > 0].min() if np.any(ratio > 0) else 1.0
    sigma = -1e-3 * ratio
    lu = spla.splu((K - sigma * M).tocsc())
    n = K.shape[0]

    def opinv(x):
        full = np.zeros(n)
        full[a] = x
        return lu.solve(full)[a]

    OP = spla.LinearOperator((len(a), len(a)), matvec=opinv, dtype=float)
    Kaa, Kab = K[a][:, a].tocsr(), K[a][:, b].tocsr()
    Kbb = spla.splu(K[b][:, b].tocsc()) if len(b) else None

    def kstar(x):
        y = Kaa @ x
        if Kbb is not None:
            y -= Kab @ Kbb.solve(Kab.T @ x)
        return y

    A = spla.LinearOperator((len(a), len(a)), matvec=kstar, dtype=float)
    k = min(k, len(a) - 1)
    # a fixed start vector: the same model gives the same digits on every run
    v0 = np.random.default_rng(0).standard_normal(len(a))
    lam, Xa = spla.eigsh(A, k=k, M=Ma, sigma=sigma, OPinv=OP, which="LM", v0=v0)
    order = np.argsort(lam)
    lam, Xa = lam[order], Xa[:, order]
    X = np.zeros((n, k))
    X[a] = Xa
    if len(b):
        X[b] = -Kbb.solve(Kab.T @ Xa)
    # zero to round-off of K - sigma M, or of the element stiffness the mode meets
    w2, zero = element_energy(element_factor(system), X)
    if np.any((w2 < 0) & (lam < 0) & ~zero):
        _unstable(lam.min())
    rigid = (np.abs(lam) < 1e-10 * ratio) | zero
    _check_stable(np.where(rigid, 0, lam), ())
    lab = system.dofs.labels
    qc = tuple(lab[a[np.argmax(np.abs(Xa[:, i]))]] for i in np.flatnonzero(rigid))
    return np.sqrt(np.maximum(lam, 0)) * ~rigid, X, rigid, qc, \
        tuple(lab[i] for i in b)


def drive_reduction(model, reduced):
    """Frequency error of the simplified drive reduction against the coupled drive.

    ``drive: reduced`` (Heletiy 2016, eq. 10) holds the drum in the vibration; the exact
    coupled model lets it turn. Elastic modes are paired in order. For the two-mass hoist
    the relative error of w^2 is m r^2 / (m r^2 + J) (docs/theory.md; the seed's printed
    m / (m r^2 + J) is not dimensionless).
    """
    from dataclasses import replace
    effects = replace(model.effects, drive="coupled")
    system = assemble(model, effects)
    # sparse: the coupled model's extra coordinates (the drums) may each add a rigid
    # (quasi-cyclic) mode first, so ask for that many more to pair every elastic one
    extra = system.K.shape[0] - reduced.dofs
    coupled = modes(model, effects, system=system,
                    count=None if reduced.solver == "dense" else len(reduced.omega) + extra,
                    solver=reduced.solver)
    wr = reduced.omega[~reduced.rigid]
    wc = coupled.omega[~coupled.rigid][:len(wr)]
    idx = np.flatnonzero(~reduced.rigid)[:len(wc)]
    return {"modes": [{"index": int(i + 1), "frequency_hz_coupled": float(c / (2 * np.pi)),
                       "relative_error": float(r / c - 1)}
                      for i, r, c in zip(idx, wr, wc)],
            "coupled_quasi_cyclic": list(coupled.quasi_cyclic)}
