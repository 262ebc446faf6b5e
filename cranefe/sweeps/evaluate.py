"""One variant of a sweep, computed in whatever process runs it.

Each analysis runs only if an output asks for it (modes, damping, a transient, the
luffing laws named in the outputs). Work that depends only on the model's structure is
reused across the variants a process runs (`cranefe.assembly.reuse.Reuse`: DOF maps and the
static null space); `cranefe study sweeps` measures the gain.
"""

import time
from functools import cached_property

import numpy as np

from ..assembly.reuse import Reuse

REUSE = Reuse()          # one per process: a worker keeps it across its chunks


class Variant:
    """The analyses of one variant's model, each run when an output first needs it."""

    def __init__(self, model, outputs, count, reuse):
        self.model, self.outputs, self.count, self.reuse = model, outputs, count, reuse

    @cached_property
    def system(self):
        from ..system import assemble
        return assemble(self.model, reuse=self.reuse)

    @cached_property
    def modal(self):
        from ..analysis.modal import modes
        return modes(self.model, count=min(self.count + 6, self.system.K.shape[0]),
                     system=self.system)

    @cached_property
    def elastic(self):
        return self.modal.omega[~self.modal.rigid]

    @cached_property
    def damping(self):
        from ..analysis.damping import modal_damping_ratios
        return modal_damping_ratios(self.system, self.modal)[~self.modal.rigid]

    @cached_property
    def transient(self):
        from ..analysis.transient.integrate import simulate
        return simulate(self.model, reuse=self.reuse)

    @cached_property
    def luffing(self):
        from ..analysis.luffing.analysis import law_figures
        laws = {o.split(".")[1] for o in self.outputs if o.startswith("luffing.")}
        return law_figures(self.model, sorted(laws))

    @cached_property
    def loads(self):
        from ..analysis.loads.analysis import loads
        only = {o.split(".")[-1] for o in self.outputs if o.startswith("factors.")}
        return loads(self.model, only=sorted(only))

    def value(self, name):
        """The output `name` (grammar: cranefe.sweeps.spec.OUTPUT)."""
        kind, _, arg = name.partition(".")
        if kind == "factors":
            f, _, drive = arg.partition(".")
            p = self.loads.factors[f]
            return (p[drive] if drive else p)["value"]
        if kind == "dofs":
            return self.modal.dofs
        if kind in ("phi2", "rope_force_max"):
            k = self.transient.rope_names.index(arg)
            return (self.transient.dynamic_factor if kind == "phi2"
                    else self.transient.rope_force_max)[k]
        if kind == "luffing":
            law, figure = arg.split(".")
            return self.luffing[law][figure]
        k = int(arg) - 1                       # the K-th elastic mode
        if k >= len(self.elastic):
            from ..errors import AnalysisError
            every = len(self.modal.omega) >= self.system.K.shape[0]
            raise AnalysisError(
                f"output {name}: this variant has {'only ' if every else ''}"
                f"{len(self.elastic)} elastic mode(s)"
                + ("" if every else f" among the {len(self.modal.omega)} computed; raise "
                   "'modes:' in the sweep file"))
        if kind == "damping_ratio":
            return self.damping[k]
        w = self.elastic[k]
        return {"omega": w, "frequency_hz": w / (2 * np.pi), "period_s": 2 * np.pi / w}[kind]


def evaluate(job):
    """job = (raw, parameters, outputs, modes, reuse, index, values) -> result dict."""
    from ..errors import AnalysisError, ModelError
    from ..model import build
    from .spec import apply
    raw, parameters, outputs, count, reuse, index, values = job
    t0 = time.perf_counter()
    try:
        model = build(*apply(raw, parameters, values))
        if model.analysis.get("type") == "loads":      # the working point (radius, hook
            from ..analysis.loads.runs import placed    # height) for every output
            from ..analysis.loads.scene import parse
            model = placed(model, parse(model))
        variant = Variant(model, outputs, count, REUSE if reuse else None)
        out = [float(variant.value(o)) for o in outputs]
        return {"index": index, "values": list(map(float, values)), "outputs": out,
                "status": "ok", "error": "", "seconds": time.perf_counter() - t0}
    except (ModelError, AnalysisError) as exc:
        message = str(exc)
    except Exception as exc:            # a variant's failure is recorded, not fatal
        message = f"{type(exc).__name__}: {exc}"
    return {"index": index, "values": list(map(float, values)),
            "outputs": [np.nan] * len(outputs), "status": "error", "error": message,
            "seconds": time.perf_counter() - t0}
