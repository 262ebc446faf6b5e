"""Kill tests for cranefe/outputs/member_forces.py (issue 20, mutation testing): section
forces of statically determinate structures against hand statics, the stresses, the
pieces and the documents, on the module's functions directly (no CLI).

Hand statics (`_section`): the section force at a point X of a member with local axes
(e_x, e_y, e_z) is the resultant of the loads on the part beyond X (towards the free
end): F = sum of the forces, M = sum of (r - X) x F; then N = F.e_x, Vy = F.e_y, Vz =
F.e_z, T = M.e_x, My = M.e_y, Mz = M.e_z (the face whose outward normal is +x). A
uniform beam segment's weight rho A l g acts at its midpoint. Local axes: e_z the
orientation made normal to e_x, e_y = e_z x e_x. A statically determinate structure's
element end forces are exact whatever the element's stiffness (each element is in
equilibrium with its consistent load, which is statically equivalent to the uniform
weight), so the tolerance is round-off: 1e-9 of the largest force or moment.
"""


import numpy as np
import pytest
import scipy.sparse.linalg as sla

from cranefe.model import load
from cranefe.outputs import member_forces as MF
from cranefe.statics import solve_static
from cranefe.system import assemble

E, Gm = 2.1e11, 8.1e10
B, H, RHO = 0.1, 0.2, 7850.0
GRAV = np.array([0.0, 3.0, -9.0])      # a y component: forces in both bending planes
a, b, MT = 3.0, 2.0, 500.0             # arm O -> A along x, A -> T along y; mass at T

FRAME = f"""cranefe: 1
gravity: [0, 3.0, -9.0]
nodes: {{O: [0, 0, 0], A: [{a}, 0, 0], T: [{a}, {b}, 0], S1: [2, 0, 5],
        S2: [-1, 1.7, 5], S3: [-1, -1.7, 5], W: [0, 0, 3], Z: [-1, 1.7, 6]}}
ground: [O, S1, S2, S3]
members:
  arm: {{type: beam, nodes: [O, A, T], E: {E}, G: {Gm}, rho: {RHO}, orientation: [0, 0, 1],
        elements: 2, section: {{shape: rectangle, b: {B}, h: {H}}}}}
  bars: {{type: truss, pairs: [[S1, W], [S2, W], [S3, W]], E: {E}, A: 0.002, rho: 0}}
  bare: {{type: beam, nodes: [S2, Z], E: {E}, G: {Gm}, A: 0.003, Iy: 1e-5, Iz: 1e-5,
         J: 1e-5, Wy: 1e-4, rho: 0, orientation: [0, 1, 0], elements: 1}}
masses: {{T: {MT}, W: 800}}
effects: {{structure: flexible}}
"""


def _section(X, ex, ez, loads):
    """Hand statics: the resultant (N, Vy, Vz, T, My, Mz) of the loads [(point, force)]
    on the part beyond X, in the axes e_x, e_z (made normal), e_y = e_z x e_x."""
    ex = ex / np.linalg.norm(ex)
    ez = ez - ez @ ex * ex
    ez /= np.linalg.norm(ez)
    ey = np.cross(ez, ex)
    F = sum((f for _, f in loads), np.zeros(3))
    M = sum((np.cross(np.asarray(p) - X, f) for p, f in loads), np.zeros(3))
    return np.array([F @ ex, F @ ey, F @ ez, M @ ex, M @ ey, M @ ez])


def _segment(P, Q, w):
    """The weight of a uniform segment P-Q of weight w per metre per unit g."""
    P, Q = np.asarray(P, float), np.asarray(Q, float)
    return ((P + Q) / 2, w * np.linalg.norm(Q - P) * GRAV)


def _arm_reference():
    """(4 elements, 2 ends, 6) hand section forces of the arm O-A-T (2 elements per
    piece)."""
    w = RHO * B * H
    O, A, T = np.zeros(3), np.array([a, 0, 0.0]), np.array([a, b, 0.0])
    out = np.zeros((4, 2, 6))
    tip = (T, MT * GRAV)
    pts = [O, (O + A) / 2, A, (A + T) / 2, T]
    for e in range(4):
        for end in range(2):
            X = pts[e + end]
            if e < 2:         # on O-A: the rest of O-A, all of A-T and the mass
                loads = [_segment(X, A, w), _segment(A, T, w), tip]
                ex = A - O
            else:
                loads = [_segment(X, T, w), tip]
                ex = T - A
            out[e, end] = _section(X, ex, np.array([0, 0, 1.0]), loads)
    return out


