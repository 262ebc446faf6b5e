"""The sweep file (docs/sweeps.md) and the variants it asks for."""

import copy
import itertools
import math
import json
import os
import re
from dataclasses import dataclass

import numpy as np

from ..errors import ModelError
from ..model import units
from ..model.load import _Reader, read_raw
from ..model.yamlio import read_yaml
from ..outpaths import inside, named_path

SWEEP_KEYS = {"cranefe", "sweep", "base", "parameters", "sampling", "outputs", "modes",
              "output"}
OUTPUT = re.compile(r"^(frequency_hz|omega|period_s|damping_ratio)\.([1-9][0-9]*)$|^dofs$"
                    r"|^(phi2|rope_force_max)\.[A-Za-z0-9_-]+$|^luffing\.\w+\.\w+$"
                    r"|^factors\.phi[1236]$|^factors\.phi5\.[A-Za-z0-9_-]+$")
# outputs that need a scene of this analysis type as the base
NEEDS = {"phi2": "transient", "rope_force_max": "transient", "luffing": "luffing",
         "factors": "loads"}


MAX_VARIANTS = 1_000_000     # variants of one sweep, checked before any is made


@dataclass(frozen=True)
class Parameter:
    name: str                 # the path as written, "ropes.hoist.EA"
    path: tuple               # keys (ints index lists)
    scene: bool = False       # the path is in the scene file (else in the model file)
    values: tuple = None      # explicit values, or
    low: float = None         # a range
    high: float = None
    count: int = None         # grid points of a range
    log: bool = False


@dataclass(frozen=True)
class Sweep:
    name: str
    file: str
    text: str
    raw: tuple                # read_raw() of the base: (model_data, file, text, scene, file)
    parameters: tuple
    variants: np.ndarray      # (n, p) parameter values of every variant
    outputs: tuple
    modes: int                # modes computed per variant
    output: str               # HDF5 table path
    inputs: tuple = ()        # (what, path) of every file the sweep reads
    digest: dict = None       # {"digest": sha256 of all, "files": {path: sha256}}


def load_sweep(path):
    file = str(path)
    data, text = read_yaml(path)
    r = _Reader(file)
    if not isinstance(data, dict):
        r.fail(None, "a sweep file is a mapping that starts with 'cranefe: 1'")
    r.keys(data, "", SWEEP_KEYS, required=("cranefe", "base", "parameters", "outputs"))
    r.version(data)
    folder = os.path.dirname(os.path.abspath(file))
    base = data["base"]
    if not isinstance(base, str) or not base:
        r.fail("base", f"must be the path of the base model or scene relative to the "
               f"sweep file, not {base!r}")
    full = named_path(base, file, "base", "base model or scene")
    if not os.path.isfile(full):
        r.fail("base", f"base model or scene {base!r} not found; give its path relative "
               "to the sweep file")
    raw = read_raw(full)
    params = tuple(_parameter(name, spec, raw, r)
                   for name, spec in r.mapping(data["parameters"], "parameters").items())
    if not params:
        r.fail("parameters", "name at least one parameter, e.g. ropes.hoist.EA: "
               "{values: [1.0e7, 2.0e7]}")
    outputs = tuple(r.listing(data["outputs"], "outputs", min_len=1))
    for k, o in enumerate(outputs):
        _output(o, f"outputs[{k}]", raw, r)
    needed = max([int(o.split(".")[1]) for o in outputs
                  if "." in o and o.split(".")[1].isdigit()] + [1])
    modes = r.integer(data.get("modes", needed), "modes", minimum=needed)
    variants = _variants(params, data.get("sampling", {"method": "grid"}), r)
    out = data.get("output", os.path.splitext(os.path.basename(file))[0] + ".h5")
    if not isinstance(out, str) or not out.strip():
        r.fail("output", "must be the path of the HDF5 table to write")
    output = os.path.join(folder, out)
    if os.path.isabs(out) or not inside(output, folder):
        r.fail("output", f"{out!r} is outside the sweep file's folder; a sweep writes its "
               "table in or below its own folder (docs/sweeps.md): give a relative path "
               "such as results/table.h5")
    inputs = input_files(file, raw)
    return Sweep(str(data.get("sweep", os.path.basename(file))), file, text, raw, params,
                 variants, outputs, modes, output, inputs, digest(inputs))


def input_files(file, raw):
    """(what, path) of every file a sweep reads: the sweep file, the base model, the
    scene and the members' mesh files."""
    files = [("the sweep file", os.path.abspath(file)),
             ("the base model", os.path.abspath(raw[1]))]
    if raw[4] is not None:
        files.append(("the base scene", os.path.abspath(raw[4])))
    members = raw[0].get("members") if isinstance(raw[0].get("members"), dict) else {}
    for name, m in members.items():
        if isinstance(m, dict) and isinstance(m.get("mesh"), str):
            files.append((f"the mesh file of member {name}",
                          named_path(m["mesh"], raw[1], f"members.{name}.mesh",
                                     "mesh file")))
    return tuple(files)


