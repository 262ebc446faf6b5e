"""Value tests of cranefe/analysis/luffing/kinematics.py alone (issue 20; tools/mutation.py
luffing_kinematics): the portal crane's `Linkage` (models/portal_crane_luffing.yaml,
every body that the joints tie to the ground, the boom driving) against the linkage
solved by hand at 30 digits (`_portal_linkage` of tests/test_values.py: circle
intersections), at angles on both sides of the model's own (60.0 deg), so that the
continuation table is followed up and down.

Checked per body (boom, jib, backstay, rocker and the massless tie rod): the pose
(x, z of the centre of mass, theta) and its first and second derivatives in alpha
(mpmath's differentiation of the hand pose); the positions and derivatives of nodes
through `KinState.point` (the jib tip D, the rod's eye Q, a ground node); and the
errors a wrong scene or model gets. The hand values are computed once per session
(module level) and never with cranefe.

Tolerances: poses 1e-10 m or rad (the code's Newton stops at 1e-13 of the size
scale, about 30 m), first derivatives 1e-9, second 1e-8 (each one more solve with the
Jacobian, condition ~1e3 over the range).
"""

import functools
import os

import mpmath as mp
import numpy as np
import pytest

from cranefe.analysis.luffing.kinematics import Linkage
from cranefe.errors import AnalysisError, ModelError
from cranefe.model import load

from test_values import ROOT, _portal_linkage

MODEL = os.path.join(ROOT, "models", "portal_crane_luffing.yaml")
DEGS = (52.0, 63.0, 77.0)


@functools.lru_cache(maxsize=None)
def _hand():
    """{deg: {body: [(x, z, theta), d/dalpha, d2/dalpha2]}, 'D': ..., 'Q': ...}."""
    mp.mp.dps = 30
    pose, _, _ = _portal_linkage()
    import yaml
    doc = yaml.safe_load(open(MODEL))
    vec = lambda v: mp.matrix([mp.mpf(str(v[0])), mp.mpf(str(v[2]))])   # noqa: E731
    N = {k: vec(v) for k, v in doc["nodes"].items()}

    def rot(t, v):
        return mp.matrix([mp.cos(t) * v[0] - mp.sin(t) * v[1],
                          mp.sin(t) * v[0] + mp.cos(t) * v[1]])

    def ang(v):
        return mp.atan2(v[1], v[0])

    def quantities(a):
        items, _, D = pose(a)
        out = {}
        for k, name in enumerate(("boom", "jib", "backstay", "rocker")):
            c, t = items[k][2], items[k][3]
            out[name] = [c[0], c[1], t]
        P = N["O"] + rot(items[0][3], N["P"] - N["O"])
        Q = N["G"] + rot(items[3][3], N["Q"] - N["G"])
        t_rod = ang(Q - P) - ang(N["Q"] - N["P"])
        # the massless rod's reference point: the middle of its nodes (the loader's
        # default centre of a body without mass, docs/model-format.md)
        c_rod = P + rot(t_rod, (N["P"] + N["Q"]) / 2 - N["P"])
        out["rod"] = [c_rod[0], c_rod[1], t_rod]
        out["D"] = [D[0], D[1]]
        out["Q"] = [Q[0], Q[1]]
        return out

    res = {}
    for deg in DEGS:
        a = mp.radians(deg)
        q0 = quantities(a)
        res[deg] = {}
        for key, vals in q0.items():
            f = [lambda t, key=key, i=i: quantities(t)[key][i] for i in range(len(vals))]
            res[deg][key] = [np.array([float(v) for v in vals]),
                             np.array([float(mp.diff(g, a)) for g in f]),
                             np.array([float(mp.diff(g, a, 2)) for g in f])]
    return res


def _linkage(model=None, **kw):
    model = model or load(MODEL)
    args = dict(boom="boom", pivot="O", tip="B")
    args.update(kw)
    return Linkage(model, args["boom"], args["pivot"], args["tip"])


