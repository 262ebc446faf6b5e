"""Build a checked `Model` from a model or scene file (model-format.md, format 1).

Every user-facing check lives here; nothing downstream re-validates input. Each error
names the file, the entry (``ropes.hoist.path[2]``) and what to change.
"""

import difflib
import itertools
import math
import os
from dataclasses import dataclass

import numpy as np

from ..errors import ModelError
from . import ropes_data, units
from ..outpaths import named_path, note_read
from .sections import OPTIONAL, SHAPES, profile_shape, section_moduli, section_properties
from .model import (EFFECT_CHOICES, GROUND, Body, Drum, Effects, Joint, LinearDrive,
                    Member, Model, PointMasses, Rope, Spring, Support)
from .yamlio import read_yaml

MODEL_KEYS = {"cranefe", "name", "plane", "gravity", "nodes", "ground", "supports", "masses",
              "bodies", "joints", "springs", "drums", "ropes", "members",
              "linear_drives", "effects"}
SCENE_KEYS = {"cranefe", "scene", "model", "effects", "analysis"}
JOINT_TYPES = ("fixed", "hinge", "ball", "slider")
# Limits on what a file can ask for, checked before anything is allocated
# (docs/model-format.md, "Checks and exit status"; docs/security.md)
MAX_FALLS = 1000              # parallel falls of one tackle (real ones have up to ~30)
MAX_ROPE_ELEMENTS = 10_000    # rope_mass: elements per fall
MAX_ROPE_ELEMENTS_TOTAL = 2_000_000   # rope_mass x every fall of every rope with mass
# Magnitudes a number in a file may have: products and quotients of a few of them stay
# far inside double precision (1e308), so no inf or 0 appears in the arrays.
MIN_NUMBER, MAX_NUMBER = 1e-60, 1e60
ANALYSIS_TYPES = ("modes", "damping", "transient", "luffing", "operation", "loads")


def load(path, text=None):
    """Load a model file or a scene file (which names a model) into a `Model`."""
    return build(*read_raw(path, text))


def read_raw(path, text=None):
    """The checked-as-YAML data of a model or scene file, before it becomes a `Model`:
    ``(model_data, model_file, model_text, scene_data, scene_file)``, the last two None
    for a model file. `build` turns them (possibly edited, as sweeps do) into a Model."""
    file = str(path)
    data, text = read_yaml(path, text)
    r = _Reader(file)
    if not isinstance(data, dict):
        raise ModelError(f"the file holds {_kind(data)}, but a model file is a mapping of "
                         "keys that starts with 'cranefe: 1'", file)
    if not _is_scene(data):
        return data, file, text, None, None
    r.keys(data, "", SCENE_KEYS)
    r.version(data)
    if "model" not in data:
        r.fail("model", "a scene names its model: add 'model: PATH' (relative to the scene "
               "file)")
    model_path = data["model"]
    if not isinstance(model_path, str) or not model_path:
        raise ModelError("must be the path of a model file, relative to the scene file",
                         file, "model")
    full = named_path(model_path, file, "model", "model file")
    if os.path.isdir(full):
        r.fail("model", f"'{model_path}' is a directory ({full}); name a model file")
    if not os.path.isfile(full):
        raise ModelError(f"model file '{model_path}' not found (looked for {full}); "
                         "the path is relative to the scene file", file, "model")
    mdata, mtext = read_yaml(full)
    if _is_scene(mdata):
        r.fail("model", f"'{model_path}' is a scene, not a model file; name the model file "
               "itself")
    if not isinstance(mdata, dict):
        raise ModelError(f"the file holds {_kind(mdata)}, but a model file is a mapping of "
                         "keys that starts with 'cranefe: 1'", full)
    return mdata, full, mtext, data, file


def build(model_data, model_file, model_text="", scene_data=None, scene_file=None):
    """A checked `Model` from raw data (see `read_raw`)."""
    model = _build_model(model_data, model_file, model_text, _Reader(model_file))
    if scene_data is None:
        _check_size(model, model_file)
        return model
    r = _Reader(scene_file)
    effects = _effects(scene_data.get("effects"), model.effects, r, "effects")
    analysis = _analysis(scene_data.get("analysis", {}), r)
    scene = scene_data.get("scene")
    if isinstance(scene, (dict, list)):
        r.fail("scene", f"must be the scene's name (text), not {_kind(scene)}")
    model = _replace(model, effects=effects, analysis=analysis, scene_file=scene_file,
                     scene=str(scene) if scene is not None else os.path.basename(scene_file))
    _check_size(model, scene_file if "effects" in scene_data else model_file)
    return model


def _check_size(model, file):
    """Rope elements asked for (rope_mass x every fall of every rope with mass) are
    bounded before any is made."""
    n = model.effects.rope_mass
    if n:
        falls = sum(int(r.falls.sum()) for r in model.ropes if r.mass_per_length > 0)
        if n * falls > MAX_ROPE_ELEMENTS_TOTAL:
            raise ModelError(
                f"rope_mass: {n} elements per fall on {falls} falls make {n * falls:,} rope "
                f"elements, more than the limit of {MAX_ROPE_ELEMENTS_TOTAL:,}; ask for fewer "
                "elements per fall", file, "effects.rope_mass")


def _is_scene(data):
    return isinstance(data, dict) and ("scene" in data or "model" in data)


def _replace(model, **kw):
    from dataclasses import replace
    return replace(model, **kw)


def _analysis(a, r):
    if not isinstance(a, dict):
        raise ModelError("must be a mapping such as {type: modes, count: 10}", r.file,
                         "analysis")
    kind = a.get("type", "modes")
    if kind not in ANALYSIS_TYPES:
        raise ModelError(f"unknown analysis type {kind!r}; use one of "
                         f"{', '.join(ANALYSIS_TYPES)}", r.file, "analysis.type")
    out = dict(a, type=kind)
    if kind in ("modes", "damping"):
        r.keys(a, "analysis", {"type", "count", "method"})
        if "count" in a:
            out["count"] = r.integer(a["count"], "analysis.count", minimum=1)
    return out


def _effects(raw, base, r, entry):
    if raw is None:
        return base
    if not isinstance(raw, dict):
        raise ModelError("must be a mapping such as {sway: false}", r.file, entry)
    r.keys(raw, entry, set(Effects.__dataclass_fields__))
    values = base.as_dict()
    for key, value in raw.items():
        e = f"{entry}.{key}"
        if key in ("rope_elasticity", "sway"):
            values[key] = r.boolean(value, e)
        elif key == "rope_mass":
            values[key] = r.integer(value, e, minimum=0, maximum=MAX_ROPE_ELEMENTS,
                                    why=": elements per fall of every rope with mass")
        else:
            if value not in EFFECT_CHOICES[key]:
                raise ModelError(f"{_echo(value)} is not one of {', '.join(EFFECT_CHOICES[key])}",
                                 r.file, e)
            values[key] = value
    return Effects(**values)