def digest(inputs):
    """SHA-256 of every input file (and of them all): what a journal is keyed to."""
    import hashlib
    folder = os.path.dirname(inputs[0][1])     # the sweep file's: keys survive a move
    files = {}
    for _, path in inputs:
        h = hashlib.sha256()
        try:
            with open(path, "rb") as fh:
                for block in iter(lambda: fh.read(1 << 20), b""):
                    h.update(block)
        except OSError:
            h.update(b"(unreadable)")
        files[os.path.relpath(path, folder)] = h.hexdigest()
    total = hashlib.sha256(json.dumps(files, sort_keys=True).encode()).hexdigest()
    return {"digest": total, "files": files}


def _output(o, entry, raw, r):
    """Check an output name against what the base can compute."""
    if not isinstance(o, str) or not OUTPUT.match(o):
        r.fail(entry, f"unknown output {o!r}; use frequency_hz.K, omega.K, period_s.K, "
               "damping_ratio.K (K = 1 for the first elastic mode), dofs; with a transient "
               "scene as base phi2.ROPE, rope_force_max.ROPE; with a luffing scene "
               "luffing.LAW.FIGURE; with a loads scene factors.phi1, factors.phi2, "
               "factors.phi3, factors.phi6, factors.phi5.DRIVE (docs/sweeps.md)")
    kind, _, arg = o.partition(".")
    if kind not in NEEDS:
        return
    scene = raw[3] or {}
    analysis = scene.get("analysis") if isinstance(scene.get("analysis"), dict) else {}
    if analysis.get("type") != NEEDS[kind]:
        r.fail(entry, f"{o} needs a {NEEDS[kind]} scene as the base (one with "
               f"'analysis: {{type: {NEEDS[kind]}, ...}}'); the base is "
               + (f"a {analysis.get('type', 'modes')} scene" if raw[3] else "a model file"))
    if kind == "factors":
        return
    if kind == "luffing":
        from ..analysis.luffing.analysis import ALL_LAWS, FIGURES
        law, _, figure = arg.partition(".")
        if law not in ALL_LAWS:
            r.fail(entry, f"unknown law {law!r}; the laws are {', '.join(ALL_LAWS)}")
        if figure not in FIGURES:
            r.fail(entry, f"unknown figure {figure!r} of a law; use one of "
                   f"{', '.join(FIGURES)}")
    else:
        ropes = raw[0].get("ropes") if isinstance(raw[0].get("ropes"), dict) else {}
        if arg not in ropes:
            r.fail(entry, f"the model has no rope '{arg}'; its ropes: "
                   f"{', '.join(map(str, ropes)) or 'none'}")


MISSING = object()


def _walk(data, path):
    """The value at `path` in raw YAML data, or MISSING."""
    for key in path:
        if not ((isinstance(data, dict) and key in data) or
                (isinstance(data, list) and isinstance(key, int) and key < len(data))):
            return MISSING
        data = data[key]
    return data


def _locate(path, raw):
    """(in the scene?, the value addressed) of a parameter's path, or None.

    With a scene as the base, 'analysis...' is in the scene, 'effects...' in the scene
    when the scene sets it (its effects override the model's), all else in the model."""
    if raw[3] is not None and path[0] in ("analysis", "effects"):
        value = _walk(raw[3], path)
        if value is not MISSING:
            return True, value
        if path[0] == "analysis":
            return None
    value = _walk(raw[0], path)
    return None if value is MISSING else (False, value)


