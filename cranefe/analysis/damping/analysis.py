"""The damping analysis of a model: modes, decoupled estimate, exact solutions where
asked or where the coupling criterion fails, and warnings."""

import time

import numpy as np

from ...errors import ModelError

from .constants import ERROR_TOL, EXTRA_MODES, KAPPA, METHODS, PARTNER_SPAN
from .exact import exact_hysteretic, exact_viscous
from .modal import modal_damping
from .result import DampingResult, _log_decrement


def scene_method(model):
    """The method a scene asks for: analysis.method, else effects.damping, else auto."""
    method = model.analysis.get("method")
    if method is not None:
        if method not in METHODS:
            raise ModelError(f"{method!r} is not one of {', '.join(METHODS)}",
                             model.scene_file or model.file, "analysis.method")
        return method
    return {"modal": "modal", "exact": "exact"}.get(model.effects.damping, "auto")


def _check_method(method, count):
    if method not in METHODS:
        raise ModelError(f"damping method {method!r}: use one of {', '.join(METHODS)}",
                         None, "method")
    if count is not None and count < 1:
        raise ModelError(f"count {count}: ask for at least one mode", None, "count")


def damping(model, method="auto", count=None, system=None, modal=None):
    """Damping of the modes of `model` from its elements' absorption coefficients.

    method : 'modal' (decoupled estimate only), 'exact' or 'both' (also the exact
        viscous and complex-stiffness solutions of every damped mode), 'auto' (the
        estimate, and the exact solutions of the modes it cannot be trusted for).
    count : modes to report (rigid ones included, as `cranefe modes --count`); more
        are computed as coupling partners (`partner_modes`).
    system, modal : an assembled System and its ModalResult, if already at hand (then
        the first `count` of its modes are reported, all if None).
    """
    from ...system import assemble
    _check_method(method, count)
    t0 = time.perf_counter()
    system = system or assemble(model)
    t1 = time.perf_counter()
    if modal is None:
        modal, shown = partner_modes(model, system, count)
    else:
        shown = len(modal.omega) if count is None else count
    t2 = time.perf_counter()
    mtot = len(modal.omega)
    m = min(shown, mtot)
    el = np.flatnonzero(~modal.rigid)             # elastic positions among all modes
    md = modal_damping(system, modal, predict=np.flatnonzero(el < m))
    t3 = time.perf_counter()

    def full(values, fill=0.0):
        out = np.full(mtot, fill, dtype=float)
        out[el] = values
        return out[:m]

    eps = np.zeros((mtot, mtot))
    eps[np.ix_(el, el)] = md.coupling
    partner = np.where(eps.max(axis=1) > 0, np.argmax(eps, axis=1), -1)[:m]
    Dfull = np.zeros((mtot, mtot))
    Dfull[np.ix_(el, el)] = md.D
    zeta = full(md.zeta)
    top = np.argmax(md.shares, axis=1) if md.shares.size else np.zeros(len(el), int)
    share = md.shares[np.arange(len(el)), top] if md.shares.size else np.zeros(len(el))
    names = np.full(mtot, "", dtype=object)
    names[el] = [md.element_names[t] if s > 0 else "" for t, s in zip(top, share)]
    rigid = modal.rigid[:m].copy()
    result = DampingResult(
        model.name, system.effects.as_dict(), method, modal.omega[:m].copy(), rigid,
        zeta, full(md.damped_omega), np.where(rigid, np.nan, _log_decrement(zeta)),
        eps.max(axis=1)[:m], partner, eps[:m, :m], full(md.predicted_error),
        Dfull[:m, :m], tuple(str(x) for x in names[:m]), full(share),
        dofs=modal.dofs, quasi_cyclic=tuple(modal.quasi_cyclic),
        timings={"assemble": t1 - t0, "modes": t2 - t1, "decoupled": t3 - t2},
        warnings=list(modal.warnings))

    psi_any = np.any(system.springs.psi * system.springs.c > 0) or (
        system.beams is not None and np.any(system.beam_psi > 0))
    stiff_less = sorted(set(n for n, p, c in zip(system.springs.names, system.springs.psi,
                                                 system.springs.c) if p > 0 and c == 0))
    if not psi_any and stiff_less:
        result.warnings.append(f"{', '.join(stiff_less)}: psi > 0 but inextensible here "
                               "(rope_elasticity: false), so no element that deforms "
                               "absorbs energy: every damping ratio is zero")
    elif not psi_any:
        result.warnings.append("no element has an absorption coefficient psi > 0: every "
                               "damping ratio is zero (give psi on ropes, springs or "
                               "members)")
    over = np.flatnonzero(zeta >= 1)
    if over.size:
        result.warnings.append("decoupled estimate overdamped (zeta >= 1) for mode(s) "
                               + ", ".join(str(i + 1) for i in over))
    _criterion_warnings(result, method)

    _solve_exact(result, system, modal, md, el, method)
    return result