def test_poses_and_transfer_functions_against_the_hand_linkage():
    hand = _hand()
    lk = _linkage()
    model = lk.model
    names = [b.name for b in model.bodies]
    assert sorted(names[b] for b in lk.bodies) == ["backstay", "boom", "jib", "rocker", "rod"]
    assert lk.n == 15 and lk.nb == 5
    assert np.degrees(lk.alpha_ref) == pytest.approx(60.0033, abs=1e-4)
    st = lk.state(np.radians(np.array(DEGS)).reshape(3, 1))       # any shape: flattened
    assert st.alpha.shape == (3,)
    assert np.all(st.residual <= 1e-10 * lk.scale)
    tol = (1e-10, 1e-9, 1e-8)
    for n, deg in enumerate(DEGS):
        for b in lk.bodies:
            i = lk.local[b]
            for d, arr in enumerate((st.q, st.dq, st.ddq)):
                got = arr[n, 3 * i:3 * i + 3]
                assert np.allclose(got, hand[deg][names[b]][d], rtol=0,
                                   atol=tol[d] * 30), (deg, names[b], d)
            th = st.angle(b)
            for d in range(3):
                assert th[d][n] == pytest.approx(hand[deg][names[b]][d][2], abs=tol[d] * 30)
        idx = model.node_index
        for node in ("D", "Q"):
            X = st.point(idx[node])
            for d in range(3):
                assert np.allclose(X[d][n], hand[deg][node][d], rtol=0, atol=tol[d] * 30), \
                    (deg, node, d)
        # the rod's eye Q seen on the rod itself is the same point
        Xr = st.point(idx["Q"], body=names.index("rod"))
        assert np.allclose(Xr[0][n], hand[deg]["Q"][0], rtol=0, atol=3e-9)
        # a ground node stays put
        Xg = st.point(idx["G"])
        assert np.allclose(Xg[0][n], [-2.15, 30.0], rtol=0, atol=1e-14)
        assert not Xg[1].any() and not Xg[2].any()
    # the continuation table now spans the angles asked, in order, at its step
    assert lk._A[0] <= np.radians(52.0) and lk._A[-1] >= np.radians(77.0)
    assert np.allclose(np.diff(lk._A), Linkage.STEP, rtol=1e-12)
    # Newton from a poor guess closes the loops too
    q, res = lk.newton(lk.q_ref[None] + 0.01, np.array([np.radians(63.0)]))
    assert res[0] < 1e-10
    assert np.allclose(q[0], st.q[1], rtol=0, atol=1e-9)


def test_carriers_of_nodes():
    lk = _linkage()
    m = lk.model
    names = [b.name for b in m.bodies]
    idx = m.node_index
    assert lk.carrier(idx["G"]) is not None and lk.carrier(idx["G"]) < 0      # ground
    assert names[lk.carrier(idx["D"])] == "jib"
    assert names[lk.carrier(idx["C"])] == "boom"


def _text(**changes):
    text = open(MODEL).read()
    for a, b in changes.items():
        assert a in text
        text = text.replace(a, b)
    return text


def test_scene_errors_name_the_entry():
    with pytest.raises(ModelError, match=r"unknown body 'mast'; bodies: boom, jib, "
                                         r"backstay, rocker, rod$") as e:
        _linkage(boom="mast")
    assert e.value.entry == "analysis.boom"
    for key, kw in (("pivot", dict(pivot="ZZ")), ("tip", dict(tip="ZZ"))):
        with pytest.raises(ModelError, match=r"unknown node 'ZZ'$") as e:
            _linkage(**kw)
        assert e.value.entry == f"analysis.{key}"
    with pytest.raises(ModelError, match=r"node 'B' is not a joint between 'boom' and "
                                         r"the ground"):
        _linkage(pivot="B", tip="C")
    with pytest.raises(ModelError, match=r"node 'D' is not carried by body 'boom'"):
        _linkage(tip="D")
    # a body on its own (the hook block made a body without joints)
    m = load("m.yaml", _text(**{"    nodes: [P, Q]\n": "    nodes: [P, Q]\n  spare: "
                                "{mass: 10, com: [23.37, 0, 9.76], inertia: 1.0, nodes: [HOOK]}\n"}))
    with pytest.raises(ModelError, match=r"body 'spare' is not joined to the ground"):
        _linkage(m, boom="spare", tip="HOOK")


