"""Bad input gets exit status 2 and a message naming the file, the entry and what to change.

Every check of model-format.md ("Checks a model file gets", and the rules for paths,
nodes, joints, bodies, effects and scenes) plus the YAML-level ones (syntax, duplicate
keys, alias bombs, numbers such as 1e7) is run through the command line
(`cranefe.cli.main`), as a user meets it: no traceback, exit status 2.

Each bad file is a small edit of a good base model; `edit` refuses an edit that does not
apply, and the base models themselves must pass (`test_base_models_are_good`), so every
case fails for the reason it names.
"""

import textwrap
import time

import pytest

from cranefe.cli import main
from cranefe.model import load


def yaml(text):
    return textwrap.dedent(text).lstrip("\n")


# A planar hoist: ground winch, head sheave, 2-fall tackle to a point mass.
HOIST = yaml("""
    cranefe: 1
    plane: xz
    nodes: {W: [-5, 0, 0], S: [0, 0, 10], H: [0, 0, 0]}
    ground: [W, S]
    masses: {H: 100}
    drums:
      hoist: {node: W, radius: 0.2, inertia: 10}
    ropes:
      r: {EA: 1e7, psi: 0.2, path: [hoist, S, {node: H, falls: 2}]}
""")

# A planar crane of bodies: mast hinged to ground (with a bending spring), jib fixed
# to it, a hook hanging from the jib on an axial spring.
CRANE = yaml("""
    cranefe: 1
    plane: xz
    nodes: {O: [0, 0, 0], T: [0, 0, 10], K: [5, 0, 10], H: [5, 0, 2]}
    ground: [O]
    masses: {H: 100}
    bodies:
      mast: {mass: 1000, com: [0, 0, 5], inertia: 1.0e4, nodes: [O, T]}
      jib: {mass: 500, com: K, inertia: 2.0e3, nodes: [T, K]}
    joints:
      - {type: hinge, bodies: [ground, mast], at: O}
      - {type: fixed, bodies: [mast, jib], at: T}
    springs:
      - {name: bend, type: rotational, bodies: [ground, mast], at: O, stiffness: 1e9}
      - {name: sling, type: axial, nodes: [K, H], stiffness: 1e6, psi: 0.1}
""")

# A 3D mast on a hinge about y, held by a rotational spring.
MAST3D = yaml("""
    cranefe: 1
    nodes: {O: [0, 0, 0], T: [0, 0, 10]}
    ground: [O]
    bodies:
      mast: {mass: 1000, com: [0, 0, 5], inertia: [1e4, 1e4, 1e2], nodes: [O, T]}
    joints:
      - {type: hinge, bodies: [ground, mast], at: O, axis: [0, 1, 0]}
    springs:
      - {type: rotational, bodies: [ground, mast], axis: [0, 1, 0], stiffness: 1e9}
""")

# Members and a linear drive on a planar body.
MEMBERS = yaml("""
    cranefe: 1
    plane: xz
    nodes: {O: [0, 0, 0], T: [0, 0, 10], A: [2, 0, 0], C: [2, 0, 5]}
    ground: [O]
    bodies:
      mast: {mass: 1000, com: [0, 0, 5], inertia: 1.0e4, nodes: [O, T, A, C]}
    joints:
      - {type: hinge, bodies: [ground, mast], at: O}
    springs:
      - {type: rotational, bodies: [ground, mast], stiffness: 1e9}
    members:
      m1: {type: beam, nodes: [T, A], E: 2.1e11, A: 1e-2, Iy: 1e-4, rho: 7850}
      t1: {type: truss, nodes: [A, T], E: 2.1e11, A: 1e-3}
    linear_drives:
      lu: {nodes: [A, C], pinion_radius: 0.2, gear_ratio: 100, rotor_inertia: 1.0}
""")

BASES = {"HOIST": HOIST, "CRANE": CRANE, "MAST3D": MAST3D, "MEMBERS": MEMBERS}


def edit(base, *pairs):
    """`base` with each (old, new) replaced once; an edit that does not apply is a bug."""
    for old, new in zip(pairs[::2], pairs[1::2]):
        assert base.count(old) == 1, f"edit {old!r} does not apply exactly once"
        base = base.replace(old, new)
    return base


def run(path, capsys, command="check"):
    """Run the CLI on `path`; return (exit status, stdout + stderr, stderr)."""
    status = main([command, str(path)])
    out, err = capsys.readouterr()
    return status, out + err, err


def assert_bad(path, capsys, entry, message, command="check"):
    status, both, err = run(path, capsys, command)
    assert "Traceback" not in both
    assert status == 2, both
    assert str(path) in err, err
    assert entry in err, err
    assert message in err, err
    return err