def _tripod_N():
    """Axial forces of the three bars: equilibrium of W, sum N_i e_i + m g = 0 with e_i
    the unit vector from W to S_i (a bar in tension pulls W towards S_i)."""
    Wp = np.array([0, 0, 3.0])
    S = np.array([[2, 0, 5], [-1, 1.7, 5], [-1, -1.7, 5.0]])
    e = (S - Wp) / np.linalg.norm(S - Wp, axis=1)[:, None]
    return np.linalg.solve(e.T, -800 * GRAV)


def _frame():
    model = load("frame.yaml", FRAME)
    system = assemble(model)
    return model, system, solve_static(model)


def _q_of(system, u):
    """Generalised coordinates of a primitive displacement u = T q (least squares)."""
    T = system.dofs.T
    q = sla.spsolve((T.T @ T).tocsc(), T.T @ u)
    assert np.allclose(T @ q, u, rtol=0, atol=1e-12 * np.abs(u).max())
    return q


def _elements(mm, model, name):
    k = [m.name for m in model.members].index(name)
    return np.flatnonzero(mm.member == k)


def test_static_forces_of_a_frame_and_a_tripod_by_hand():
    model, system, static = _frame()
    dofs = system.dofs
    mm = dofs.members
    F = MF.element_end_forces(model, dofs.layout, mm, static.u)
    assert F.shape == (1, len(mm.member), 2, 6)
    ref = _arm_reference()
    scale = np.abs(ref).max()
    arm = _elements(mm, model, "arm")
    np.testing.assert_allclose(F[0, arm], ref, rtol=0, atol=1e-9 * scale)
    assert np.abs(ref[:, :, 3]).max() > 0.1 * scale           # torsion in O-A
    # the tripod: N the same at both ends, no shear or moment
    bars = _elements(mm, model, "bars")
    N = _tripod_N()
    np.testing.assert_allclose(F[0, bars, :, 0], np.column_stack([N, N]), rtol=1e-9)
    assert np.all(F[0, bars, :, 1:] == 0)
    # the unloaded cantilever S2-Z (rho 0, no mass): nothing
    np.testing.assert_allclose(F[0, _elements(mm, model, "bare")], 0, atol=1e-9 * scale)
    # the same state as a row of a (k, n_prim) input, twice
    F2 = MF.element_end_forces(model, dofs.layout, mm, np.stack([static.u, static.u]))
    np.testing.assert_allclose(F2, np.concatenate([F, F]), rtol=0, atol=1e-12 * scale)
    # without the weight load: the consistent load of each arm element (weight w l g
    # split to its nodes as w l g / 2, end moments w l^2 g / 12 of opposite sign) is
    # added back: start face -f_1, end face +f_2
    Fn = MF.element_end_forces(model, dofs.layout, mm, static.u, weight=False)
    d = Fn[0, arm] - F[0, arm]
    w = RHO * B * H
    for e in range(4):
        l = 1.5 if e < 2 else 1.0
        ex, ey = (np.array([1.0, 0, 0]), np.array([0, 1.0, 0])) if e < 2 else \
            (np.array([0, 1.0, 0]), np.array([-1.0, 0, 0]))
        ez = np.array([0, 0, 1.0])
        f = w * l * GRAV / 2
        np.testing.assert_allclose(d[e, 0, :3], -np.array([f @ ex, f @ ey, f @ ez]),
                                   rtol=0, atol=1e-9 * scale)
        np.testing.assert_allclose(d[e, 1, :3], [f @ ex, f @ ey, f @ ez], rtol=0,
                                   atol=1e-9 * scale)
        # end moments of a uniform transverse load q: q l^2 / 12, about e_y from the
        # e_z load and about e_z from the e_y load, the same on both faces
        qz, qy = w * GRAV @ ez, w * GRAV @ ey
        np.testing.assert_allclose(np.abs(d[e, :, 4]), abs(qz) * l**2 / 12, rtol=1e-9)
        np.testing.assert_allclose(np.abs(d[e, :, 5]), abs(qy) * l**2 / 12, rtol=1e-9)
        assert d[e, 0, 4] == pytest.approx(d[e, 1, 4], rel=1e-9)
        assert d[e, 0, 5] == pytest.approx(d[e, 1, 5], rel=1e-9)
        assert abs(d[e, 0, 3]) < 1e-9 * scale
    np.testing.assert_allclose(Fn[0, bars], F[0, bars], rtol=1e-12)   # rho 0, trusses


