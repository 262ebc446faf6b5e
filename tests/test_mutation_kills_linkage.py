"""Value tests of cranefe/analysis/operation/linkage.py (issue 20, mutation testing):
luffing by a linear drive in an operation scene, against hand geometry.

The linkage: a four-bar in the x-z plane, the boom O-E-B hinged to the ground at O, a
coupler (tie) E-Q-C hinged to the boom at E and to a rocker G-Q at Q, the rocker hinged
to the ground at G; a cylinder from A (ground) to C on the coupler, so the drive's end
moves with a body other than the boom. Hand geometry, with the boom turned by
theta = alpha - alpha_ref about O (alpha the angle of O -> B):

    E(alpha) = O + Rot(theta) (E0 - O),
    Q = the intersection of the circles |Q - G| = |Q0 - G| and |Q - E| = |Q0 - E0| on
        the reference's side (G + a dv + h perp(dv), dv = E - G,
        a = (r1^2 - r2^2 + |dv|^2) / (2 |dv|^2), h = sqrt(r1^2 / |dv|^2 - a^2)),
    the coupler's and the rocker's rotations the ones taking Q0 - E0 to Q - E and
    Q0 - G to Q - G (cos = u0.u / |u|^2, sin = u0 x u / |u|^2),
    every node X = Rot X0 + p of its body; d(alpha) = |C(alpha) - A|.

alpha(t) solves d(alpha) = d_ref + s(t) (scipy's brentq, xtol 1e-15), and implicit
differentiation of d(alpha(t)) = d_ref + s(t) gives alpha' = s' / d_alpha,
alpha'' = (s'' - d_alphaalpha alpha'^2) / d_alpha. The alpha-derivatives of the hand
maps (orders 1, 2) come from Cauchy's integral formula (32 samples on a circle of
radius 0.02 rad about alpha; every formula above is analytic in alpha: aliasing
0.02^32, round-off 1e-16 / 0.02^2 ~ 3e-13 of the maps' size), not from the code's
implicit differentiation of the closure equations.

Tolerances: alpha to 1e-11 rad (Newton stops at |d - target| < 1e-13 of the linkage's
size, ~1e-12 m, over d_alpha ~ 4 m/rad); the rates, the maps and their time derivatives
to 1e-9 of their size (the derivative references' round-off above, times the chain
rule's factors of O(10)).
"""

import numpy as np
import pytest
from scipy.optimize import brentq

from cranefe.analysis.operation.linkage import LinkageDrive, _rot3
from cranefe.analysis.operation.scene import parse
from cranefe.errors import AnalysisError, ModelError
from cranefe.model import load

MODEL = """cranefe: 1
name: four-bar luffed by a cylinder on its coupler
plane: xz
nodes:
  O: [1, 0, 2]
  E: [5, 0, 6]
  B: [11, 0, 12]
  G: [-3, 0, 8]
  Q: [-0.5, 0, 10]
  C: [2, 0, 9]
  A: [AX, 0, AZ]
  H: [11, 0, 5]
ground: [O, G, GA]
masses: {H: 1000}
bodies:
  boom: {mass: 2000, com: [6, 0, 7], inertia: 2.0e4, nodes: [O, E, B]}
  tie: {mass: 100, com: [2, 0, 8], inertia: 50, nodes: [E, Q, C]}
  rocker: {mass: 300, com: [-2, 0, 9], inertia: 100, nodes: [G, Q]}
joints:
  - {name: foot, type: hinge, bodies: [boom, ground], at: O, axis: [0, 1, 0]FOOT}
  - {name: te, type: hinge, bodies: [boom, tie], at: E, axis: [0, 1, 0]TE}
  - {name: tq, type: hinge, bodies: [tie, rocker], at: Q, axis: [0, 1, 0]}
  - {name: pivot, type: hinge, bodies: [ground, rocker], at: G, axis: [0, -1, 0]PIVOT}
linear_drives:
  cyl: {nodes: [A, C], pinion_radius: 0.1, gear_ratio: 10}
ropes:
  hoist: {EA: 1.0e6, path: [B, H]}
"""
# the trapezoid: 0.1 m/s^2 for 2 s, 0.2 m/s for 0.5 s, -0.1 m/s^2 for 2 s (0.5 m)
SCENE = """cranefe: 1
scene: t
model: {model}
analysis:
  type: operation
  duration: 6
  drives:
    c: {{linear: cyl, profile: {{type: trapezoid, distance: DIST, v_max: 0.2,
                                 a_max: 0.1}}}}
"""
NODES = {k: np.array(v, float) for k, v in dict(
    O=[1, 2], E=[5, 6], B=[11, 12], G=[-3, 8], Q=[-0.5, 10], C=[2, 9]).items()}