class _Reader:
    """Typed access to raw YAML values with messages that name the entry."""

    def __init__(self, file, drums=None):
        self.file = file
        self.drums = drums or {}      # drum name -> radius: rope speeds of scenes

    def fail(self, entry, message):
        raise ModelError(message, self.file, entry or None)

    def version(self, data):
        if "cranefe" not in data:
            self.fail("cranefe", "missing the format version; start the file with "
                      "'cranefe: 1'")
        v = data["cranefe"]
        if isinstance(v, bool) or v != 1:
            self.fail("cranefe", f"format version must be 1 (found {_echo(v)}); this cranefe "
                      "reads format 1: start the file with 'cranefe: 1'")

    def keys(self, d, entry, allowed, required=()):
        if not isinstance(d, dict):
            self.fail(entry, f"must be a mapping, not {_kind(d)}")
        for k in d:
            if k not in allowed:
                close = difflib.get_close_matches(str(k), sorted(allowed), n=1)
                hint = f"did you mean '{close[0]}'? " if close else ""
                self.fail(f"{entry}.{k}" if entry else str(k),
                          f"unknown key {k!r}; {hint}allowed here: "
                          f"{', '.join(sorted(allowed))}")
        for k in required:
            if k not in d:
                self.fail(entry, f"missing required key '{k}'; add it")

    def number(self, v, entry, positive=False, nonneg=False, unit=None):
        """A finite float; text with a unit ('110 MN') in the SI unit of `entry`
        (cranefe.model.units; `unit` overrides its table)."""
        if isinstance(v, str) and units.has_unit(v):
            v = units.convert(v, entry, self.file, unit, drums=self.drums)
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            hint = "; write a plain number in SI units, e.g. 2.0e7, without quotes, or " \
                "a number with its unit, e.g. '110 MN'" if isinstance(v, str) else ""
            self.fail(entry, f"must be a number, not {_kind(v)} {_echo(v)}{hint}")
        v = math.inf if isinstance(v, int) and abs(v) > MAX_NUMBER else float(v)
        if not math.isfinite(v) or not (v == 0 or MIN_NUMBER <= abs(v) <= MAX_NUMBER):
            self.fail(entry, f"must be a finite number of magnitude {MIN_NUMBER:g} .. "
                      f"{MAX_NUMBER:g} (or 0), not {v:g}; give its value in SI units")
        if positive and v <= 0:
            self.fail(entry, f"must be positive (found {v:g}); give a value > 0")
        if nonneg and v < 0:
            self.fail(entry, f"must not be negative (found {v:g}); give a value >= 0")
        return v

    def integer(self, v, entry, minimum=None, maximum=None, why=""):
        """A whole number in [minimum, maximum]; `why` says what the maximum bounds."""
        if isinstance(v, bool) or not isinstance(v, int):
            if isinstance(v, float) and v.is_integer():
                v = int(v)
            else:
                self.fail(entry, f"must be a whole number, not {_kind(v)} {_echo(v)}")
        if minimum is not None and v < minimum:
            self.fail(entry, f"must be at least {minimum} (found {v})")
        if maximum is not None and v > maximum:
            self.fail(entry, f"must be at most {maximum:,} (found {_short(v)}){why}")
        return v

    def boolean(self, v, entry):
        if not isinstance(v, bool):
            self.fail(entry, f"must be true or false, not {_echo(v)}")
        return v

    def vector(self, v, entry, n=3):
        if not isinstance(v, (list, tuple)) or len(v) != n:
            self.fail(entry, f"must be a list of {n} numbers, not {_echo(v)}")
        return np.array([self.number(x, f"{entry}[{i}]") for i, x in enumerate(v)])

    def unit(self, v, entry):
        a = self.vector(v, entry)
        n = np.linalg.norm(a)
        if n == 0:
            self.fail(entry, "axis must not be the zero vector")
        return a / n

    def name(self, v, entry):
        if not isinstance(v, str) or not v:
            self.fail(entry, f"must be a name (text), not {_kind(v)} {_echo(v)}")
        return v

    def listing(self, v, entry, min_len=0):
        if not isinstance(v, list):
            self.fail(entry, f"must be a list, not {_kind(v)}")
        if len(v) < min_len:
            self.fail(entry, f"must list at least {min_len} entries")
        return v

    def mapping(self, v, entry):
        if v is None:
            return {}
        if not isinstance(v, dict):
            self.fail(entry, f"must be a mapping of names to entries, not {_kind(v)}")
        for k in v:
            if not isinstance(k, str):
                self.fail(entry, f"names must be text, not {_kind(k)} {k!r}")
        return v


def _short(v):
    """A number for a message, at most a few dozen characters (a 400-digit integer is
    not echoed whole)."""
    s = str(v)
    return s if len(s) <= 24 else f"{s[:6]}...({len(s)} digits)"


def _echo(v):
    """A value for a message, at most a few dozen characters: a wrong value is shown,
    not a whole megabyte of text pasted into a number."""
    r = repr(v)
    return r if len(r) <= 60 else f"{r[:40]}... ({len(r)} characters)"


def _kind(v):
    return {dict: "a mapping", list: "a list", str: "text", bool: "a boolean",
            type(None): "nothing (null)"}.get(type(v), type(v).__name__)


class _Names:
    """One namespace per kind, with 'used as the wrong kind' messages."""

    def __init__(self, r):
        self.r = r
        self.kinds = {}       # name -> kind -> index

    def add(self, kind, name, index):
        self.kinds.setdefault(name, {})[kind] = index
        if kind == "node":
            self._node_index = None

    def add_all(self, kind, names):
        """`add` of names[i] as index i, for each i."""
        kinds = self.kinds
        for i, name in enumerate(names):
            kinds.setdefault(name, {})[kind] = i
        if kind == "node":
            self._node_index = None

    def node_index(self):
        """name -> node index of every node (built once while no node is added)."""
        if getattr(self, "_node_index", None) is None:
            self._node_index = {n: ks["node"] for n, ks in self.kinds.items() if "node" in ks}
        return self._node_index

    def get(self, name, kinds, entry):
        kinds = (kinds,) if isinstance(kinds, str) else kinds
        if not isinstance(name, str):
            self.r.fail(entry, f"must name a {' or '.join(kinds)}, not {_kind(name)} {name!r}")
        found = self.kinds.get(name, {})
        for k in kinds:
            if k in found:
                return k, found[k]
        if found:
            other = ", ".join(found)
            self.r.fail(entry, f"'{name}' is a {other}, not a {' or '.join(kinds)}")
        known = sorted(n for n, ks in self.kinds.items() if set(ks) & set(kinds))
        hint = f"; known: {', '.join(known[:12])}{' ...' if len(known) > 12 else ''}" \
            if known else ""
        self.r.fail(entry, f"unknown {' or '.join(kinds)} '{name}'{hint}")