def _parameter(name, spec, raw, r):
    e = f"parameters.{name}"
    path = tuple(int(p) if p.isdigit() else p for p in name.split("."))
    found = _locate(path, raw)
    if found is None:
        r.fail(e, f"the base {'scene' if raw[3] is not None else 'model'} has no "
               f"'{name}'; a parameter is a path into the model file, e.g. ropes.hoist.EA "
               "or masses.B (with a scene as the base also analysis... and effects...)")
    in_scene, target = found
    quantity = isinstance(target, str) and units.has_unit(target)   # '110 MN' in the base
    if isinstance(target, bool) or not (isinstance(target, (int, float)) or quantity):
        r.fail(e, f"addresses {type(target).__name__} {target!r}, not a number; address "
               "the number itself (e.g. masses.B.mass)")
    r.keys(spec, e, {"values", "range", "count", "scale"})
    if "values" in spec:
        vals = r.listing(spec["values"], f"{e}.values", min_len=1)
        return Parameter(name, path, in_scene, tuple(_value(v, f"{e}.values[{i}]", name,
                                                            raw, r)
                                                     for i, v in enumerate(vals)))
    if "range" not in spec:
        r.fail(e, "give 'values: [...]' or 'range: [low, high]' (with 'count' for a grid)")
    rng = r.listing(spec["range"], f"{e}.range", min_len=2)
    lo, hi = (_value(rng[k], f"{e}.range[{k}]", name, raw, r) for k in (0, 1))
    if len(rng) != 2 or not lo < hi:
        r.fail(f"{e}.range", "must be [low, high] with low < high")
    log = spec.get("scale", "linear") == "log"
    if spec.get("scale", "linear") not in ("linear", "log") or (log and lo <= 0):
        r.fail(f"{e}.scale", "is linear or log (log needs a positive range)")
    count = r.integer(spec["count"], f"{e}.count", minimum=1, maximum=MAX_VARIANTS,
                      why=": variants of one sweep") if "count" in spec else None
    return Parameter(name, path, in_scene, None, lo, hi, count, log)


def _value(v, entry, name, raw, r):
    """A parameter's value in SI: a number, or a quantity (`40 m/min`, `110 MN`) read by
    the model files' units machinery (cranefe.model.units) for the entry the parameter
    sets (a drum's `speed` also as a rope speed, by the drum's radius in the base)."""
    if isinstance(v, str) and units.has_unit(v):
        drums = {}
        for dname, d in (raw[0].get("drums") or {}).items() if isinstance(raw[0], dict) \
                else ():
            radius = d.get("radius") if isinstance(d, dict) else None
            if isinstance(radius, str) and units.has_unit(radius):
                radius = units.convert(radius, f"drums.{dname}.radius", raw[1])
            if isinstance(radius, (int, float)) and not isinstance(radius, bool):
                drums[dname] = float(radius)
        try:
            v = units.convert(v, name, r.file, drums=drums)
        except ModelError as exc:
            raise ModelError(f"{exc.message} (the unit of {name})", r.file, entry) from None
    return r.number(v, entry)


def _grid(p):
    if p.values is not None:
        return np.array(p.values)
    if p.count is None:
        raise ValueError(p.name)
    return np.geomspace(p.low, p.high, p.count) if p.log else \
        np.linspace(p.low, p.high, p.count)


def _variants(params, sampling, r):
    r.keys(sampling, "sampling", {"method", "samples", "seed"})
    method = sampling.get("method", "grid")
    if method == "grid":
        for p in params:
            if p.values is None and p.count is None:
                r.fail(f"parameters.{p.name}", "a grid needs 'count' with a range")
        sizes = [len(p.values) if p.values is not None else p.count for p in params]
        if math.prod(sizes) > MAX_VARIANTS:
            r.fail("parameters", f"the grid has {' x '.join(map(str, sizes))} = "
                   f"{math.prod(sizes):,} variants, more than the limit of {MAX_VARIANTS:,}; "
                   "use fewer points or sampling: {method: lhs, samples: N}")
        return np.array(list(itertools.product(*(_grid(p) for p in params))), dtype=float)
    if method not in ("random", "lhs"):
        r.fail("sampling.method", f"{method!r} is not grid, random or lhs")
    n = r.integer(sampling.get("samples", 100), "sampling.samples", minimum=1,
                  maximum=MAX_VARIANTS, why=": variants of one sweep")
    seed = r.integer(sampling.get("seed", 0), "sampling.seed", minimum=0)
    if method == "random":
        u = np.random.default_rng(seed).random((n, len(params)))
    else:
        from scipy.stats import qmc
        u = qmc.LatinHypercube(d=len(params), seed=seed).random(n)
    cols = []
    for k, p in enumerate(params):
        if p.values is not None:         # choose among the values
            cols.append(np.array(p.values)[np.minimum((u[:, k] * len(p.values)).astype(int),
                                                      len(p.values) - 1)])
        elif p.log:
            cols.append(np.exp(np.log(p.low) + u[:, k] * np.log(p.high / p.low)))
        else:
            cols.append(p.low + u[:, k] * (p.high - p.low))
    return np.column_stack(cols)


def apply(raw, parameters, values):
    """A copy of `read_raw`'s data of the base with each parameter set to its value."""
    model, scene = copy.deepcopy(raw[0]), copy.deepcopy(raw[3])
    for p, v in zip(parameters, values):
        target = scene if p.scene else model
        for key in p.path[:-1]:
            target = target[key]
        target[p.path[-1]] = float(v)
    return (model, raw[1], raw[2], scene, raw[4])