A_NODE = np.array([2.0, -3.0])               # the cylinder's ground end (x, z)
ALPHA_REF = np.arctan2(10.0, 10.0)           # O -> B
BODY_NODES = {"boom": "OEB", "tie": "EQC", "rocker": "GQ"}


def drive_of(tmp_path, dist=0.5, foot="", pivot="", a=A_NODE, planar=True,
             a_on=None, te=""):
    """The scene's model and drive; `a_on="boom"`: A on the boom, not the ground."""
    model = MODEL.replace("AX", str(a[0])).replace("AZ", str(a[1]))
    model = model.replace("G, GA]", "G]" if a_on else "G, A]")
    model = model.replace("nodes: [O, E, B]", "nodes: [O, E, B, A]" if a_on else
                          "nodes: [O, E, B]")
    model = model.replace("FOOT", foot).replace("PIVOT", pivot).replace("TE", te)
    if not planar:
        model = model.replace("plane: xz\n", "")
    mp = tmp_path / "fourbar.yaml"
    mp.write_text(model)
    sp = tmp_path / "scene.yaml"
    sp.write_text(SCENE.format(model=mp).replace("DIST", str(dist)))
    m = load(str(sp))
    spec = parse(m)
    return m, spec.drives[0]


# ------------------------------------------------------------------ hand geometry

def _maps(alpha, a=A_NODE, a_on=None):
    """{body: (R (2, 2), p (2,))} with X = R X0 + p, and d(alpha); alpha may be complex
    (every step analytic); A at `a` on the ground, or on the body `a_on`."""
    N = NODES
    th = alpha - ALPHA_REF
    c, s = np.cos(th), np.sin(th)

    def rot(c, s, v):
        return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])
    E = N["O"] + rot(c, s, N["E"] - N["O"])
    r1 = np.linalg.norm(N["Q"] - N["G"])
    r2 = np.linalg.norm(N["Q"] - N["E"])
    dv = E - N["G"]
    L2 = dv[0] ** 2 + dv[1] ** 2
    aa = (r1 ** 2 - r2 ** 2 + L2) / (2 * L2)
    h = np.sqrt(r1 ** 2 / L2 - aa ** 2)
    Q = N["G"] + aa * dv + h * np.array([-dv[1], dv[0]])

    def turn(u0, u):
        L2 = u0 @ u0
        return (u0 @ u) / L2, (u0[0] * u[1] - u0[1] * u[0]) / L2
    out = {}
    for name, (cc, ss), X0, X in (("boom", (c, s), N["O"], N["O"]),
                                  ("tie", turn(N["Q"] - N["E"], Q - E), N["E"], E),
                                  ("rocker", turn(N["Q"] - N["G"], Q - N["G"]), N["G"],
                                   N["G"])):
        R = np.array([[cc, -ss], [ss, cc]])
        out[name] = (R, X - R @ X0)
    Rt, pt = out["tie"]
    C = Rt @ N["C"] + pt
    if a_on:
        Ra, pa = out[a_on]
        a = Ra @ a + pa
    d = np.sqrt((C[0] - a[0]) ** 2 + (C[1] - a[1]) ** 2)
    return out, d


def _flat(alpha, a=A_NODE, a_on=None):
    out, d = _maps(alpha, a, a_on)
    return np.concatenate([np.concatenate([R.ravel(), p]) for R, p in
                           (out[b] for b in BODY_NODES)] + [np.atleast_1d(d)])