def _solve_exact(result, system, modal, md, el, method):
    """The exact viscous and complex-stiffness solutions of the modes that `method`
    asks for ('auto': those the decoupled estimate cannot be trusted for)."""
    rigid, zeta, m = result.rigid, result.zeta, len(result.omega)
    damped = ~rigid & (zeta > 0)
    if method in ("exact", "both"):
        want = damped
    elif method == "auto":
        want = damped & ~result.trusted
    else:
        want = np.zeros(m, dtype=bool)
    if method in ("exact", "both") or want.any():
        result.exact_zeta, result.exact_damped_omega = _exact_fill(result, rigid)
        result.hysteretic_zeta, result.hysteretic_damped_omega = _exact_fill(result, rigid)
    if want.any():
        idx = np.flatnonzero(want)                 # positions among all modes
        which = np.searchsorted(el, idx)          # the same modes among the elastic ones
        V = modal.shapes[:, el]
        args = (system, V, md.omega, md.zeta, md.Kpsi, md.coupling, which)
        t4 = time.perf_counter()
        ze, wd = exact_viscous(*args)
        t5 = time.perf_counter()
        zh, wh = exact_hysteretic(*args)
        t6 = time.perf_counter()
        result.exact_zeta[idx], result.exact_damped_omega[idx] = ze, wd
        result.hysteretic_zeta[idx], result.hysteretic_damped_omega[idx] = zh, wh
        result.timings.update(exact_viscous=t5 - t4, hysteretic=t6 - t5)


def partner_modes(model, system, count=None):
    """Modes for the damping analysis and how many of them to report.

    Coupling partners matter near the reported modes, so modes are kept up to
    PARTNER_SPAN times the highest reported frequency (at least EXTRA_MODES more): from
    all modes on the dense path, doubling the count on the sparse one. Reported:
    `count`, else what `cranefe modes` reports (all modes of a dense model, else 10).
    """
    from ...condense import DENSE_MAX as MODAL_DENSE_MAX
    from ..modal import SMALL, modes
    n = system.K.shape[0]
    if n <= SMALL or (count is None and n <= MODAL_DENSE_MAX):
        modal = modes(model, count=None, system=system)       # dense: all modes anyway
        if count is None or count >= len(modal.omega):
            return modal, len(modal.omega)
        w = modal.omega
        keep = max(count + EXTRA_MODES, int(np.sum(w <= PARTNER_SPAN * w[count - 1])))
        return first_modes(modal, keep), count
    want = count or 10
    k = want + EXTRA_MODES
    while True:
        modal = modes(model, count=min(k, n - 2), system=system)
        w = modal.omega
        if len(w) <= want or w[-1] >= PARTNER_SPAN * w[want - 1] or k >= n - 2:
            return modal, want
        k *= 2


def first_modes(modal, k):
    """The ModalResult of the first k modes."""
    from dataclasses import replace
    return replace(modal, omega=modal.omega[:k], shapes=modal.shapes[:, :k],
                   node_shapes=modal.node_shapes[:k], rigid=modal.rigid[:k])


def _exact_fill(result, rigid):
    """Exact arrays before solving: the decoupled values where they are exact (rigid
    and undamped modes: no element deforms, so B V_i = 0), NaN elsewhere."""
    z = np.where(rigid | (result.zeta == 0), result.zeta, np.nan)
    w = np.where(rigid | (result.zeta == 0), result.damped_omega, np.nan)
    return z, w


def _criterion_warnings(result, method):
    """Warn where Hasselman's criterion fails or the predicted error is large."""
    m = len(result.omega)
    eps = result.coupling_matrix
    pairs = [(i, j) for i, j in zip(*np.nonzero(np.triu(eps >= KAPPA))) if i < j]
    outside = [i for i in range(m) if result.coupling[i] >= KAPPA
               and result.coupled_with[i] >= m]
    then = {"auto": "; they are solved exactly",
            "modal": "; use --method exact"}.get(method, "")
    if pairs or outside:
        text = ", ".join([f"{i + 1}-{j + 1} ({eps[i, j]:.2g})" for i, j in pairs] +
                         [f"{i + 1}-{result.coupled_with[i] + 1} "
                          f"({result.coupling[i]:.2g})" for i in outside])
        result.warnings.append(
            f"Hasselman's weak-coupling criterion fails (coupling >= {KAPPA}) for modes "
            f"{text}: their decoupled damping ratios are not reliable{then}")
    loose = np.flatnonzero(result.criterion_holds &
                           (np.abs(result.predicted_error) >= ERROR_TOL))
    if loose.size:
        text = ", ".join(f"{i + 1} ({100 * result.predicted_error[i]:+.1f} %)"
                         for i in loose)
        result.warnings.append(
            f"weakly coupled, but the predicted error of the decoupled damping ratio "
            f"exceeds {100 * ERROR_TOL:g} % for mode(s) {text}{then}")