@dataclass
class _Ctx:
    """What the sections of a model file share while it is read."""

    r: object
    names: object
    planar: bool
    coords: np.ndarray = None
    node_names: tuple = ()
    scale: float = 1.0
    raw: dict = None
    mesh_pairs: dict = None

    def node(self, v, entry):
        return self.names.get(v, "node", entry)[1]

    def body(self, v, entry):
        if v == "ground":
            return GROUND
        return self.names.get(v, "body", entry)[1]


def _header(data, r):
    """Keys, version, name, plane and gravity -> (planar, gravity)."""
    r.keys(data, "", MODEL_KEYS)
    r.version(data)
    if "nodes" not in data:
        r.fail("nodes", "a model needs 'nodes:' (named points, e.g. 'A: [0, 0, 0]')")
    if "name" in data and (isinstance(data["name"], (dict, list)) or data["name"] is None):
        r.fail("name", f"must be text, not {_kind(data['name'])}")
    plane = data.get("plane")
    if plane not in (None, "xz"):
        r.fail("plane", f"only 'xz' is supported (found {plane!r}); omit it for a 3D model")
    planar = plane == "xz"
    gravity = r.vector(data["gravity"], "gravity") if "gravity" in data \
        else np.array([0.0, 0.0, -9.81])
    if planar and gravity[1] != 0:
        r.fail("gravity", "a plane: xz model needs gravity with y = 0")
    return planar, gravity


def _nodes(data, c):
    """Nodes (and the points of members given as mesh files, merged with coinciding
    ones); then every name of the other sections, so that a reference to an entry further
    down the file that is of another kind says what it is ("'jib' is a body, not a
    node")."""
    r, names, planar = c.r, c.names, c.planar
    nodes = r.mapping(data["nodes"], "nodes")
    if not nodes:
        r.fail("nodes", "a model needs at least one node")
    node_names = list(nodes)
    coords = _coordinates(nodes, node_names, r)
    names.add_all("node", node_names)
    if planar and np.any(coords[:, 1] != 0):
        i = int(np.flatnonzero(coords[:, 1] != 0)[0])
        r.fail(f"nodes.{node_names[i]}", f"y = {coords[i, 1]:g} is off the plane of a "
               "plane: xz model; set y to 0 or remove 'plane: xz'")
    # members given as mesh files add their points as nodes (merged with coinciding ones)
    mesh_pairs = {}
    for mname, m in r.mapping(data.get("members"), "members").items():
        if isinstance(m, dict) and "mesh" in m:
            coords, mesh_pairs[mname] = _mesh_member(mname, m["mesh"], r, coords, node_names,
                                                     names, planar)
    c.coords, c.node_names, c.mesh_pairs = coords, tuple(node_names), mesh_pairs
    c.scale = float(np.ptp(coords, axis=0).max()) or 1.0
    # register every name first, so that a reference to an entry further down the file
    # that is of another kind says what it is ("'jib' is a body, not a node")
    c.raw = raw = {}
    for section, kind in (("bodies", "body"), ("drums", "drum"), ("ropes", "rope"),
                          ("members", "member"), ("linear_drives", "linear drive")):
        raw[section] = r.mapping(data.get(section), section)
        for i, n in enumerate(raw[section]):
            names.add(kind, n, i)



def _ground(data, c):
    r = c.r
    ground, seen = [], set()
    for i, n in enumerate(r.listing(data.get("ground", []) or [], "ground")):
        g = c.node(n, f"ground[{i}]")
        if g in seen:
            r.fail(f"ground[{i}]", f"node '{n}' is listed twice")
        ground.append(g)
        seen.add(g)

    return ground


def _masses(data, c):
    r, planar = c.r, c.planar
    pm_nodes, pm_mass, pm_inertia = [], [], []
    for n, v in r.mapping(data.get("masses"), "masses").items():
        e = f"masses.{n}"
        i = c.node(n, e)
        if isinstance(v, dict):
            r.keys(v, e, {"mass", "inertia"}, required=("mass",))
            m = r.number(v["mass"], f"{e}.mass", positive=True)
            inertia = _inertia(v["inertia"], f"{e}.inertia", planar, r, allow_zero=True) \
                if "inertia" in v else np.zeros((3, 3))
        else:
            m = r.number(v, e, positive=True)
            inertia = np.zeros((3, 3))
        pm_nodes.append(i)
        pm_mass.append(m)
        pm_inertia.append(inertia)
    masses = PointMasses(np.array(pm_nodes, dtype=int), np.array(pm_mass, dtype=float),
                         np.array(pm_inertia, dtype=float).reshape(-1, 3, 3))

    return masses


def _bodies(c):
    """Rigid bodies -> (bodies, owner: node -> [(body, position in its list)])."""
    r, planar, coords, names = c.r, c.planar, c.coords, c.names
    bodies = []
    owner = {}
    for bi, (bname, b) in enumerate(c.raw["bodies"].items()):
        e = f"bodies.{bname}"
        if bname == "ground":
            r.fail(e, "'ground' is the name of the fixed frame; rename the body")
        r.keys(b, e, {"mass", "com", "inertia", "nodes"}, required=("mass",))
        m = r.number(b["mass"], f"{e}.mass", nonneg=True)
        if m > 0:
            for k in ("com", "inertia"):
                if k not in b:
                    r.fail(e, f"a body with mass needs '{k}'")
        if "com" in b:
            com = coords[c.node(b["com"], f"{e}.com")] if isinstance(b["com"], str) \
                else r.vector(b["com"], f"{e}.com")
            if planar and com[1] != 0:
                r.fail(f"{e}.com", "is off the x-z plane of a plane: xz model")
        else:
            com = None
        inertia = _inertia(b["inertia"], f"{e}.inertia", planar, r, allow_zero=True) \
            if "inertia" in b else np.zeros((3, 3))
        bnodes = []
        for k, n in enumerate(r.listing(b.get("nodes", []) or [], f"{e}.nodes")):
            i = c.node(n, f"{e}.nodes[{k}]")
            if i in bnodes:
                r.fail(f"{e}.nodes[{k}]", f"node '{n}' is listed twice")
            owner.setdefault(i, []).append((bi, k))
            bnodes.append(i)
        if com is None:
            com = coords[bnodes].mean(axis=0) if bnodes else np.zeros(3)
        names.add("body", bname, bi)
        bodies.append(Body(bname, m, com, inertia, tuple(bnodes)))

    return bodies, owner