def _derivs(alpha, a=A_NODE, a_on=None):
    """(f, f', f'') of the flattened maps and d by Cauchy's formula (module docstring)."""
    n, r = 32, 0.02
    z = alpha + r * np.exp(2j * np.pi * np.arange(n) / n)
    F = np.array([_flat(zk, a, a_on) for zk in z])
    c = np.fft.fft(F, axis=0) / n
    return _flat(alpha, a, a_on), (c[1] / r).real, (2 * c[2] / r ** 2).real


def _reference(t, motion, a=A_NODE, a_on=None):
    """alpha, alpha', alpha'' and every body's (R, R', R'', p, p', p'') in time."""
    s, ds, dds = motion(t)
    d_ref = float(np.linalg.norm(NODES["C"] - a))
    al = brentq(lambda x: _maps(x, a, a_on)[1] - (d_ref + s), ALPHA_REF - 0.3,
                ALPHA_REF + 0.3, xtol=1e-15)
    f, f1, f2 = _derivs(al, a, a_on)
    d1, d2 = f1[-1], f2[-1]
    a1 = ds / d1
    a2 = (dds - d2 * a1 ** 2) / d1
    ft = f1 * a1                              # d/dt and d^2/dt^2 by the chain rule
    ftt = f2 * a1 ** 2 + f1 * a2
    maps = {}
    for k, b in enumerate(BODY_NODES):
        sl = slice(6 * k, 6 * k + 6)
        maps[b] = [(g[sl][:4].reshape(2, 2), g[sl][4:]) for g in (f, ft, ftt)]
    return al, a1, a2, maps


def _xz(M3):
    return M3[np.ix_([0, 2], [0, 2])]


TIMES = (0.0, 1.3, 2.2, 3.7, 5.0)             # rest, accelerating, cruising, braking, end


@pytest.mark.parametrize("a_on", [None, "boom"])
def test_angle_rates_and_body_motions_against_hand_geometry(tmp_path, a_on):
    """The cylinder from the ground (A at (2, -3)) or from the boom (A at (8, 9): both
    ends move, d' = e . (C' - A'), d'' with C'' - A'')."""
    a = np.array([8.0, 9.0]) if a_on else A_NODE
    model, drive = drive_of(tmp_path, a=a, a_on=a_on)
    ld = LinkageDrive(model, drive, {})
    names = [b.name for b in model.bodies]
    assert sorted(ld.bodies) == [0, 1, 2]
    assert ld.d_ref == pytest.approx(np.linalg.norm(NODES["C"] - a), abs=1e-12)
    for t in TIMES:
        al, a1, a2, maps = _reference(t, drive.motion, a, a_on)
        got = ld.solve(t)
        assert abs(got[0] - al) < 1e-11, t
        assert abs(got[1] - a1) < 1e-9 * max(1.0, abs(a1)), t
        assert abs(got[2] - a2) < 1e-9, t
        assert abs(ld.angle(t) - al) < 1e-11
        mot = ld.motions(t)
        assert sorted(mot) == [0, 1, 2]
        for b, (R3, dR3, ddR3, p3, dp3, ddp3) in mot.items():
            (R, p), (dR, dp), (ddR, ddp) = maps[names[b]]
            for got3, ref in ((R3, R), (dR3, dR), (ddR3, ddR)):
                assert np.allclose(_xz(got3), ref, rtol=0, atol=1e-9), (t, b)
            assert R3[1, 1] == 1.0 and not dR3[1].any() and not ddR3[1].any()
            for got3, ref in ((p3, p), (dp3, dp), (ddp3, ddp)):
                assert np.allclose(got3[[0, 2]], ref, rtol=0, atol=1e-9 * 20), (t, b)
                assert got3[1] == 0.0
            # and the nodes: X = R X0 + p of the body's own nodes
            for nd in BODY_NODES[names[b]]:
                X0 = model.coords[model.node_index[nd]]
                assert np.allclose((R3 @ X0 + p3)[[0, 2]], R @ NODES[nd] + p, atol=1e-9)