def test_stresses_of_the_frame():
    model, system, static = _frame()
    mm = system.dofs.members
    F = MF.element_end_forces(model, system.dofs.layout, mm, static.u)
    S = MF.extreme_stresses(model, mm, F)
    assert S.shape == (1, len(mm.member), 2, 2)
    ref = _arm_reference()
    A, Wy, Wz = B * H, B * H**2 / 6, H * B**2 / 6
    bend = np.abs(ref[..., 4]) / Wy + np.abs(ref[..., 5]) / Wz
    arm = _elements(mm, model, "arm")
    sc = np.abs(bend).max()
    np.testing.assert_allclose(S[0, arm, :, 0], ref[..., 0] / A + bend, atol=1e-9 * sc)
    np.testing.assert_allclose(S[0, arm, :, 1], ref[..., 0] / A - bend, atol=1e-9 * sc)
    bars = _elements(mm, model, "bars")
    N = _tripod_N()
    for k in (0, 1):
        np.testing.assert_allclose(S[0, bars, :, k], np.column_stack([N, N]) / 0.002,
                                   rtol=1e-9)
    # a 3D beam with Wy but without Wz: nan
    assert np.isnan(S[0, _elements(mm, model, "bare")]).all()


PLANE = f"""cranefe: 1
plane: xz
nodes: {{O: [0, 0, 0], T: [2, 0, 0], U: [0, 0, -1]}}
ground: [O, U]
members:
  c: {{type: beam, nodes: [O, T], E: {E}, A: 0.01, Iy: 2e-5, Wy: 4e-4, rho: 0,
      elements: 1}}
  d: {{type: beam, nodes: [U, T], E: {E}, A: 0.01, Iy: 2e-5, rho: 0, elements: 1}}
masses: {{T: 1000}}
effects: {{structure: flexible}}
"""


def test_rigid_motions_give_no_forces():
    # a small rigid motion u = t + theta x (x - x0), rotations theta at every node: no
    # element is strained, so every section force is 0 (without the weight load); the
    # trusses' ends both move (their N is the difference of the ends' motions)
    from cranefe.assembly.springs import all_coords
    model, system, static = _frame()
    dofs = system.dofs
    mm = dofs.members
    X = all_coords(model, dofs.layout, mm)
    t, th, x0 = np.array([1e-3, -2e-3, 3e-3]), np.array([2e-4, -1e-4, 3e-4]), X[1]
    U = np.zeros_like(static.u)
    for i, x in enumerate(X):
        U[6 * i:6 * i + 3] = t + np.cross(th, x - x0)
        U[6 * i + 3:6 * i + 6] = th
    F = MF.element_end_forces(model, dofs.layout, mm, U, weight=False)
    # against the forces of a unit strain of the arm: E A / l * 1e-3 ~ 1e7 N
    np.testing.assert_allclose(F, 0, atol=1e-9 * E * B * H * 1e-3)


def test_planar_beam_without_wz_and_without_wy():
    # a planar model: Wz is not needed (its term 0), a beam without Wy has nan stresses
    model = load("p.yaml", PLANE)
    system = assemble(model)
    mm = system.dofs.members
    F = MF.element_end_forces(model, system.dofs.layout, mm, solve_static(model).u)
    S = MF.extreme_stresses(model, mm, F)
    c = _elements(mm, model, "c")[0]
    My = np.abs(F[0, c, :, 4])
    assert My.max() > 0
    np.testing.assert_allclose(S[0, c, :, 0], F[0, c, :, 0] / 0.01 + My / 4e-4, rtol=1e-12)
    np.testing.assert_allclose(S[0, c, :, 1], F[0, c, :, 0] / 0.01 - My / 4e-4, rtol=1e-12)
    assert np.isnan(S[0, _elements(mm, model, "d")]).all()


