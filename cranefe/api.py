"""The Python API: the command line's analyses as functions for notebooks and scripts.

Each takes a model (a `Model` from `load`, or the path of a model or scene file) and
returns a result dataclass with named fields whose ``to_dict()`` is the document the
matching ``cranefe COMMAND --json`` prints (docs/api.md). Nothing here prints; errors are
`cranefe.errors.ModelError` (bad input) and `AnalysisError` (failed computation).
"""

import os
import time
from dataclasses import replace

__all__ = ["load", "modes", "damping", "simulate", "luff", "sweep", "loads"]


def load(path):
    """The checked, frozen `Model` of a model or scene file (model-format.md)."""
    from .model import load as _load
    return _load(os.fspath(path))


def _model(model, effects=None):
    """A Model from a Model or a path, with `effects` (a dict) changed if given."""
    if not hasattr(model, "effects"):
        model = load(model)
    if effects:
        model = replace(model, effects=replace(model.effects, **effects))
    return model


def modes(model, count=None, solver="auto", effects=None):
    """Natural frequencies and mass-normalised modes -> `ModalResult`.

    count : modes to report (default: the scene's count, else all for small models and
        10 for large ones); solver : 'auto' | 'dense' | 'sparse'; effects : a dict of
        effects to change, e.g. ``{"sway": False, "rope_mass": 8}``.
    With ``drive: reduced`` the result carries the comparison with the coupled drive.
    """
    from .analysis.modal import drive_reduction
    from .analysis.modal import modes as _modes
    from .system import assemble
    t0 = time.perf_counter()
    model = _model(model, effects)
    count = count or model.analysis.get("count")
    result = _modes(model, count=count, solver=solver, system=assemble(model))
    if model.effects.drive == "reduced":
        result.drive_reduction = drive_reduction(model, result)
    result.timings["total"] = time.perf_counter() - t0
    return result


def damping(model, method=None, count=None, effects=None):
    """Damping ratios from the elements' absorption coefficients -> `DampingResult`.

    method : 'modal' | 'exact' | 'both' | 'auto' (default: the scene's, else 'auto');
    count : modes to report (coupling partners beyond them are computed as well).
    """
    from .analysis.damping import damping as _damping
    from .analysis.damping import partner_modes, scene_method
    from .system import assemble
    model = _model(model, effects)
    system = assemble(model)
    modal, shown = partner_modes(model, system, count or model.analysis.get("count"))
    return _damping(model, method or scene_method(model), shown, system=system,
                    modal=modal)


def simulate(scene, progress=None):
    """Integrate a scene, as `cranefe simulate` does: a transient scene (``analysis: {type:
    transient}``) -> `TransientResult` (time histories, peak rope forces, dynamic factors,
    energy balance); an operation scene (``type: operation``, large motions;
    docs/operations.md) -> `OperationResult`."""
    model = _model(scene)
    if model.analysis.get("type") == "operation":
        from .analysis.operation.integrate import simulate as _operation
        return _operation(model, progress=progress)
    from .analysis.transient.integrate import simulate as _simulate
    return _simulate(model, progress=progress)


def luff(scene, sensitivity=True):
    """Energy-optimal luffing of a level-luffing jib (``analysis: {type: luffing}``)
    -> `LuffingResult` (docs/luffing.md)."""
    from .analysis.luffing.analysis import analyse
    model = _model(scene)
    return analyse(model, file=model.scene_file or model.file, sensitivity=sensitivity)


def sweep(spec, workers=None, scheduler=None, reuse=True):
    """Run (or resume) the parameter sweep of a sweep file -> `SweepRun` (its table in
    ``.table``). workers : None = all cores, 0 = serial; scheduler : a Dask address."""
    from .sweeps.engine import run_sweep
    from .sweeps.spec import load_sweep
    from .sweeps.summary import summarise
    s = load_sweep(os.fspath(spec))
    return summarise(s, run_sweep(s, workers=workers, scheduler=scheduler, reuse=reuse))


def loads(model, only=None, shapers=()):
    """Dynamic factors of EN 13001-2 from simulations of the crane (a model, a transient
    scene or a loads scene, ``analysis: {type: loads}``) -> `LoadsResult`, whose
    ``to_dict()`` is ``cranefe loads --json`` (docs/loads.md). only : factor or drive
    names (``["phi2"]``, ``["trolley_travel"]``) to run just the simulations they need.
    shapers : e.g. ``("ZV", "ZVD")``: every trolley, slewing and luffing move also run
    shaped, ``to_dict()["shapers"]`` (docs/shaping.md)."""
    from .analysis.loads.analysis import loads as _loads
    return _loads(_model(model), only=only, shapers=shapers)