def _joints(data, c):
    r, planar = c.r, c.planar
    joints = []
    for k, j in enumerate(r.listing(data.get("joints", []) or [], "joints")):
        e = f"joints[{k}]"
        r.keys(j, e, {"type", "bodies", "at", "axis", "name", "range", "range_deg"},
               required=("type", "bodies", "at"))
        if j["type"] not in JOINT_TYPES:
            r.fail(f"{e}.type", f"unknown joint type {j['type']!r}; use one of "
                   f"{', '.join(JOINT_TYPES)}")
        pair = r.listing(j["bodies"], f"{e}.bodies")
        if len(pair) != 2:
            r.fail(f"{e}.bodies", "a joint connects exactly two bodies (one may be ground)")
        b1, b2 = c.body(pair[0], f"{e}.bodies[0]"), c.body(pair[1], f"{e}.bodies[1]")
        if b1 == b2:
            r.fail(f"{e}.bodies", f"a joint connects two different bodies (found "
                   f"'{pair[0]}' twice); name the other body or 'ground'")
        at = c.node(j["at"], f"{e}.at")
        axis = None
        if j["type"] in ("hinge", "slider"):
            if "axis" in j:
                axis = r.unit(j["axis"], f"{e}.axis")
            elif planar and j["type"] == "hinge":
                axis = np.array([0.0, 1.0, 0.0])
            else:
                r.fail(f"{e}.axis", f"missing: a {j['type']} joint in a 3D model needs "
                       f"'axis: [x, y, z]' (the direction it "
                       f"{'turns about' if j['type'] == 'hinge' else 'slides along'})")
            if planar and j["type"] == "hinge" and abs(abs(axis[1]) - 1) > 1e-12:
                r.fail(f"{e}.axis", "a hinge in a plane: xz model turns about [0, 1, 0]")
            if planar and j["type"] == "slider" and abs(axis[1]) > 1e-12:
                r.fail(f"{e}.axis", "a slider in a plane: xz model slides in the plane (y = 0)")
        elif "axis" in j:
            r.fail(f"{e}.axis", f"a {j['type']} joint has no axis; remove it")
        jname = r.name(j["name"], f"{e}.name") if "name" in j else None
        joints.append(Joint(j["type"], (b1, b2), at, axis, e, jname,
                            _joint_range(j, e, r),
                            "range_deg" if "range_deg" in j else "range"))

    named = [j.name for j in joints if j.name is not None]
    for k, j in enumerate(joints):
        if j.name is not None and named.count(j.name) > 1:
            r.fail(f"{j.entry}.name", f"joint name '{j.name}' is used twice; rename one")
    return joints


def _shared_nodes(c, bodies, joints, owner, ground):
    """A node belongs to one body unless a joint between the bodies is at it."""
    r, node_names = c.r, c.node_names
    joint_nodes = {}
    for j in joints:
        joint_nodes.setdefault(j.at, set()).update(j.bodies)
    for i, owners in owner.items():
        shared = joint_nodes.get(i, set())
        carriers = [bi for bi, _ in owners]
        if len(owners) > 1 and not set(carriers) <= shared:
            (b0, _), (b1, k1) = owners[:2]
            r.fail(f"bodies.{bodies[b1].name}.nodes[{k1}]",
                   f"node '{node_names[i]}' is also carried by body '{bodies[b0].name}'; a "
                   "node belongs to one body unless a joint between the bodies is at it: "
                   f"add a joint at '{node_names[i]}' or use a separate node")
        if i in ground and GROUND not in shared:
            b0, k0 = owners[0]
            r.fail(f"bodies.{bodies[b0].name}.nodes[{k0}]",
                   f"node '{node_names[i]}' is also in ground; only the node of a joint "
                   f"between the body and the ground may be both: add a joint to ground "
                   f"at '{node_names[i]}' or remove it from ground or from the body")



def _springs(data, c):
    r, planar, coords, scale = c.r, c.planar, c.coords, c.scale
    springs = []
    seen = set()
    for k, s in enumerate(r.listing(data.get("springs", []) or [], "springs")):
        e = f"springs[{k}]"
        if not isinstance(s, dict):
            r.fail(e, f"must be a mapping such as {{type: axial, nodes: [A, B], "
                   f"stiffness: 1.0e6}}, not {_kind(s)}")
        sname = r.name(s.get("name", f"spring{k + 1}"), f"{e}.name")
        if sname in seen:
            r.fail(f"{e}.name", f"spring name '{sname}' is used twice; rename one")
        seen.add(sname)
        e = f"springs.{sname}" if "name" in s else e
        r.keys(s, e, {"name", "type", "nodes", "bodies", "at", "axis", "stiffness", "psi"},
               required=("type", "stiffness"))
        k_s = r.number(s["stiffness"], f"{e}.stiffness", positive=True,
                       unit="N*m/rad" if s["type"] == "rotational" else None)
        psi = r.number(s.get("psi", 0.0), f"{e}.psi", nonneg=True)
        if s["type"] == "axial":
            for bad in ("bodies", "axis"):
                if bad in s:
                    r.fail(f"{e}.{bad}", "an axial spring joins two nodes; use 'nodes'")
            pair = r.listing(s.get("nodes"), f"{e}.nodes")
            if len(pair) != 2:
                r.fail(f"{e}.nodes", "an axial spring joins exactly two nodes")
            a, b = c.node(pair[0], f"{e}.nodes[0]"), c.node(pair[1], f"{e}.nodes[1]")
            if np.linalg.norm(coords[b] - coords[a]) <= 1e-9 * scale:
                r.fail(f"{e}.nodes", "the two nodes coincide: an axial spring needs a length")
            springs.append(Spring(sname, "axial", k_s, psi, nodes=(a, b)))
        elif s["type"] == "rotational":
            if "nodes" in s:
                r.fail(f"{e}.nodes", "a rotational spring joins two bodies; use 'bodies'")
            pair = r.listing(s.get("bodies"), f"{e}.bodies")
            if len(pair) != 2:
                r.fail(f"{e}.bodies", "a rotational spring joins exactly two bodies")
            b1, b2 = c.body(pair[0], f"{e}.bodies[0]"), c.body(pair[1], f"{e}.bodies[1]")
            if b1 == b2:
                r.fail(f"{e}.bodies", "a rotational spring joins two different bodies")
            at = c.node(s["at"], f"{e}.at") if "at" in s else -1
            if "axis" in s:
                axis = r.unit(s["axis"], f"{e}.axis")
            elif planar:
                axis = np.array([0.0, 1.0, 0.0])
            else:
                r.fail(f"{e}.axis", "missing: a rotational spring in a 3D model needs "
                       "'axis: [x, y, z]'")
            if planar and abs(abs(axis[1]) - 1) > 1e-12:
                r.fail(f"{e}.axis", "in a plane: xz model rotations are about [0, 1, 0]")
            springs.append(Spring(sname, "rotational", k_s, psi, bodies=(b1, b2), at=at,
                                  axis=axis))
        else:
            r.fail(f"{e}.type", f"unknown spring type {s['type']!r}; use axial or rotational")

    return springs