def test_pieces_and_element_members():
    model, system, _ = _frame()
    mm = system.dofs.members
    arm, bars, bare = (_elements(mm, model, n) for n in ("arm", "bars", "bare"))
    p = MF.pieces(model, mm)
    assert p == [("arm", "beam", "O", "A", arm[0], arm[1]),
                 ("arm", "beam", "A", "T", arm[2], arm[3]),
                 ("bars", "truss", "S1", "W", bars[0], bars[0]),
                 ("bars", "truss", "S2", "W", bars[1], bars[1]),
                 ("bars", "truss", "S3", "W", bars[2], bars[2]),
                 ("bare", "beam", "S2", "Z", bare[0], bare[0])]
    assert all(type(v) is int for q in p for v in q[4:])
    names = MF.element_members(model, mm)
    assert names == tuple(model.members[k].name for k in mm.member)
    assert names.count("arm") == 4 and names.count("bars") == 3


def test_member_end_forces_document():
    model, system, static = _frame()
    mm = system.dofs.members
    doc = MF.member_end_forces(model, system.dofs.layout, mm, static.u)
    assert [(d["member"], d["from"], d["to"]) for d in doc] == [
        ("arm", "O", "A"), ("arm", "A", "T"), ("bare", "S2", "Z")]
    ref = _arm_reference()
    for d, (i, j) in zip(doc, ((0, 1), (2, 3))):
        assert [d["start"][k] for k in MF.FORCE_NAMES] == pytest.approx(
            list(ref[i, 0]), abs=1e-9 * np.abs(ref).max())
        assert [d["end"][k] for k in MF.FORCE_NAMES] == pytest.approx(
            list(ref[j, 1]), abs=1e-9 * np.abs(ref).max())
        assert d["type"] == "beam"
        assert set(d["start"]) == set(MF.FORCE_NAMES) | set(MF.STRESS_NAMES)
    assert doc[2]["start"]["sigma_max"] is None            # nan -> None
    full = MF.member_end_forces(model, system.dofs.layout, mm, static.u, trusses=True)
    assert len(full) == 6 and full[2]["type"] == "truss"
    assert full[2]["start"]["N"] == pytest.approx(_tripod_N()[0], rel=1e-9)
    assert MF.member_end_forces(model, system.dofs.layout, None, static.u) == []
    # a model of trusses only: [] unless asked for them
    only = load("t.yaml", "\n".join(line for line in FRAME.splitlines() if not line
                                     .startswith(("  arm", "        elements", "  bare",
                                                  "         J"))).replace(f"T: {MT}, ", ""))
    so = assemble(only)
    u = solve_static(only).u
    assert MF.member_end_forces(only, so.dofs.layout, so.dofs.members, u) == []
    assert len(MF.member_end_forces(only, so.dofs.layout, so.dofs.members, u,
                                    trusses=True)) == 3