def write(tmp_path, text, name="m.yaml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


# --------------------------------------------------------------------------- the table
# (yaml_text, expected entry, expected part of the message: what is wrong / what to do)

P = pytest.param
CASES = [
    # -- the document
    P("- 1\n- 2\n", "", "holds a list", id="not-a-mapping"),
    P("just text\n", "", "starts with 'cranefe: 1'", id="a-scalar"),
    P("", "", "the file is empty", id="empty"),
    P("# a comment only\n", "", "the file is empty", id="only-comment"),
    P(edit(HOIST, "cranefe: 1\n", ""), "cranefe", "start the file with 'cranefe: 1'",
      id="no-version"),
    P(edit(HOIST, "cranefe: 1", "cranefe: 2"), "cranefe", "found 2", id="version-2"),
    P(edit(HOIST, "cranefe: 1", "cranefe: '1'"), "cranefe", "format version must be 1",
      id="version-text"),
    P(edit(HOIST, "cranefe: 1", "cranefe: true"), "cranefe", "format version must be 1",
      id="version-bool"),
    P("cranefe: 1\nname: x\n", "nodes", "a model needs 'nodes:'", id="no-nodes"),
    P("cranefe: 1\nnodes: {}\n", "nodes", "at least one node", id="zero-nodes"),
    P("cranefe: 1\nnodes: [A, B]\n", "nodes", "must be a mapping", id="nodes-list"),
    P(edit(HOIST, "plane: xz", "name: [1, 2]\nplane: xz"), "name", "must be text",
      id="name-list"),
    # -- YAML level
    P(HOIST + "nodes: {X: [0, 0, 0]}\n", "nodes, line 10", "key 'nodes' is repeated",
      id="duplicate-top-key"),
    P(edit(HOIST, "H: [0, 0, 0]}", "H: [0, 0, 0], H: [1, 0, 0]}"), "nodes.H",
      "delete or rename the other", id="duplicate-node"),
    P(edit(HOIST, "EA: 1e7,", "EA: 1e7, EA: 2e7,"), "ropes.r.EA", "repeated in 'ropes.r'",
      id="duplicate-rope-key"),
    P(edit(HOIST, "ground: [W, S]", "ground: [W, S\n"), "line 6, column 7",
      "YAML syntax error: did not find expected ',' or ']' (while parsing a flow sequence "
      "that starts on line 4)", id="syntax-flow"),
    P(edit(HOIST, "  hoist:", "\thoist:"), "line 7, column 1", "not tabs", id="syntax-tab"),
    P(edit(HOIST, "ground: [W, S]", "ground: *nothing"), "line 4", "undefined alias",
      id="undefined-alias"),
    P(edit(HOIST, "ground: [W, S]", "ground: !!python/object:os.system [W]"), "line 4",
      "could not determine a constructor", id="python-tag"),
    P(HOIST + "---\ncranefe: 1\n", "line", "another document", id="two-documents"),
    P(edit(HOIST, "H: [0, 0, 0]", "H: &a [0, *a, 0]"), "nodes.H[1]",
      "refers to an entry that contains it", id="recursive-alias"),
    # -- unknown keys, everywhere
    P(HOIST + "foo: 1\n", "foo", "unknown key 'foo'; allowed here:", id="top-key"),
    P(HOIST + "rope: {}\n", "rope", "did you mean 'ropes'?", id="top-key-typo"),
    P(edit(HOIST, "EA: 1e7,", "EA: 1e7, diameter_mm: 20,"), "ropes.r.diameter_mm",
      "unknown key 'diameter_mm'", id="rope-key"),
    P(edit(HOIST, "{node: H, falls: 2}", "{node: H, falls: 2, sheave: 1}"),
      "ropes.r.path[2].sheave", "allowed here: falls, node", id="tackle-key"),
    P(edit(CRANE, "mass: 1000,", "mass: 1000, weight: 1,"), "bodies.mast.weight",
      "unknown key 'weight'", id="body-key"),
    P(edit(CRANE, "at: O}", "at: O, stiffness: 1}"), "joints[0].stiffness",
      "unknown key 'stiffness'", id="joint-key"),
    P(edit(HOIST, "inertia: 10}", "inertia: 10, width: 1}"), "drums.hoist.width",
      "unknown key 'width'", id="drum-key"),
    P(edit(HOIST, "inertia: 10}", "inertia: 10, motor: {gear_ratio: 5, rotor_inertia: 1, "
           "power: 3}}"), "drums.hoist.motor.power", "unknown key 'power'", id="motor-key"),
    P(edit(CRANE, "psi: 0.1}", "psi: 0.1, damping: 1}"), "springs.sling.damping",
      "unknown key 'damping'", id="spring-key"),
    P(edit(MEMBERS, "rho: 7850}", "rho: 7850, I: 1}"), "members.m1.I", "unknown key 'I'",
      id="member-key"),
    P(edit(MEMBERS, "rotor_inertia: 1.0}", "rotor_inertia: 1.0, stroke: 1}"),
      "linear_drives.lu.stroke", "unknown key 'stroke'", id="drive-key"),
    P(edit(HOIST, "masses: {H: 100}", "masses: {H: {mass: 100, Ixx: 1}}"), "masses.H.Ixx",
      "allowed here: inertia, mass", id="mass-key"),
    P(HOIST + "effects: {sway: false, gravity: 0}\n", "effects.gravity",
      "unknown key 'gravity'", id="effects-key"),
    # -- numbers
    P(edit(HOIST, "EA: 1e7", "EA: abc"), "ropes.r.EA", "must be a number, not text 'abc'",
      id="EA-text"),
    P(edit(HOIST, "EA: 1e7", "EA: '1e7'"), "ropes.r.EA", "without quotes", id="EA-quoted"),
    P(edit(HOIST, "EA: 1e7", "EA: 17 mm"), "ropes.r.EA",
      "17 mm is a length, but EA is a force (N)", id="EA-units"),
    P(edit(HOIST, "EA: 1e7", "EA: true"), "ropes.r.EA", "must be a number, not a boolean",
      id="EA-bool"),
    P(edit(HOIST, "EA: 1e7", "EA: .nan"), "ropes.r.EA", "must be a finite number",
      id="EA-nan"),
    P(edit(HOIST, "EA: 1e7", "EA: .inf"), "ropes.r.EA", "must be a finite number",
      id="EA-inf"),
    P(edit(HOIST, "EA: 1e7", "EA: 1e400"), "ropes.r.EA", "must be a finite number",
      id="EA-overflow"),
    P(edit(HOIST, "H: [0, 0, 0]", "H: [0, 0, -.inf]"), "nodes.H[2]",
      "must be a finite number", id="coordinate-inf"),
    P(edit(HOIST, "H: [0, 0, 0]", "H: [0, 0, .NaN]"), "nodes.H[2]",
      "must be a finite number", id="coordinate-nan"),
    P(edit(HOIST, "H: [0, 0, 0]", "H: [0, 0]"), "nodes.H", "must be a list of 3 numbers",
      id="coordinate-2"),
    P(edit(HOIST, "plane: xz", "plane: xz\ngravity: [0, 0, .nan]"), "gravity[2]",
      "finite", id="gravity-nan"),
    # -- positive where positive is required
    P(edit(HOIST, "EA: 1e7", "EA: 0"), "ropes.r.EA", "give a value > 0", id="EA-zero"),
    P(edit(HOIST, "EA: 1e7", "EA: -1e7"), "ropes.r.EA", "must be positive", id="EA-neg"),
    P(edit(HOIST, "H: 100", "H: 0"), "masses.H", "must be positive", id="mass-zero"),
    P(edit(HOIST, "H: 100", "H: -100"), "masses.H", "must be positive", id="mass-neg"),
    P(edit(CRANE, "mass: 1000,", "mass: -1000,"), "bodies.mast.mass", "must not be negative",
      id="body-mass-neg"),
    # zero rotary inertia is allowed (issue 15: a massless rotation, condensed)
    P(edit(CRANE, "inertia: 1.0e4", "inertia: -5"), "bodies.mast.inertia",
      "must not be negative", id="body-inertia-neg"),
    P(edit(MAST3D, "[1e4, 1e4, 1e2]", "[1e4, 1e4, -1]"), "bodies.mast.inertia",
      "negative principal value", id="inertia3d-neg"),
    P(edit(MAST3D, "[1e4, 1e4, 1e2]", "[[1, 2, 0], [2, 1, 0], [0, 0, 1]]"),
      "bodies.mast.inertia", "negative principal value", id="inertia3d-indefinite"),
    P(edit(MAST3D, "[1e4, 1e4, 1e2]", "[[1, 1, 0], [0, 1, 0], [0, 0, 1]]"),
      "bodies.mast.inertia", "symmetric", id="inertia3d-unsymmetric"),
    P(edit(MAST3D, "[1e4, 1e4, 1e2]", "1e4"), "bodies.mast.inertia",
      "give [Ixx, Iyy, Izz]", id="inertia3d-scalar"),
    P(edit(HOIST, "H: 100", "H: {mass: 100, inertia: -1}"), "masses.H.inertia",
      "must not be negative", id="point-inertia-neg"),
    P(edit(CRANE, "inertia: 1.0e4, ", ""), "bodies.mast", "a body with mass needs 'inertia'",
      id="body-no-inertia"),
    P(edit(CRANE, "stiffness: 1e9", "stiffness: 0"), "springs.bend.stiffness",
      "must be positive", id="spring-stiffness-zero"),
    P(edit(CRANE, "stiffness: 1e6", "stiffness: -1e6"), "springs.sling.stiffness",
      "must be positive", id="spring-stiffness-neg"),
    P(edit(CRANE, "psi: 0.1", "psi: -0.1"), "springs.sling.psi", "must not be negative",
      id="spring-psi-neg"),
    P(edit(HOIST, "radius: 0.2", "radius: 0"), "drums.hoist.radius", "must be positive",
      id="drum-radius-zero"),
    P(edit(HOIST, "radius: 0.2", "radius: -0.2"), "drums.hoist.radius", "must be positive",
      id="drum-radius-neg"),
    P(edit(HOIST, "inertia: 10}", "inertia: 0}"), "drums.hoist.inertia", "must be positive",
      id="drum-inertia-zero"),
    P(edit(HOIST, "inertia: 10}", "inertia: 10, motor: {gear_ratio: 0, rotor_inertia: 1}}"),
      "drums.hoist.motor.gear_ratio", "must be positive", id="gear-ratio-zero"),
    P(edit(HOIST, "inertia: 10}", "inertia: 10, motor: {gear_ratio: 10}}"),
      "drums.hoist.motor", "missing required key 'rotor_inertia'", id="motor-incomplete"),
    P(edit(HOIST, "inertia: 10}", "inertia: 10, brake: 1}"), "drums.hoist.brake",
      "must be true or false", id="brake-int"),
    P(edit(HOIST, "psi: 0.2,", "psi: 0.2, mass_per_length: -1,"),
      "ropes.r.mass_per_length", "must not be negative", id="rope-mass-neg"),
    P(edit(HOIST, "psi: 0.2,", "psi: 0.2, extra_length: -3,"), "ropes.r.extra_length",
      "must not be negative", id="extra-length-neg"),
    P(edit(MEMBERS, "E: 2.1e11, A: 1e-2", "E: 0, A: 1e-2"), "members.m1.E",
      "must be positive", id="member-E-zero"),
    P(edit(MEMBERS, "E: 2.1e11, A: 1e-3", "E: 2.1e11, A: -1e-3"), "members.t1.A",
      "must be positive", id="member-A-neg"),
    P(edit(MEMBERS, "Iy: 1e-4", "Iy: 0"), "members.m1.Iy", "must be positive",
      id="member-Iy-zero"),
    P(edit(MEMBERS, "rho: 7850", "rho: -7850"), "members.m1.rho", "must not be negative",
      id="member-rho-neg"),
    P(edit(MEMBERS, "pinion_radius: 0.2", "pinion_radius: 0"),
      "linear_drives.lu.pinion_radius", "must be positive", id="pinion-zero"),
    # -- geometry
    P(edit(HOIST, "H: [0, 0, 0]", "H: [0, 0, 10]"), "ropes.r.path[2]",
      "span S -> H has zero length", id="zero-span"),
    P(edit(HOIST, "H: [0, 0, 0]", "H: [0, 0.5, 0]"), "nodes.H",
      "off the plane of a plane: xz model", id="off-plane-node"),
    P(edit(CRANE, "com: [0, 0, 5]", "com: [0, 1, 5]"), "bodies.mast.com",
      "off the x-z plane", id="off-plane-com"),
    P(edit(HOIST, "plane: xz", "plane: xz\ngravity: [0, -1, -9.81]"), "gravity",
      "needs gravity with y = 0", id="off-plane-gravity"),
    P(edit(HOIST, "plane: xz", "plane: xy"), "plane", "only 'xz' is supported",
      id="plane-xy"),
    P(edit(CRANE, "at: O}", "at: O, axis: [1, 0, 0]}"), "joints[0].axis",
      "turns about [0, 1, 0]", id="planar-hinge-axis"),
    P(edit(CRANE, "{type: hinge, bodies: [ground, mast], at: O}",
           "{type: slider, bodies: [ground, mast], at: O, axis: [0, 1, 0]}"),
      "joints[0].axis", "slides in the plane", id="planar-slider-axis"),
    P(edit(CRANE, "at: O, stiffness: 1e9}", "at: O, axis: [0, 0, 1], stiffness: 1e9}"),
      "springs.bend.axis", "rotations are about [0, 1, 0]", id="planar-spring-axis"),
    P(edit(CRANE, "nodes: [K, H]", "nodes: [K, K]"), "springs.sling.nodes",
      "the two nodes coincide", id="spring-zero-length"),
    P(edit(MEMBERS, "nodes: [T, A]", "nodes: [T, T]"), "members.m1.nodes[1]",
      "consecutive nodes coincide", id="member-zero-length"),
    P(edit(MEMBERS, "nodes: [A, C]", "nodes: [A, A]"), "linear_drives.lu.nodes",
      "the two nodes coincide", id="drive-coincident"),
    # -- names: unknown, wrong kind, duplicate
    P(edit(HOIST, "path: [hoist, S,", "path: [hoist, X,"), "ropes.r.path[1]",
      "unknown node or drum 'X'; known: H, S, W, hoist", id="path-unknown"),
    P(edit(CRANE, "stiffness: 1e6", "stiffness: 1e6}\n"
           "  - {type: axial, nodes: [K, jib], stiffness: 1e6"), "springs[2].nodes[1]",
      "'jib' is a body, not a node", id="body-as-node"),
    P(edit(HOIST, "path: [hoist, S,", "path: [r, S,"), "ropes.r.path[0]",
      "'r' is a rope, not a node or drum", id="rope-as-node"),
    P(edit(HOIST, "{node: H, falls: 2}", "{node: hoist, falls: 2}"), "ropes.r.path[2].node",
      "'hoist' is a drum, not a node", id="drum-as-tackle"),
    P(edit(CRANE, "bodies: [ground, mast], at: O}", "bodies: [ground, O], at: O}"),
      "joints[0].bodies[1]", "'O' is a node, not a body", id="node-as-body"),
    P(edit(CRANE, "bodies: [ground, mast], at: O}", "bodies: [ground, mast], at: mast}"),
      "joints[0].at", "'mast' is a body, not a node", id="body-as-at"),
    P(edit(CRANE, "com: [0, 0, 5]", "com: jib"), "bodies.mast.com",
      "'jib' is a body, not a node", id="body-as-com"),
    P(edit(CRANE, "bodies: [ground, mast], at: O}", "bodies: [ground, boom], at: O}"),
      "joints[0].bodies[1]", "unknown body 'boom'; known: jib, mast", id="unknown-body"),
    P(edit(HOIST, "masses: {H: 100}", "masses: {X: 100}"), "masses.X", "unknown node 'X'",
      id="unknown-mass-node"),
    P(edit(HOIST, "ground: [W, S]", "ground: [W, S, W]"), "ground[2]",
      "node 'W' is listed twice", id="ground-twice"),
    P(edit(HOIST, "hoist: {node: W", "S: {node: W"), "drums.S",
      "also a node name", id="drum-named-like-node"),
    P(edit(HOIST, "{node: W", "{node: X"), "drums.hoist.node", "unknown node 'X'",
      id="drum-unknown-node"),
    P(edit(CRANE, "name: sling", "name: bend"), "springs[1].name",
      "spring name 'bend' is used twice", id="spring-name-twice"),
    P(edit(CRANE, "  mast:", "  ground:", "[ground, mast], at: O}", "[ground, jib], at: O}",
           "mast, jib", "ground, jib", "[ground, mast], at: O, stiffness",
           "[ground, jib], at: O, stiffness"),
      "bodies.ground", "name of the fixed frame; rename the body", id="body-named-ground"),
    # -- rope paths
    P(edit(HOIST, "[hoist, S, {node: H, falls: 2}]", "[S, hoist, H]"), "ropes.r.path[1]",
      "drum 'hoist' in the middle of the path", id="drum-mid-path"),
    P(edit(HOIST, "[hoist, S, {node: H, falls: 2}]", "[{node: H, falls: 2}, S, hoist]"),
      "ropes.r.path[0]", "a tackle needs a previous point", id="tackle-first"),
    P(edit(HOIST, "falls: 2", "falls: 0"), "ropes.r.path[2].falls", "must be at least 1",
      id="falls-0"),
    P(edit(HOIST, "falls: 2", "falls: 1.5"), "ropes.r.path[2].falls",
      "must be a whole number", id="falls-1.5"),
    P(edit(HOIST, "falls: 2", "falls: -2"), "ropes.r.path[2].falls", "must be at least 1",
      id="falls-neg"),
    P(edit(HOIST, "{node: H, falls: 2}", "{node: H}"), "ropes.r.path[2]",
      "missing required key 'falls'", id="tackle-no-falls"),
    P(edit(HOIST, "path: [hoist, S, {node: H, falls: 2}]", "path: [hoist]"), "ropes.r.path",
      "at least 2 entries", id="path-one-entry"),
    P(edit(HOIST, "[hoist, S, {node: H, falls: 2}]", "hoist"), "ropes.r.path",
      "must be a list", id="path-not-list"),
    P(edit(HOIST, "path: [hoist, S,", "path: [hoist, 3,"), "ropes.r.path[1]",
      "must name a node or drum", id="path-number"),
    P(edit(HOIST, "EA: 1e7, ", ""), "ropes.r", "missing required key 'EA'",
      id="rope-no-EA"),
    # -- nodes shared by bodies and ground
    P(edit(CRANE, "  - {type: fixed, bodies: [mast, jib], at: T}\n", ""), "bodies.jib.nodes[0]",
      "node 'T' is also carried by body 'mast'", id="node-on-two-bodies"),
    P(edit(CRANE, "at: T}", "at: K}"), "bodies.jib.nodes[0]", "add a joint at 'T'",
      id="node-on-two-bodies-joint-elsewhere"),
    P(edit(CRANE, "ground: [O]", "ground: [O, K]"), "bodies.jib.nodes[1]",
      "node 'K' is also in ground", id="ground-node-on-body"),
    # -- joints
    P(edit(CRANE, "bodies: [ground, mast], at: O}", "bodies: [mast], at: O}"),
      "joints[0].bodies", "exactly two bodies", id="joint-one-body"),
    P(edit(CRANE, "bodies: [mast, jib]", "bodies: [mast, mast]"), "joints[1].bodies",
      "found 'mast' twice", id="joint-same-body"),
    P(edit(CRANE, "type: hinge", "type: pin"), "joints[0].type",
      "use one of fixed, hinge, ball, slider", id="joint-type"),
    P(edit(CRANE, "{type: hinge, bodies: [ground, mast], at: O}",
           "{bodies: [ground, mast], at: O}"), "joints[0]", "missing required key 'type'",
      id="joint-no-type"),
    P(edit(CRANE, "at: O}", "at: X}"), "joints[0].at", "unknown node 'X'",
      id="joint-unknown-node"),
    P(edit(MAST3D, ", axis: [0, 1, 0]}\nsprings", "}\nsprings"), "joints[0].axis",
      "needs 'axis: [x, y, z]'", id="hinge-3d-no-axis"),
    P(edit(MAST3D, "type: hinge", "type: slider", ", axis: [0, 1, 0]}\nsprings", "}\nsprings"),
      "joints[0].axis", "slides along", id="slider-3d-no-axis"),
    P(edit(MAST3D, "type: hinge", "type: ball"), "joints[0].axis",
      "a ball joint has no axis; remove it", id="ball-axis"),
    P(edit(MAST3D, "type: hinge", "type: fixed"), "joints[0].axis",
      "a fixed joint has no axis", id="fixed-axis"),
    P(edit(MAST3D, "at: O, axis: [0, 1, 0]", "at: O, axis: [0, 0, 0]"), "joints[0].axis",
      "must not be the zero vector", id="axis-zero"),
    P(edit(MAST3D, "at: O, axis: [0, 1, 0]", "at: O, axis: [0, 1]"), "joints[0].axis",
      "must be a list of 3 numbers", id="axis-short"),
    # -- springs
    P(edit(CRANE, "type: rotational", "type: torsion"), "springs.bend.type",
      "use axial or rotational", id="spring-type"),
    P(edit(CRANE, "type: rotational", "type: axial"), "springs.bend.bodies",
      "an axial spring joins two nodes; use 'nodes'", id="axial-with-bodies"),
    P(edit(CRANE, "type: axial", "type: rotational"), "springs.sling.nodes",
      "a rotational spring joins two bodies; use 'bodies'", id="rotational-with-nodes"),
    P(edit(CRANE, "nodes: [K, H]", "nodes: [K]"), "springs.sling.nodes",
      "exactly two nodes", id="axial-one-node"),
    P(edit(CRANE, "bodies: [ground, mast], at: O, stiffness",
           "bodies: [mast, mast], at: O, stiffness"), "springs.bend.bodies",
      "two different bodies", id="rotational-same-body"),
    P(edit(MAST3D, "axis: [0, 1, 0], stiffness", "stiffness"), "springs[0].axis",
      "needs 'axis: [x, y, z]'", id="rotational-3d-no-axis"),
    P(edit(CRANE, ", stiffness: 1e6", ""), "springs.sling",
      "missing required key 'stiffness'", id="spring-no-stiffness"),
    # -- members
    P(edit(MEMBERS, "A: 1e-3}", "A: 1e-3, elements: 2}"), "members.t1.elements",
      "a subdivided truss would be a mechanism; use 1", id="truss-elements"),
    P(edit(MEMBERS, "rho: 7850}", "rho: 7850, elements: 0}"), "members.m1.elements",
      "must be at least 1", id="beam-elements-0"),
    P(edit(MEMBERS, "Iy: 1e-4, ", ""), "members.m1", "a beam needs 'Iy'",
      id="beam-no-Iy"),
    P(edit(MEMBERS, "A: 1e-3}", "A: 1e-3, Iy: 1e-4}"), "members.t1.Iy",
      "a truss has only axial stiffness; remove it", id="truss-Iy"),
    P(edit(MEMBERS, "rho: 7850}", "rho: 7850, mass: diagonal}"), "members.m1.mass",
      "'diagonal' is not consistent or lumped", id="member-mass-option"),
    P(edit(MEMBERS, "type: beam", "type: cable"), "members.m1.type",
      "use beam or truss", id="member-type"),
    P(edit(MEMBERS, "nodes: [T, A]", "nodes: [T]"), "members.m1.nodes",
      "at least 2 entries", id="member-one-node"),
    P(edit(MEMBERS, "nodes: [T, A]", "nodes: [T, mast]"), "members.m1.nodes[1]",
      "'mast' is a body, not a node", id="member-body-node"),
    P(edit(MEMBERS, ", gear_ratio: 100", ""), "linear_drives.lu",
      "missing required key 'gear_ratio'", id="drive-no-gear"),
    P(edit(MEMBERS, "nodes: [A, C]", "nodes: [A]"), "linear_drives.lu.nodes",
      "between two nodes", id="drive-one-node"),
    # -- effects in a model file
    P(HOIST + "effects: {rope_mass: -1}\n", "effects.rope_mass", "must be at least 0",
      id="rope-mass-neg-effect"),
    P(HOIST + "effects: {rope_mass: 1.5}\n", "effects.rope_mass", "must be a whole number",
      id="rope-mass-fraction"),
    P(HOIST + "effects: {drive: foo}\n", "effects.drive",
      "'foo' is not one of coupled, held, reduced", id="drive-foo"),
    P(HOIST + "effects: {damping: rayleigh}\n", "effects.damping",
      "is not one of none, modal, exact", id="damping-option"),
    P(HOIST + "effects: {structure: soft}\n", "effects.structure",
      "is not one of rigid, flexible", id="structure-option"),
    P(HOIST + "effects: {sway: maybe}\n", "effects.sway", "must be true or false",
      id="sway-text"),
    P(HOIST + "effects: sway\n", "effects", "must be a mapping such as {sway: false}",
      id="effects-not-mapping"),
]


@pytest.mark.parametrize("text, entry, message", CASES)
def test_bad_model(tmp_path, capsys, text, entry, message):
    assert_bad(write(tmp_path, text), capsys, entry, message)


@pytest.mark.parametrize("text, entry, message", [
    P(edit(CRANE, "ground: [O]", "ground: [O, K]"), "bodies.jib.nodes[1]",
      "also in ground", id="load-error"),
    P(HOIST + "foo: 1\n", "foo", "unknown key", id="unknown-key"),
    P(edit(HOIST, "EA: 1e7", "EA: 1 e7"), "ropes.r.EA", "must be a number", id="number"),
])
def test_bad_model_modes(tmp_path, capsys, text, entry, message):
    """`cranefe modes` reports the same errors as `cranefe check`."""
    assert_bad(write(tmp_path, text), capsys, entry, message, command="modes")


# ------------------------------------------------------------------ good input passes

@pytest.mark.parametrize("name", BASES)
@pytest.mark.parametrize("command", ["check", "modes"])
def test_base_models_are_good(tmp_path, capsys, name, command):
    status, both, _ = run(write(tmp_path, BASES[name]), capsys, command)
    assert status == 0, both
    assert "error" not in both


@pytest.mark.parametrize("text", ["1e7", "1E7", "1e+7", "2.0e7", "1.0E+07", "10_000_000",
                                  "10000000", "1.e7"])
def test_exponent_numbers_are_numbers(tmp_path, capsys, text):
    """YAML 1.1 reads 1e7 as text; the contract says it is a number."""
    expected = 2.0e7 if text == "2.0e7" else 1e7
    path = write(tmp_path, edit(HOIST, "EA: 1e7", f"EA: {text}"))
    assert load(path).ropes[0].EA == expected
    status, both, _ = run(path, capsys)
    assert status == 0, both


def test_merge_key_and_aliases_are_fine(tmp_path, capsys):
    """Aliases and '<<' merges are YAML, not errors; an explicit key beats a merged one."""
    text = edit(CRANE, "  mast: {mass: 1000,", "  mast: {<<: {mass: 5, psi: 1}, mass: 1000,")
    text = edit(text, "jib: {mass: 500, com: K, inertia: 2.0e3",
                "jib: {mass: 500, com: K, inertia: &i 2.0e3")
    text = text.replace("<<: {mass: 5, psi: 1}", "<<: {mass: 5}")
    path = write(tmp_path, text)
    assert load(path).bodies[0].mass == 1000
    assert run(path, capsys)[0] == 0


# ------------------------------------------------------------------------ the file

def test_file_not_found(tmp_path, capsys):
    assert_bad(tmp_path / "nope.yaml", capsys, "", "file not found; check the path")


def test_path_is_a_directory(tmp_path, capsys):
    assert_bad(tmp_path, capsys, "", "is a directory, not a model file")


def test_not_utf8(tmp_path, capsys):
    path = tmp_path / "m.yaml"
    path.write_bytes(HOIST.encode() + b"name: \xff\xfe\n")
    assert_bad(path, capsys, "", "not UTF-8 text")


def test_control_character(tmp_path, capsys):
    path = tmp_path / "m.yaml"
    path.write_bytes(HOIST.encode() + b"name: a\x00b\n")
    assert_bad(path, capsys, "line 10", "is not allowed in YAML")


def test_alias_bomb_is_refused_quickly(tmp_path, capsys):
    """Billion laughs: 9 levels of 9 aliases each would expand to 9**9 entries."""
    lines = [HOIST.rstrip("\n"), "name: &a [lol, lol, lol, lol, lol, lol, lol, lol, lol]"]
    prev = "a"
    for k, c in enumerate("bcdefghi"):
        lines.append(f"x{k}: &{c} [" + ", ".join([f"*{prev}"] * 9) + "]")
        prev = c
    path = write(tmp_path, "\n".join(lines) + "\n")
    t0 = time.perf_counter()
    assert_bad(path, capsys, "", "expands (through aliases '*name') to more than")
    assert time.perf_counter() - t0 < 2.0


def test_deep_nesting(tmp_path, capsys):
    path = write(tmp_path, HOIST + "name: " + "[" * 3000 + "]" * 3000 + "\n")
    status, both, err = run(path, capsys)
    assert status == 2 and "Traceback" not in both and str(path) in err


# ------------------------------------------------------------------------ scenes

SCENE = yaml("""
    cranefe: 1
    scene: hoist without sway
    model: model.yaml
    effects: {sway: false}
    analysis: {type: modes, count: 2}
""")

SCENE_CASES = [
    P(edit(SCENE, "model.yaml", "missing.yaml"), "model",
      "model file 'missing.yaml' not found", id="missing-model"),
    P(edit(SCENE, "model.yaml", "."), "model", "is a directory", id="model-directory"),
    P(edit(SCENE, "model.yaml", "scene.yaml"), "model", "is a scene, not a model file",
      id="scene-names-itself"),
    P(edit(SCENE, "model: model.yaml", "model: 3"), "model",
      "must be the path of a model file", id="model-number"),
    P(edit(SCENE, "type: modes", "type: buckling"), "analysis.type",
      "unknown analysis type 'buckling'; use one of modes", id="analysis-type"),
    P(edit(SCENE, "count: 2", "count: 0"), "analysis.count", "must be at least 1",
      id="count-0"),
    P(edit(SCENE, "count: 2", "count: 2.5"), "analysis.count", "must be a whole number",
      id="count-fraction"),
    P(edit(SCENE, "count: 2}", "count: 2, modes: 3}"), "analysis.modes",
      "unknown key 'modes'", id="analysis-key"),
    P(edit(SCENE, "analysis: {type: modes, count: 2}", "analysis: modes"), "analysis",
      "must be a mapping", id="analysis-not-mapping"),
    P(edit(SCENE, "{sway: false}", "{drive: foo}"), "effects.drive",
      "'foo' is not one of coupled, held, reduced", id="effects-drive"),
    P(edit(SCENE, "{sway: false}", "{rope_mass: -1}"), "effects.rope_mass",
      "must be at least 0", id="effects-rope-mass-neg"),
    P(edit(SCENE, "{sway: false}", "{rope_mass: 0.5}"), "effects.rope_mass",
      "must be a whole number", id="effects-rope-mass-fraction"),
    P(edit(SCENE, "{sway: false}", "{swing: false}"), "effects.swing",
      "unknown key 'swing'", id="effects-key"),
    P(SCENE + "nodes: {A: [0, 0, 0]}\n", "nodes", "unknown key 'nodes'", id="scene-key"),
    P(edit(SCENE, "cranefe: 1\n", ""), "cranefe", "start the file with 'cranefe: 1'",
      id="scene-no-version"),
    P(edit(SCENE, "scene: hoist without sway\n", "scene: x\nscene: y\n"), "scene, line 3",
      "repeated", id="scene-duplicate-key"),
]


@pytest.mark.parametrize("command", ["check", "modes"])
@pytest.mark.parametrize("text, entry, message", SCENE_CASES)
def test_bad_scene(tmp_path, capsys, text, entry, message, command):
    write(tmp_path, HOIST, "model.yaml")
    assert_bad(write(tmp_path, text, "scene.yaml"), capsys, entry, message, command)


def test_scene_reports_errors_of_its_model(tmp_path, capsys):
    """An error in the model a scene names points at the model file."""
    model = write(tmp_path, edit(HOIST, "EA: 1e7", "EA: abc"), "model.yaml")
    write(tmp_path, SCENE, "scene.yaml")
    status, both, err = run(tmp_path / "scene.yaml", capsys)
    assert status == 2 and "Traceback" not in both
    assert str(model) in err and "ropes.r.EA" in err


def test_good_scene(tmp_path, capsys):
    write(tmp_path, HOIST, "model.yaml")
    for command in ("check", "modes"):
        status, both, _ = run(write(tmp_path, SCENE, "scene.yaml"), capsys, command)
        assert status == 0, both


# ------------------------------------------------ model-level errors found by analysis

# S -> B -> H: two ropes meeting at a massless node B.
JUNCTION = yaml("""
    cranefe: 1
    plane: xz
    nodes: {S: [0, 0, 10], B: [0, 0, 5], H: [0, 0, 0]}
    ground: [S]
    masses: {H: 100}
    ropes:
      r1: {EA: 1e7, path: [S, B]}
      r2: {EA: 1e7, path: [B, H]}
""")

OFFSET_JUNCTION = edit(JUNCTION, "B: [0, 0, 5]", "B: [3, 0, 5]", "H: [0, 0, 0]", "H: [3, 0, 0]")

ANALYSIS_CASES = [
    # a massless node on one slack rope: nothing holds it sideways (sway on, zero tension)
    P(edit(JUNCTION, "masses: {H: 100}\n", "", "  r2: {EA: 1e7, path: [B, H]}\n", "",
           "H: [0, 0, 0]", "H: [1, 0, 0]"),
      "nodes.B", "massless and unrestrained", id="massless-one-rope"),
    # the same junction with no load: both ropes slack, B free sideways
    P(edit(JUNCTION, "masses: {H: 100}\n", ""), "nodes.B", "attach a rope or spring",
      id="massless-slack-junction"),
    # a load hung from one inclined rope is not in equilibrium in the reference geometry
    P(edit(HOIST, "H: [0, 0, 0]", "H: [4, 0, 0]"), "nodes.H",
      "not in static equilibrium", id="inclined-hanging-load"),
    # a massless junction off the vertical: it would swing under the load
    P(OFFSET_JUNCTION, "", "not in static equilibrium: gravity moves node B",
      id="offset-massless-junction"),
]


@pytest.mark.parametrize("command", ["check", "modes"])
@pytest.mark.parametrize("text, entry, message", ANALYSIS_CASES)
def test_model_errors_found_by_analysis(tmp_path, capsys, text, entry, message, command):
    assert_bad(write(tmp_path, text), capsys, entry, message, command)


@pytest.mark.parametrize("command", ["check", "modes"])
def test_junction_is_good(tmp_path, capsys, command):
    """The massless junction is fine when a load keeps its ropes taut, with or without
    sway (without sway it moves only along its ropes)."""
    for text in (JUNCTION, JUNCTION + "effects: {sway: false}\n"):
        status, both, _ = run(write(tmp_path, text), capsys, command)
        assert status == 0, both


# ------------------------------------------- found by the analysis stages

def test_static_mechanism_names_the_node(tmp_path, capsys):
    assert_bad(write(tmp_path, OFFSET_JUNCTION), capsys, "nodes.B",
               "not in static equilibrium")


def test_model_without_inertia_is_an_error_not_a_traceback(tmp_path, capsys):
    text = edit(JUNCTION, "masses: {H: 100}\n", "", "  r2: {EA: 1e7, path: [B, H]}\n", "")
    path = write(tmp_path, text + "effects: {sway: false}\n")
    status, both, err = run(path, capsys, "modes")
    assert "Traceback" not in both and status in (1, 2) and str(path) in err


def test_fixed_joint_to_ground_is_valid(tmp_path, capsys):
    text = edit(CRANE, "{type: hinge, bodies: [ground, mast], at: O}",
                "{type: fixed, bodies: [ground, mast], at: O}",
                "  - {name: bend, type: rotational, bodies: [ground, mast], at: O, "
                "stiffness: 1e9}\n", "")
    status, both, _ = run(write(tmp_path, text), capsys)
    assert status == 0, both


def test_member_through_joint_node_is_valid(tmp_path, capsys):
    text = edit(MEMBERS, "nodes: [T, A]", "nodes: [O, T]")
    status, both, _ = run(write(tmp_path, text), capsys)
    assert status == 0, both