def _drums(c):
    r, names = c.r, c.names
    drums = []
    for di, (dname, d) in enumerate(c.raw["drums"].items()):
        e = f"drums.{dname}"
        if "node" in names.kinds.get(dname, {}):
            r.fail(e, f"'{dname}' is also a node name; rope paths need drum names distinct "
                   "from node names: rename the drum")
        r.keys(d, e, {"node", "radius", "inertia", "motor", "brake", "rope_reserve"},
               required=("node", "radius", "inertia"))
        motor = d.get("motor") or {}
        r.keys(motor, f"{e}.motor", {"rotor_inertia", "gear_ratio"},
               required=("rotor_inertia", "gear_ratio") if motor else ())
        drums.append(Drum(
            dname, c.node(d["node"], f"{e}.node"),
            r.number(d["radius"], f"{e}.radius", positive=True),
            r.number(d["inertia"], f"{e}.inertia", positive=True),
            r.number(motor.get("rotor_inertia", 0.0), f"{e}.motor.rotor_inertia",
                     nonneg=True),
            r.number(motor.get("gear_ratio", 1.0), f"{e}.motor.gear_ratio", positive=True),
            r.boolean(d.get("brake", False), f"{e}.brake"),
            r.number(d["rope_reserve"], f"{e}.rope_reserve", nonneg=True)
            if "rope_reserve" in d else float("inf")))
        names.add("drum", dname, di)

    return drums


def _ropes_and_members(c, drums):
    r, names, coords, scale, planar = c.r, c.names, c.coords, c.scale, c.planar
    node_names, mesh_pairs = c.node_names, c.mesh_pairs
    # ropes
    ropes = []
    for rname, rp in c.raw["ropes"].items():
        ropes.append(_rope(rname, rp, r, names, coords, scale, node_names, drums))
        names.add("rope", rname, len(ropes) - 1)

    # members
    members = []
    for mname, m in c.raw["members"].items():
        members.append(_member(mname, m, r, c.node, coords, scale, planar,
                               mesh_pairs.get(mname), names))
        names.add("member", mname, len(members) - 1)

    return ropes, members


def _linear_drives(c):
    r, coords, scale = c.r, c.coords, c.scale
    linear = []
    for lname, ld in c.raw["linear_drives"].items():
        e = f"linear_drives.{lname}"
        r.keys(ld, e, {"nodes", "pinion_radius", "gear_ratio", "rotor_inertia"},
               required=("nodes", "pinion_radius", "gear_ratio"))
        pair = r.listing(ld["nodes"], f"{e}.nodes")
        if len(pair) != 2:
            r.fail(f"{e}.nodes", "a linear drive sets the distance between two nodes")
        a, cn = c.node(pair[0], f"{e}.nodes[0]"), c.node(pair[1], f"{e}.nodes[1]")
        if np.linalg.norm(coords[cn] - coords[a]) <= 1e-9 * scale:
            r.fail(f"{e}.nodes", "the two nodes coincide; the drive needs a length")
        linear.append(LinearDrive(
            lname, (a, cn), r.number(ld["pinion_radius"], f"{e}.pinion_radius", positive=True),
            r.number(ld["gear_ratio"], f"{e}.gear_ratio", positive=True),
            r.number(ld.get("rotor_inertia", 0.0), f"{e}.rotor_inertia", nonneg=True)))

    return linear


def _build_model(data, file, text, r):
    """The Model of a model file's data: one section at a time, each with its checks."""
    planar, gravity = _header(data, r)
    c = _Ctx(r, _Names(r), planar)
    _nodes(data, c)
    ground = _ground(data, c)
    supports = _supports(data, c, ground)
    masses = _masses(data, c)
    bodies, owner = _bodies(c)
    joints = _joints(data, c)
    _shared_nodes(c, bodies, joints, owner, ground)
    springs = _springs(data, c)
    drums = _drums(c)
    ropes, members = _ropes_and_members(c, drums)
    linear = _linear_drives(c)
    coords, node_names = c.coords, c.node_names
    effects = _effects(data.get("effects"), Effects(), r, "effects")
    name = data.get("name", os.path.splitext(os.path.basename(file))[0])
    return Model(
        name=str(name), file=file, text=text, planar=planar, gravity=gravity,
        node_names=node_names, coords=coords, ground=np.array(ground, dtype=int),
        masses=masses, bodies=tuple(bodies), joints=tuple(joints), springs=tuple(springs),
        drums=tuple(drums), ropes=tuple(ropes), members=tuple(members),
        linear_drives=tuple(linear), effects=effects, supports=supports)


def _joint_range(j, e, r):
    """The travel of a slider (m along its axis) or the turn of a hinge (rad; or
    `range_deg`) from the reference geometry, [min, max] with min <= 0 <= max; None if
    not given (docs/operations.md: a driven slider needs one)."""
    keys = [k for k in ("range", "range_deg") if k in j]
    if not keys:
        return None
    if len(keys) > 1:
        r.fail(e, "give range or range_deg, not both")
    k = keys[0]
    if j["type"] not in ("slider", "hinge"):
        r.fail(f"{e}.{k}", f"a {j['type']} joint does not move; only a slider or a hinge "
               "has a range")
    if k == "range_deg" and j["type"] != "hinge":
        r.fail(f"{e}.{k}", "a slider's range is a length: give range: [min, max] in m")
    lo, hi = r.vector(j[k], f"{e}.{k}", 2)
    if k == "range_deg":
        lo, hi = np.radians(lo), np.radians(hi)
    if not lo <= 0 <= hi:
        r.fail(f"{e}.{k}", f"[{j[k][0]:g}, {j[k][1]:g}] must contain 0 (the reference "
               "position of the model file) and have min <= max")
    return np.array([lo, hi])


def _inertia(v, entry, planar, r, allow_zero):
    """Scalar (planar, about y), [Ixx, Iyy, Izz] or a full 3x3 list -> (3, 3)."""
    if planar and not isinstance(v, list):
        iyy = r.number(v, entry, nonneg=allow_zero, positive=not allow_zero)
        return np.diag([0.0, iyy, 0.0])
    if isinstance(v, list) and len(v) == 3 and all(isinstance(x, list) for x in v):
        inertia = np.array([r.vector(row, f"{entry}[{i}]") for i, row in enumerate(v)])
        if not np.allclose(inertia, inertia.T, rtol=1e-12, atol=0):
            r.fail(entry, "a full inertia tensor must be symmetric")
    else:
        if not planar and not isinstance(v, list):
            r.fail(entry, "in a 3D model give [Ixx, Iyy, Izz] or a full 3x3 list")
        inertia = np.diag(r.vector(v, entry))
    eig = np.linalg.eigvalsh(inertia)
    if planar:
        eig = np.array([inertia[1, 1]])
    if eig.min() < 0 or (not allow_zero and eig.min() <= 0):
        r.fail(entry, ("must have no negative principal value" if allow_zero else
                       "must be positive definite") + f" (principal values {np.round(eig, 6)})")
    return inertia