def test_motions_are_kept_for_the_same_drive_state_and_remade_for_another(tmp_path):
    model, drive = drive_of(tmp_path)
    ld = LinkageDrive(model, drive, {})
    m1 = ld.motions(1.3)
    assert ld.motions(1.3) is m1
    m2 = ld.motions(2.2)
    al, a1, a2, maps = _reference(2.2, drive.motion)
    assert np.allclose(_xz(m2[0][0]), maps["boom"][0][0], atol=1e-9)
    # back to the first time: recomputed (not the cached second), the same values
    m3 = ld.motions(1.3)
    assert np.allclose(m3[1][1], m1[1][1], atol=1e-12)


def test_rot3_and_its_derivatives():
    """x turning toward z: R (1, 0, 0) = (cos, 0, sin); R' and R'' by hand."""
    th = 0.7
    R, dR, ddR = _rot3(th)
    c, s = np.cos(th), np.sin(th)
    assert np.allclose(R @ [1, 0, 0], [c, 0, s], atol=1e-15)
    assert np.allclose(R @ [0, 0, 1], [-s, 0, c], atol=1e-15)
    assert np.allclose(R @ [0, 1, 0], [0, 1, 0], atol=1e-15)
    assert np.allclose(dR, [[-s, 0, -c], [0, 0, 0], [c, 0, -s]], atol=1e-15)
    assert np.allclose(ddR, -R + np.diag([0, 1, 0]), atol=1e-15)


# ------------------------------------------------------------------ hinge ranges

def _turns(motion, duration=6.0):
    """The boom's and the rocker's rotations (rad, x toward z) at the stroke's ends
    (monotonic between: d_alpha > 0 over the range, the rotations monotonic in alpha)."""
    th = []
    for t in (0.0, duration):
        al, _, _, maps = _reference(t, motion)
        th.append({b: np.arctan2(maps[b][0][0][1, 0], maps[b][0][0][0, 0]) for b in maps})
    return th


def test_check_range_passes_inside_and_resets_the_solution(tmp_path):
    model, drive = drive_of(tmp_path, foot=", range_deg: [-20, 20]",
                            pivot=", range_deg: [-30, 30]")
    ld = LinkageDrive(model, drive, {})
    ld.check_range(6.0)
    al, a1, a2, _ = _reference(3.7, drive.motion)
    got = ld.solve(3.7)
    assert abs(got[0] - al) < 1e-11 and abs(got[2] - a2) < 1e-9


@pytest.mark.parametrize("which", ["foot", "pivot", "te"])
def test_check_range_names_the_turn_past_the_range(tmp_path, which):
    """The foot joins [boom, ground] about +y: the ground's turn relative to the boom,
    -(0 - theta_boom) = +theta_boom (a turn about +y takes x toward -z); the pivot
    joins [ground, rocker] about -y: its turn is +theta_rocker; te joins [boom, tie]
    about +y: -(theta_tie - theta_boom). Each range cut at half the turn."""
    model0, drive0 = drive_of(tmp_path)
    th0, th1 = _turns(drive0.motion)
    f = 180 / np.pi
    turn = {"foot": th1["boom"], "pivot": th1["rocker"],
            "te": -(th1["tie"] - th1["boom"])}[which]
    assert abs(turn) > 0.01
    lo, hi = sorted((0.0, turn * f))
    cut = [-40, round(hi / 2, 4)] if turn > 0 else [round(lo / 2, 4), 40]
    rng = f", range_deg: [{cut[0]}, {cut[1]}]"
    model, drive = drive_of(tmp_path, **{which: rng})
    ld = LinkageDrive(model, drive, {})
    with pytest.raises(ModelError) as exc:
        ld.check_range(6.0)
    msg = str(exc.value)
    assert f"[{lo + 0.0:.6g}, {hi + 0.0:.6g}] deg within 6 s" in msg, msg
    assert f"past the end of its range [{cut[0]:g}, {cut[1]:g}] deg" in msg, msg
    assert f"hinge '{which}'" in msg or which in msg
    assert exc.value.file == model.scene_file
    assert exc.value.entry == f"{drive.entry}.profile"
    # the solution is reset after the check: the next solve starts from the reference
    got = ld.solve(1.3)
    al, a1, a2, _ = _reference(1.3, drive.motion)
    assert abs(got[0] - al) < 1e-11 and abs(got[1] - a1) < 1e-9