def test_modal_and_run_forces_are_linear_in_the_shape():
    # a shape equal to the static displacement: its forces are the static ones without
    # the weight load (weight=False), mass-normalised scale = the shape as given; with an
    # amplitude, scaled by amplitude / largest node translation
    model, system, static = _frame()
    dofs = system.dofs
    mm = dofs.members
    q = _q_of(system, static.u)
    Fn = MF.element_end_forces(model, dofs.layout, mm, static.u, weight=False)[0]
    shapes = np.column_stack([q, -2 * q])
    mf = MF.modal_member_forces(model, dofs, shapes)
    assert mf.kind == "modes" and mf.scale == {"normalisation":
                                               "mass (shapes^T M shapes = I)"}
    sc = np.abs(Fn).max()
    np.testing.assert_allclose(mf.forces, [Fn, -2 * Fn], rtol=0, atol=1e-9 * sc)
    np.testing.assert_allclose(mf.stress[0], MF.extreme_stresses(model, mm, Fn[None])[0],
                               rtol=1e-9)
    assert mf.element_member == MF.element_members(model, mm)
    assert mf.pieces == MF.pieces(model, mm)
    node_shapes = np.zeros((2, 8, 3))
    node_shapes[0, 2] = [0.0, 3.0, 4.0]           # largest translation 5 m
    node_shapes[1, 1] = [0.0, 0.0, -0.5]          # 0.5 m
    mf = MF.modal_member_forces(model, dofs, shapes, node_shapes, amplitude=0.1)
    assert mf.scale == {"normalisation": "largest node translation", "amplitude_m": 0.1}
    np.testing.assert_allclose(mf.forces, [Fn * 0.1 / 5, -2 * Fn * 0.1 / 0.5], rtol=0,
                               atol=1e-9 * sc)
    node_shapes[1] = 0                              # a zero shape: not scaled (no 0/0)
    mf = MF.modal_member_forces(model, dofs, shapes, node_shapes, amplitude=0.1)
    np.testing.assert_allclose(mf.forces[1], -2 * Fn * 0.1, rtol=0, atol=1e-9 * sc)
    # run states static_u + T q(t), with the weight: (1 + c) K u - f = F + c (F + f)
    Fs = MF.element_end_forces(model, dofs.layout, mm, static.u)[0]
    c = np.array([0.0, 1.0, -0.5])
    run = MF.run_member_forces(model, dofs, static.u, c[:, None] * q[None])
    assert run.kind == "times" and run.forces.shape[0] == 3
    for k in range(3):
        np.testing.assert_allclose(run.forces[k], Fs + c[k] * Fn, rtol=0, atol=1e-9 * sc)
    assert run.element_member == MF.element_members(model, mm)
    assert run.pieces == MF.pieces(model, mm)
    # envelope: min and max over the times, in chunks (2: the last chunk of one time)
    env = MF.transient_envelope(model, dofs, static.u, c[:, None] * q[None], chunk=2)
    assert env.kind == "envelope" and env.forces.shape[0] == 2
    # the archive stores element_member; the documents need the pieces
    assert env.element_member == MF.element_members(model, mm)
    assert env.pieces == MF.pieces(model, mm)
    st = MF.static_member_forces(model, dofs.layout, mm, static.u)
    assert st.kind == "static" and st.element_member == MF.element_members(model, mm)
    assert st.pieces == MF.pieces(model, mm)
    np.testing.assert_allclose(st.forces, Fs[None], rtol=0, atol=1e-12 * sc)
    np.testing.assert_allclose(env.forces[0], run.forces.min(0), rtol=0, atol=1e-9 * sc)
    np.testing.assert_allclose(env.forces[1], run.forces.max(0), rtol=0, atol=1e-9 * sc)
    np.testing.assert_array_equal(np.isnan(env.stress[0]), np.isnan(run.stress[0]))
    np.testing.assert_allclose(env.stress[0], np.fmin.reduce(run.stress, 0), atol=1e-6 * sc)
    np.testing.assert_allclose(env.stress[1], np.fmax.reduce(run.stress, 0), atol=1e-6 * sc)
    one = MF.transient_envelope(model, dofs, static.u, c[:, None] * q[None])
    np.testing.assert_allclose(one.forces, env.forces, rtol=0, atol=1e-12 * sc)


def _hand_mf(kind="static"):
    """A MemberForces of two states, three elements (member a: 0, 1 in one piece; b: 2),
    numbers chosen by hand."""
    F = np.zeros((2, 3, 2, 6))
    F[0, 0, 0] = [1, 2, 3, 4, 5, 6]
    F[0, 1, 1] = [-7, 0, 0, 0, 0, 9]
    F[1, 0, 1] = [0.5, 0, 0, 0, 0, -11]
    F[1, 2, 0, 0] = 3.0
    S = np.zeros((2, 3, 2, 2))
    S[0, 0, 0] = [10.0, -20.0]
    S[0, 1, 1] = [30.0, 5.0]
    S[1, 1, 0] = [2.0, -40.0]
    S[:, 2] = np.nan
    S[1, 1, 1] = [np.inf, 0]
    pieces = [("a", "beam", "P", "Q", 0, 1), ("b", "truss", "Q", "R", 2, 2)]
    return MF.MemberForces(kind, F, S, pieces, {"normalisation": "n", "amplitude_m": 0.25})