def test_model_errors():
    spatial = load("p.yaml", "cranefe: 1\nnodes: {O: [0, 0, 0], B: [2, 0, 0]}\n"
                   "ground: [O]\nbodies:\n  boom: {mass: 10, com: [1, 0, 0], "
                   "inertia: [1, 1, 1], nodes: [B]}\njoints:\n  - {type: hinge, bodies: "
                   "[ground, boom], at: O, axis: [0, 1, 0]}\n")
    with pytest.raises(ModelError, match=r"^p.yaml: plane: the luffing analysis needs a "
                                         r"planar model \(plane: xz\)$"):
        _linkage(spatial)
    # without the rod the rocker turns freely: two degrees of freedom with the drive free
    free = _text(**{"  rod:                                # tie rod: a two-force link\n"
                    "    mass: 0\n    nodes: [P, Q]\n": "",
                    "  - {type: hinge, bodies: [boom, rod], at: P}\n": "",
                    "  - {type: hinge, bodies: [rod, rocker], at: Q}\n": ""})
    with pytest.raises(ModelError, match=r"^m.yaml: joints: the linkage \(boom, jib, "
                                         r"backstay, rocker\) has 2 degree\(s\) of freedom "
                                         r"with the drive free; the luffing analysis needs "
                                         r"exactly one, the boom angle: add or fix joints$"):
        _linkage(load("m.yaml", free))


def test_a_toggle_stops_the_continuation():
    """Past about 100 deg the four-bar O-B-E-F cannot close (|BE| + |FE| < |BF|)."""
    lk = _linkage()
    with pytest.raises(AnalysisError, match=r"the linkage cannot follow the boom beyond "
                                            r"alpha = .* deg \(it locks or leaves its "
                                            r"branch there\); asked for 120.00 deg"):
        lk.state(np.radians(120.0))
    assert lk.limits[1] is not None and 60 < np.degrees(lk.limits[1]) < 120
    assert lk.limits[0] is None


CYLINDER = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 0], A: [-1, 0, -1.5], C: [3, 0, 1], T: [6, 0, 0], M: [1, 0, -0.5],
        E: [7, 0, 1]}
ground: [O, A]
bodies:
  boom: {mass: 1000, com: [3, 0, 0], inertia: 3000, nodes: [C, T]}
  barrel: {mass: 100, com: [0, 0, -0.9], inertia: 20, nodes: [M]}
  rod: {mass: 50, com: [2, 0, 0.5], inertia: 10, nodes: [M]}
  head: {mass: 200, com: [7, 0, 0.5], inertia: 30, nodes: [E]}
joints:
  - {type: hinge, bodies: [ground, boom], at: O}
  - {type: hinge, bodies: [ground, barrel], at: A}
  - {type: slider, bodies: [barrel, rod], at: M, axis: [0.8, 0, 0.6]}
  - {type: hinge, bodies: [boom, rod], at: C}
  - {type: fixed, bodies: [boom, head], at: T}