def _rope(name, rp, r, names, coords, scale, node_names, drums):
    e = f"ropes.{name}"
    r.keys(rp, e, {"EA", "mass_per_length", "psi", "extra_length", "path",
                   *ropes_data.KEYS}, required=("path",))
    EA, mass_per_length, _ = ropes_data.rope_values(rp, r, e)   # given, or by designation
    path = r.listing(rp["path"], f"{e}.path", min_len=2)
    points = []          # (kind, index) after tackle expansion
    span_a, span_b, falls = [], [], []

    def point(v, entry):
        return names.get(v, ("node", "drum"), entry)

    def node_of(p):
        return drums[p[1]].node if p[0] == "drum" else p[1]

    current = None
    for k, entry in enumerate(path):
        pe = f"{e}.path[{k}]"
        n = 1
        if isinstance(entry, dict):
            r.keys(entry, pe, {"node", "falls"}, required=("node", "falls"))
            n = r.integer(entry["falls"], f"{pe}.falls", minimum=1, maximum=MAX_FALLS,
                          why=": the parallel falls of one tackle")
            if k == 0:
                r.fail(pe, "a tackle needs a previous point; the first entry is the rope's end")
            p = ("node", names.get(entry["node"], "node", f"{pe}.node")[1])
        else:
            p = point(entry, pe)
        if p[0] == "drum" and 0 < k < len(path) - 1:
            r.fail(pe, f"drum '{entry}' in the middle of the path; a drum is a rope end "
                   "(first or last entry)")
        if current is None:
            current = p
            points.append(p)
            continue
        a, b = node_of(current), node_of(p)
        if np.linalg.norm(coords[b] - coords[a]) <= 1e-9 * scale:
            r.fail(pe, f"span {_pname(current, node_names, drums)} -> "
                   f"{_pname(p, node_names, drums)} has zero length; move a node or "
                   "remove the entry")
        span_a.append(a)
        span_b.append(b)
        falls.append(n)
        points.extend([p, current] * (n // 2) + ([p] if n % 2 else []))
        if n % 2:          # odd tackle: continues at X; even: back at P
            current = p
        elif k < len(path) - 1 and current[0] == "drum":
            r.fail(pe, f"this even tackle brings the rope back to drum "
                   f"'{drums[current[1]].name}' and the path goes on; a drum is a rope end "
                   "(make the tackle odd, or end the path here)")
    ends = [points[0], points[-1]]
    end_drums = tuple(p[1] for p in ends if p[0] == "drum")
    return Rope(
        name, EA, mass_per_length,
        r.number(rp.get("psi", 0.0), f"{e}.psi", nonneg=True),
        r.number(rp.get("extra_length", 0.0), f"{e}.extra_length", nonneg=True),
        np.array(span_a, dtype=int), np.array(span_b, dtype=int),
        np.array(falls, dtype=int), end_drums,
        tuple(_pname(p, node_names, drums) for p in points))


def _pname(p, node_names, drums):
    return drums[p[1]].name if p[0] == "drum" else node_names[p[1]]


def _coordinates(nodes, node_names, r):
    """(n, 3) node coordinates: a vectorised path for big files, per-node messages else."""
    values = [nodes[n] for n in node_names]
    # the same test as per value, in C-speed passes: lists of three ints or floats
    if set(map(type, values)) <= {list} and set(map(len, values)) <= {3} and \
            set(map(type, itertools.chain.from_iterable(values))) <= {int, float}:
        coords = np.array(values, dtype=float)
        if np.all(np.isfinite(coords)):
            return coords
    return np.array([r.vector(nodes[n], f"nodes.{n}") for n in node_names])


def _mesh_member(name, mesh, r, coords, node_names, names, planar):
    """Read a member's line cells from a mesh file (any format meshio reads).

    Points within 1e-6 of the model size of a named node are that node; the others become
    nodes named 'NAME.i' (i the point's index in the file). Returns (coords, pairs)."""
    e = f"members.{name}.mesh"
    if not isinstance(mesh, str):
        r.fail(e, "must be the path of a mesh file (VTU, Gmsh, Abaqus INP, ...)")
    path = named_path(mesh, r.file, e, "mesh file")
    note_read(path)
    if not os.path.isfile(path):
        r.fail(e, f"mesh file '{mesh}' not found (looked for {path}); the path is relative "
               "to the model file")
    import meshio
    try:
        m = meshio.read(path)
    except Exception as exc:            # meshio raises many kinds for unreadable files
        r.fail(e, f"meshio cannot read '{mesh}': {exc}")
    lines = [c.data for c in m.cells if c.type == "line"]
    if not lines:
        r.fail(e, f"'{mesh}' has no line cells (found: "
               f"{', '.join(sorted({c.type for c in m.cells})) or 'none'})")
    pts = np.asarray(m.points, dtype=float)
    if pts.shape[1] == 2:
        pts = np.column_stack([pts[:, 0], np.zeros(len(pts)), pts[:, 1]]) if planar \
            else np.column_stack([pts, np.zeros(len(pts))])
    used = np.unique(np.concatenate(lines).ravel())
    scale = float(np.ptp(np.vstack([coords, pts[used]]), axis=0).max()) or 1.0
    index = np.full(len(pts), -1)
    if len(coords):
        from scipy.spatial import cKDTree
        dist, near = cKDTree(coords).query(pts[used], distance_upper_bound=1e-6 * scale)
        hit = np.isfinite(dist)
        index[used[hit]] = near[hit]
    new = used[index[used] < 0]
    index[new] = len(coords) + np.arange(len(new))
    for k, i in enumerate(new):
        n = f"{name}.{i}"
        if n in names.kinds:
            r.fail(e, f"the mesh point name '{n}' is already used; rename that entry")
        node_names.append(n)
        names.add("node", n, len(coords) + k)
    coords = np.vstack([coords, pts[new]])
    if planar and np.any(np.abs(coords[:, 1]) > 0):
        r.fail(e, "the mesh has points off the x-z plane of a plane: xz model")
    return coords, index[np.concatenate(lines)]


def _member(name, m, r, node, coords, scale, planar, mesh_pairs=None, names=None):
    e = f"members.{name}"
    m = _with_section(m, e, r)
    r.keys(m, e, {"type", "nodes", "pairs", "mesh", "E", "G", "A", "Iy", "Iz", "J", "rho",
                  "orientation", "elements", "mass", "psi", "Asy", "Asz",
                  "shear_coefficient", "releases", "Wy", "Wz"}, required=("type", "E", "A"))
    given = [k for k in ("nodes", "pairs", "mesh") if k in m]
    if len(given) != 1:
        r.fail(e, "give exactly one of 'nodes' (a chain), 'pairs' (a list of [A, B]) or "
               f"'mesh' (a mesh file){'; found ' + ', '.join(given) if given else ''}")
    kind = m["type"]
    if kind not in ("beam", "truss"):
        r.fail(f"{e}.type", f"unknown member type {kind!r}; use beam or truss")
    chain, pairs = (), None
    if "nodes" in m:
        chain = [node(n, f"{e}.nodes[{k}]") for k, n in
                 enumerate(r.listing(m["nodes"], f"{e}.nodes", min_len=2))]
        for k in range(1, len(chain)):
            if np.linalg.norm(coords[chain[k]] - coords[chain[k - 1]]) <= 1e-9 * scale:
                r.fail(f"{e}.nodes[{k}]", "zero-length piece: consecutive nodes coincide")
        chain = tuple(chain)
    else:
        if "pairs" in m:
            raw = r.listing(m["pairs"], f"{e}.pairs", min_len=1)
            lookup = names.node_index()
            try:       # strict zip: pairs of two (as `for a, b in raw` would require)
                a, b = zip(*raw, strict=True) if raw else ((), ())
                pairs = np.column_stack([np.fromiter(map(lookup.__getitem__, x), int, len(x))
                                         for x in (a, b)])
            except (KeyError, TypeError, ValueError):
                for k, p in enumerate(raw):
                    if not isinstance(p, list) or len(p) != 2:
                        r.fail(f"{e}.pairs[{k}]", f"must be a pair [A, B] of node names, "
                               f"not {p!r}")
                    node(p[0], f"{e}.pairs[{k}][0]")
                    node(p[1], f"{e}.pairs[{k}][1]")
        else:
            pairs = np.asarray(mesh_pairs, dtype=int)
        short = np.linalg.norm(coords[pairs[:, 1]] - coords[pairs[:, 0]], axis=1) \
            <= 1e-9 * scale
        if short.any():
            k = int(np.flatnonzero(short)[0])
            r.fail(f"{e}.{'pairs' if 'pairs' in m else 'mesh'}[{k}]",
                   "zero-length element: its two nodes coincide")
    kw = {}
    if kind == "beam":
        need = ("G", "Iy", "Iz", "J") if not planar else ("Iy",)
        for k in need:
            if k not in m:
                r.fail(e, f"a beam needs '{k}'")
        for k in ("G", "Iy", "Iz", "J", "Wy", "Wz"):
            if k in m:
                kw[k] = r.number(m[k], f"{e}.{k}", positive=True)
        if "orientation" in m:
            kw["orientation"] = r.unit(m["orientation"], f"{e}.orientation")
        elif not planar:
            r.fail(e, "a 3D beam needs 'orientation' (a vector in its local x-z plane)")
        kw.update(_shear_areas(m, e, r, planar))
        kw.update(_releases(m, e, r, node, chain, pairs, planar))
    else:
        for k in ("G", "Iy", "Iz", "J", "orientation", "Asy", "Asz", "shear_coefficient",
                  "releases", "Wy", "Wz"):
            if k in m:
                r.fail(f"{e}.{k}", "a truss has only axial stiffness; remove it")
    elements = r.integer(m.get("elements", 1), f"{e}.elements", minimum=1)
    if kind == "truss" and elements != 1:
        r.fail(f"{e}.elements", "a subdivided truss would be a mechanism; use 1")
    mass = m.get("mass", "consistent")
    if mass not in ("consistent", "lumped"):
        r.fail(f"{e}.mass", f"{mass!r} is not consistent or lumped")
    return Member(name, kind, chain, r.number(m["E"], f"{e}.E", positive=True),
                  r.number(m["A"], f"{e}.A", positive=True),
                  r.number(m.get("rho", 0.0), f"{e}.rho", nonneg=True),
                  elements=elements, mass=mass, pairs=pairs,
                  psi=r.number(m.get("psi", 0.0), f"{e}.psi", nonneg=True), **kw)


def _shear_areas(m, e, r, planar):
    """Shear areas of a Timoshenko beam: `Asy`, `Asz` (m^2) or `shear_coefficient`
    k or [ky, kz] (As = k A); none: Euler-Bernoulli ({})."""
    given = [k for k in ("Asy", "Asz") if k in m]
    if "shear_coefficient" in m:
        if given:
            r.fail(e, "give shear areas 'Asy', 'Asz' or a 'shear_coefficient', not both")
        v = m["shear_coefficient"]
        ks = r.vector(v, f"{e}.shear_coefficient", n=2) if isinstance(v, list) \
            else np.array([r.number(v, f"{e}.shear_coefficient", positive=True)] * 2)
        if np.any(ks <= 0):
            r.fail(f"{e}.shear_coefficient", "must be > 0")
        A = r.number(m["A"], f"{e}.A", positive=True)
        out = {"Asy": float(ks[0] * A), "Asz": float(ks[1] * A)}
    elif given:
        need = ("Asz",) if planar else ("Asy", "Asz")
        for k in need:
            if k not in m:
                r.fail(e, f"a {'planar ' if planar else ''}Timoshenko beam needs '{k}' "
                       "(the shear area for shear along local "
                       f"{k[-1]}), or give a 'shear_coefficient'")
        out = {k: r.number(m[k], f"{e}.{k}", positive=True) for k in given}
    else:
        return {}
    if "G" not in m:
        r.fail(e, "a Timoshenko beam (shear areas given) needs the shear modulus 'G'")
    return out


SUPPORT_COMPONENTS = ("ux", "uy", "uz", "rx", "ry", "rz")
SUPPORT_SHORTHANDS = {"pinned": ("ux", "uy", "uz"), "fixed": SUPPORT_COMPONENTS}


def _supports(data, c, ground):
    """Per-direction restraints of nodes: `NODE: [ux, uz, ry]`, `pinned`, `fixed`, or
    `{fix: [...], axes: [x', y', z']}` with the components along given orthonormal axes."""
    r, out = c.r, []
    for n, v in r.mapping(data.get("supports"), "supports").items():
        e = f"supports.{n}"
        i = c.node(n, e)
        if i in ground:
            r.fail(e, f"node '{n}' is in ground (fixed in every direction); list it in one "
                   "of them")
        axes = np.eye(3)
        if isinstance(v, dict):
            r.keys(v, e, {"fix", "axes"}, required=("fix",))
            if "axes" in v:
                rows = r.listing(v["axes"], f"{e}.axes")
                if len(rows) != 3:
                    r.fail(f"{e}.axes", "give three axes x', y', z' (rows of a rotation)")
                axes = np.array([r.unit(a, f"{e}.axes[{k}]") for k, a in enumerate(rows)])
                if np.abs(axes @ axes.T - np.eye(3)).max() > 1e-9:
                    r.fail(f"{e}.axes", "the three axes must be mutually orthogonal")
            v = v["fix"]
            e = f"{e}.fix"
        comps = SUPPORT_SHORTHANDS.get(v) if isinstance(v, str) else r.listing(v, e, 1)
        if comps is None:
            r.fail(e, f"{_echo(v)} is not a list of components ({', '.join(SUPPORT_COMPONENTS)}), "
                   "'pinned' or 'fixed'")
        for k, comp in enumerate(comps):
            if comp not in SUPPORT_COMPONENTS or list(comps).count(comp) > 1:
                r.fail(f"{e}[{k}]", f"{comp!r}: use each of {', '.join(SUPPORT_COMPONENTS)} "
                       "at most once")
        idx = [SUPPORT_COMPONENTS.index(k) for k in comps]
        out.append(Support(i, axes[[k for k in idx if k < 3]],
                           axes[[k - 3 for k in idx if k >= 3]], f"supports.{n}"))
    return tuple(out)


RELEASE_COMPONENTS = ("rx", "ry", "rz")


def _releases(m, e, r, node, chain, pairs, planar):
    """Member-end releases `{NODE: [rx, ry, rz]}` (local rotations set free at the
    member's element ends at NODE) -> {"releases": ((node, (0..2, ...)), ...)} or {}."""
    if "releases" not in m:
        return {}
    pieces = np.asarray(pairs, dtype=int).reshape(-1, 2) if pairs is not None else \
        np.stack([chain[:-1], chain[1:]], axis=1)
    out = {}
    for n, comps in r.mapping(m["releases"], f"{e}.releases").items():
        entry = f"{e}.releases.{n}"
        i = node(n, entry)
        if i not in pieces:
            r.fail(entry, f"node '{n}' is not a node of this member")
        comps = [comps] if isinstance(comps, str) else r.listing(comps, entry, 1)
        for k, comp in enumerate(comps):
            if comp not in RELEASE_COMPONENTS or comps.count(comp) > 1 or \
                    (planar and comp != "ry"):
                allowed = "ry (in a plane: xz model)" if planar else "rx, ry, rz (local axes)"
                r.fail(f"{entry}[{k}]", f"{comp!r}: release each of {allowed} at most once")
        out[i] = tuple(sorted(RELEASE_COMPONENTS.index(c) for c in comps))
    for a, b in pieces:
        if 0 in out.get(a, ()) and 0 in out.get(b, ()):
            r.fail(f"{e}.releases", "rx released at both ends of a piece leaves it free to "
                   "twist; release it at one end")
    return {"releases": tuple(out.items())}


SECTION_FILLS = ("A", "Iy", "Iz", "J", "Wy", "Wz")


def _with_section(m, e, r):
    """The member entry with `section: {shape, dimensions..., timoshenko}` or `section:
    {profile: NAME, timoshenko}` replaced by the A, Iy, Iz, J (and with timoshenko: true
    the shear areas) of that shape (`cranefe.model.sections`), plus the elastic moduli
    Wy, Wz for stresses; unchanged without a section."""
    if not isinstance(m, dict) or "section" not in m:
        return m
    sec, es = r.mapping(m["section"], f"{e}.section"), f"{e}.section"
    if "profile" in sec:
        r.keys(sec, es, {"profile", "timoshenko"}, required=("profile",))
        found = profile_shape(sec["profile"])
        if found is None:
            r.fail(f"{es}.profile", f"unknown profile {sec['profile']!r}; use a name of "
                   "cranefe/model/profiles.csv (IPE, HEA, HEB, HEM, equal angles 'L 100x10'"
                   ") or a hollow section by its size ('CHS 168.3x10', 'SHS 100x5', "
                   "'RHS 200x100x8'), or give the shape's dimensions")
        shape, vals = found
        dims = ()
    else:
        shape = sec.get("shape")
        if shape not in SHAPES:
            r.fail(f"{es}.shape", f"{shape!r} is not one of {', '.join(sorted(SHAPES))}")
        dims = SHAPES[shape][0]
        opt = tuple(OPTIONAL[shape])
        r.keys(sec, es, {"shape", "timoshenko", *dims, *opt}, required=("shape", *dims))
        vals = {d: r.number(sec[d], f"{es}.{d}", positive=True) for d in dims}
        vals.update({d: r.number(sec[d], f"{es}.{d}", nonneg=True) for d in opt if d in sec})
    thin = {"t": (2, ("D", "b", "h")), "tw": (1, ("b",)), "tf": (2, ("h",))}
    for d, (n, outer) in thin.items():
        for o in outer:
            if d in dims and o in vals and n * vals[d] >= vals[o]:
                r.fail(f"{es}.{d}", f"{'twice ' if n == 2 else ''}the thickness {d} must "
                       f"be less than {o}")
    radii = {"r": lambda v: min((v["b"] - v["tw"]) / 2, v["h"] / 2 - v["tf"]),
             "r1": lambda v: min(v["h"], v["b"]) - v["t"], "r2": lambda v: v["t"],
             "ro": lambda v: min(v["b"], v["h"]) / 2, "ri": lambda v: min(v["b"], v["h"]) / 2 - v["t"]}
    for d, limit in radii.items():
        if d in vals and shape != "tube" and vals[d] > limit(vals):
            r.fail(f"{es}.{d}", f"the radius {d} = {vals[d]:g} m does not fit the section "
                   f"(at most {limit(vals):g} m)")
    if shape == "angle" and vals["t"] >= min(vals["h"], vals["b"]):
        r.fail(f"{es}.t", "the thickness t must be less than both legs h and b")
    both = [k for k in SECTION_FILLS if k in m]
    if both:
        r.fail(e, f"give the section or {', '.join(both)}, not both")
    G = m.get("G")
    nu = m["E"] / (2 * G) - 1 if isinstance(G, (int, float)) and G and \
        isinstance(m.get("E"), (int, float)) else 0.3
    A, Iy, Iz, J, Asy, Asz = section_properties(shape, vals, nu)
    Wy, Wz = section_moduli(shape, vals)
    out = {k: v for k, v in m.items() if k != "section"}
    out.update(A=A, Iy=Iy, Iz=Iz, J=J, Wy=Wy, Wz=Wz)
    if m.get("type") == "truss":
        for k in ("Iy", "Iz", "J", "Wy", "Wz"):
            del out[k]
    if r.boolean(sec.get("timoshenko", False), f"{es}.timoshenko"):
        if any(k in m for k in ("Asy", "Asz", "shear_coefficient")):
            r.fail(e, "timoshenko: true takes the shear areas from the section; remove "
                   "Asy, Asz, shear_coefficient")
        out.update(Asy=Asy, Asz=Asz)
    return out