def test_check_range_looks_only_within_the_duration(tmp_path):
    """A range the boom passes only after 3 s (between its turns at 3 s and at the
    stroke's end, 4.5 s): a run of 3 s is accepted, one of 6 s refused."""
    _, drive0 = drive_of(tmp_path)
    f = 180 / np.pi
    b3 = _turns(drive0.motion, 3.0)[1]["boom"]
    b6 = _turns(drive0.motion, 6.0)[1]["boom"]
    assert b6 - b3 > 0.01
    model, drive = drive_of(tmp_path, foot=f", range_deg: [-40, {(b3 + b6) / 2 * f}]")
    LinkageDrive(model, drive, {}).check_range(3.0)
    with pytest.raises(ModelError):
        LinkageDrive(model, drive, {}).check_range(6.0)


def test_the_turns_of_the_hand_geometry_have_the_signs_the_range_test_assumes(tmp_path):
    model, drive = drive_of(tmp_path)
    th0, th1 = _turns(drive.motion)
    assert abs(th0["boom"]) < 1e-12 and abs(th0["rocker"]) < 1e-12
    assert th1["boom"] > 0.05 and th1["rocker"] > 0.05


# ------------------------------------------------------------------ errors

def test_a_stroke_past_the_dead_point_stops_the_run(tmp_path):
    """With A at (-5, 1) the cylinder's length d(alpha) has a maximum near alpha = 0.93
    (10.68 m, 0.05 m longer than at the reference): a stroke of 0.5 m cannot be made."""
    a = np.array([-5.0, 1.0])
    model, drive = drive_of(tmp_path, a=a)
    ld = LinkageDrive(model, drive, {})
    dmax = max(_maps(x, a)[1] for x in np.linspace(0.8, 1.1, 301))
    assert dmax - _maps(ALPHA_REF, a)[1] < 0.06
    with pytest.raises(AnalysisError) as exc:
        for t in np.linspace(0.0, 6.0, 61):
            ld.solve(float(t))
    assert "shorten the stroke" in str(exc.value)


def test_a_driven_joint_of_the_linkage_is_refused(tmp_path):
    model, drive = drive_of(tmp_path)
    other = type("D", (), {"name": "hook", "entry": "analysis.drives.hook"})()
    with pytest.raises(ModelError) as exc:
        LinkageDrive(model, drive, {1: other})
    assert "drive 'hook' moves a joint of the linkage" in str(exc.value)
    assert exc.value.file == model.scene_file and exc.value.entry == "analysis.drives.hook"
    LinkageDrive(model, drive, {7: other})     # a joint outside the linkage: accepted


def test_a_model_not_in_a_plane_is_refused(tmp_path):
    import dataclasses
    model, drive = drive_of(tmp_path)
    model = dataclasses.replace(model, planar=False)
    with pytest.raises(ModelError) as exc:
        LinkageDrive(model, drive, {})
    assert "needs a planar model (plane: xz) in this version" in exc.value.message
    assert exc.value.file == model.scene_file and exc.value.entry == drive.entry


def test_check_range_up_to_a_dead_point(tmp_path):
    """The dead-point geometry (A at (-5, 1)): the check follows the stroke until the
    linkage cannot follow (the run will report that) and judges the ranges over the
    part it could follow; no range at all: nothing to check."""
    a = np.array([-5.0, 1.0])
    model, drive = drive_of(tmp_path, a=a, foot=", range_deg: [-20, 20]")
    LinkageDrive(model, drive, {}).check_range(6.0)
    model, drive = drive_of(tmp_path, a=a, foot=", range_deg: [-20, 1]")
    with pytest.raises(ModelError) as exc:
        LinkageDrive(model, drive, {}).check_range(6.0)
    # the boom rises by more than 1 deg before the dead point (alpha 0.785 -> 0.93)
    assert "past the end of its range" in str(exc.value)
    model, drive = drive_of(tmp_path)
    ld = LinkageDrive(model, drive, {})
    ld.check_range(6.0)
    assert ld._last_solution == (0.0, ALPHA_REF, 0.0, 0.0)