def test_member_forces_documents():
    mf = _hand_mf()
    d = mf.to_dict()
    assert d[0]["start"] == {"N": 1.0, "Vy": 2.0, "Vz": 3.0, "T": 4.0, "My": 5.0, "Mz": 6.0,
                             "sigma_max": 10.0, "sigma_min": -20.0}
    assert d[0]["end"]["N"] == -7.0 and d[0]["end"]["Mz"] == 9.0
    assert d[0]["end"]["sigma_max"] == 30.0
    assert (d[1]["member"], d[1]["type"], d[1]["from"], d[1]["to"]) == ("b", "truss", "Q",
                                                                        "R")
    assert d[1]["start"]["sigma_max"] is None and d[1]["end"]["sigma_min"] is None
    assert mf.piece_list(1)[0]["end"]["sigma_max"] is None          # inf -> None
    mf.kind = "modes"
    d = mf.to_dict()
    assert d["scale"] == {"normalisation": "n", "amplitude_m": 0.25}
    assert [m["index"] for m in d["modes"]] == [1, 2]
    assert d["modes"][1]["pieces"] == mf.piece_list(1)
    mf.kind = "envelope"
    d = mf.to_dict()
    assert d["over"] == "output times"
    p = d["pieces"][0]
    assert (p["member"], p["type"], p["from"], p["to"]) == ("a", "beam", "P", "Q")
    assert p["start"]["min"] == mf.piece_list(0)[0]["start"]
    assert p["end"]["max"] == mf.piece_list(1)[0]["end"]
    assert set(p) == {"member", "type", "from", "to", "start", "end"}


def test_peak_stresses_summary_table_and_cells():
    mf = _hand_mf()
    mf.stress[1, 1, 1] = [0.0, 0.0]                # no inf here
    peaks = mf.peak_stresses()
    # member a: |sigma| largest 40 at state 2, element 1, start; b: all nan
    assert peaks == [{"member": "a", "sigma_abs_max_Pa": 40.0, "state": 2, "element": 1,
                      "end": "start"},
                     {"member": "b", "sigma_abs_max_Pa": None, "state": None,
                      "element": None, "end": None}]
    mf.element_member = ("a", "a", "b")
    assert mf.peak_stresses() == peaks
    # the all-nan member first: the others still follow
    first = MF.MemberForces("static", mf.forces[:, [2, 0, 1]], mf.stress[:, [2, 0, 1]],
                            [], element_member=("b", "a", "a"))
    assert first.peak_stresses() == [dict(peaks[1]), dict(peaks[0], element=2)]
    mf.stress[0, 1, 1] = [50.0, 1.0]               # now at the end of element 1, state 1
    assert mf.peak_stresses()[0] == {"member": "a", "sigma_abs_max_Pa": 50.0, "state": 1,
                                     "element": 1, "end": "end"}
    s = mf.summary()
    assert s == {"kind": "static", "scale": mf.scale, "states": 2, "elements": 3,
                 "peak_stress": mf.peak_stresses()}
    lines = mf.table().splitlines()
    assert lines[0] == ("member forces (static, n 0.25 m): 3 elements, largest |sigma| "
                        "per member")
    assert lines[1] == f"  {'member':<16} {'|sigma| MPa':>12}  state, element, end"
    assert lines[2] == f"  {'a':<16} {5e-05:>12.6g}  1, 1, end"
    assert lines[3] == f"  {'b':<16} {'-':>12}  (no Wy / Wz)"
    mf.kind, mf.scale = "modes", {"normalisation": "mass"}
    assert mf.table().splitlines()[0] == ("member forces (modes, mass): 3 elements, "
                                          "largest |sigma| per member")
    assert mf.table().splitlines()[1].endswith("  mode, element, end")
    mf.scale = {}
    assert mf.table().startswith("member forces (modes): 3")
    mf.stress[0, 1, 1] = [1234565.5, 1.0]          # MPa to six figures: 1.23457
    assert mf.table().splitlines()[2] == f"  {'a':<16} {'1.23457':>12}  1, 1, end"
    mf.stress[0, 1, 1] = [50.0, 1.0]
    for kind, word in (("envelope", "state (1 min, 2 max)"), ("times", "output time")):
        mf.kind = kind
        assert mf.table().splitlines()[1].endswith(f"  {word}, element, end")
    # cells: the end value of larger magnitude (the start on a tie), the larger
    # sigma_max and the smaller sigma_min of the two ends
    cv = mf.cell_values(0)
    assert cv.shape == (3, 8)
    np.testing.assert_array_equal(cv[0], [1, 2, 3, 4, 5, 6, 10.0, -20.0])
    np.testing.assert_array_equal(cv[1], [-7, 0, 0, 0, 0, 9, 50.0, 0.0])
    mf.forces[0, 2, 0, 0], mf.forces[0, 2, 1, 0] = 2.0, -2.0
    assert mf.cell_values(0)[2, 0] == 2.0
    assert np.isnan(mf.cell_values(0)[2, 6])
    np.testing.assert_array_equal(mf.cell_values(1)[0, [0, 5]], [0.5, -11])