"""
CYL_DEGS = (-5.0, 10.0, 25.0)


@functools.lru_cache(maxsize=None)
def _cylinder_by_hand():
    """A boom luffed by a cylinder (barrel hinged to the ground at A, rod hinged to the
    boom at C, a slider between them along the line M-C, u0 = (0.8, 0, 0.6), which does
    not pass through A: the barrel's point M then moves along the line too, and the
    slider's Coriolis term 2 w u.(v_b - v_a) does not vanish; the rod's centre is off the
    line too, and so is the barrel's, else the curvature terms of the slider equation
would vanish along the normal) with a
    head fixed to the
    boom at T. With d = alpha (alpha_ref = 0: O -> T horizontal): C = Rot(d) C0; the
    barrel and the rod turn by theta, the root of cross(Rot(theta) u0, C - P(theta)) = 0
    with P = A + Rot(theta)(M0 - A) (C on the barrel's line; mpmath's findroot from 0);
    the barrel about A, the rod about C (hinged there, it follows C); the head turns
    with the boom. Poses (x, z, theta) per body and their alpha derivatives by mpmath at
    30 digits."""
    mp.mp.dps = 30

    def v(x, z):
        return mp.matrix([mp.mpf(x), mp.mpf(z)])

    def rot(t, p):
        return mp.matrix([mp.cos(t) * p[0] - mp.sin(t) * p[1],
                          mp.sin(t) * p[0] + mp.cos(t) * p[1]])

    def ang(p):
        return mp.atan2(p[1], p[0])

    A, C0, M0 = v(-1, "-1.5"), v(3, 1), v(1, "-0.5")
    u0 = v("0.8", "0.6")
    com = {"boom": v(3, 0), "barrel": v(0, "-0.9"), "rod": v(2, "0.5"),
           "head": v(7, "0.5")}

    def pose(a):
        C = rot(a, C0)

        def off(t):
            P, u = A + rot(t, M0 - A), rot(t, u0)
            return u[0] * (C - P)[1] - u[1] * (C - P)[0]
        th = mp.findroot(off, mp.mpf(0) if abs(a) < 0.3 else a / 2)
        out = {"boom": (rot(a, com["boom"]), a),
               "barrel": (A + rot(th, com["barrel"] - A), th),
               "rod": (C + rot(th, com["rod"] - C0), th),
               "head": (rot(a, com["head"]), a)}
        return {k: [p[0], p[1], t] for k, (p, t) in out.items()}

    res = {}
    for deg in CYL_DEGS:
        a = mp.radians(deg)
        res[deg] = {}
        for name in com:
            f = [lambda t, name=name, i=i: pose(t)[name][i] for i in range(3)]
            res[deg][name] = [np.array([float(g(a)) for g in f]),
                              np.array([float(mp.diff(g, a)) for g in f]),
                              np.array([float(mp.diff(g, a, 2)) for g in f])]
    return res


def test_a_cylinder_with_a_slider_and_a_fixed_head_against_the_hand_linkage():
    hand = _cylinder_by_hand()
    m = load("cyl.yaml", CYLINDER)
    lk = Linkage(m, "boom", "O", "T")
    assert lk.square and lk.n == 12 and lk.alpha_ref == 0.0
    names = [b.name for b in m.bodies]
    st = lk.state(np.radians(CYL_DEGS))
    tol = (1e-11, 1e-10, 1e-9)
    for n, deg in enumerate(CYL_DEGS):
        for b in lk.bodies:
            i = lk.local[b]
            for d, arr in enumerate((st.q, st.dq, st.ddq)):
                assert np.allclose(arr[n, 3 * i:3 * i + 3], hand[deg][names[b]][d], rtol=0,
                                   atol=tol[d] * 10), (deg, names[b], d)
    # the constraint equations vanish at the solution, and their Jacobian is the
    # derivative of Phi (central differences, h = 1e-6: truncation ~1e-12 m)
    F, J = lk.equations(st.q, st.alpha)
    assert np.abs(F).max() < 1e-12
    h = 1e-6
    for k in range(lk.n):
        dq = np.zeros(lk.n)
        dq[k] = h
        Fp, _ = lk.equations(st.q + dq, st.alpha)
        Fm, _ = lk.equations(st.q - dq, st.alpha)
        assert np.allclose((Fp - Fm) / (2 * h), J[:, :, k], rtol=0, atol=1e-8), k


def test_a_planar_ball_joint_is_a_hinge():
    """The rocker's ground hinge at G given as a ball joint (planar: the same two
    equations): the same poses and transfer functions as the hand linkage at 63 deg."""
    hand = _hand()
    text = open(MODEL).read()
    a = "  - {type: hinge, bodies: [ground, rocker], at: G}"
    assert a in text
    m = load("ball.yaml", text.replace(a, "  - {type: ball, bodies: [ground, rocker], at: G}"))
    lk = _linkage(m)
    st = lk.state(np.radians([63.0]))
    names = [b.name for b in m.bodies]
    i = lk.local[names.index("rocker")]
    for d, arr in enumerate((st.q, st.dq, st.ddq)):
        assert np.allclose(arr[0, 3 * i:3 * i + 3], hand[63.0]["rocker"][d], rtol=0,
                           atol=(1e-9, 1e-8, 1e-7)[d])
