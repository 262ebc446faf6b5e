"""Kill tests for luffing configurations no other fast test builds (issue 20, mutation
testing; docs/testing.md "Not run yet, or not whole"):

- kinematics.py (tools/mutation.py luffing_kinematics): a linkage with a REDUNDANT joint,
  whose closure Jacobian has more rows than coordinates, so `Linkage` solves its linear
  systems by the pseudo-inverse. The linkage: a boom O-B and two links F1-E1, F2-E2 of the
  boom's length, parallel to it, all hinged to the ground, and a jib hinged to all three
  (B, E1, E2). One link is enough to make a parallelogram; the second adds two closure
  equations of which one is dependent (13 equations for 12 coordinates, rank 11 with the
  driver free: one degree of freedom). By hand, with theta = alpha - alpha_ref: the boom
  and both links turn by theta about their ground hinges, X = P + Rot(theta) (X0 - P),
  dX/dalpha = Rot(theta + pi/2) (X0 - P), d2X/dalpha2 = -Rot(theta) (X0 - P), and the jib
  translates with B, X = X0 + B(alpha) - B0, without turning.
- analysis.py (tools/mutation.py luffing_analysis): a four-bar whose coupler turns, so
  that the jib tip runs on a coupler curve (its |dD/dalpha|^2 varies with alpha, unlike
  on the circles of every point of a parallelogram): the load-mass law's fit
  (`Luffing.optimal` with an extra inertia), the sensitivity report's load-mass rows,
  and the collocation report of a scene with `inertia: paper` (see the second part).
"""

import math
import os
import tempfile
from functools import cache

import numpy as np
import pytest
from scipy.integrate import cumulative_trapezoid, quad

from cranefe.analysis.luffing.kinematics import Linkage
from cranefe.model import load

# --------------------------------------------------------------- the redundant linkage
L, A_REF = 10.0, math.radians(30.0)
F1, F2 = np.array([0.0, -2.0]), np.array([1.0, -3.0])
B0 = L * np.array([math.cos(A_REF), math.sin(A_REF)])
TIP = np.array([4.0, 0.0])               # D = B + TIP on the jib


def _p(v):
    return f"[{float(v[0])!r}, 0, {float(v[1])!r}]"


# centres of mass: boom 5 u, links F + 5 u, jib B + (2, -1)
COMS = {"boom": np.zeros(2) + 5 * B0 / L, "link1": F1 + 5 * B0 / L,
        "link2": F2 + 5 * B0 / L, "jib": B0 + np.array([2.0, -1.0])}
PIVOTS = {"boom": np.zeros(2), "link1": F1, "link2": F2}

REDUNDANT = f"""cranefe: 1
name: parallelogram with a redundant link
plane: xz
nodes:
  O: [0.0, 0, 0.0]
  F1: {_p(F1)}
  F2: {_p(F2)}
  B: {_p(B0)}
  E1: {_p(B0 + F1)}
  E2: {_p(B0 + F2)}
  D: {_p(B0 + TIP)}
ground: [O, F1, F2]
bodies:
  boom: {{mass: 1000, com: {_p(COMS['boom'])}, inertia: 8000, nodes: [O, B]}}
  link1: {{mass: 200, com: {_p(COMS['link1'])}, inertia: 1500, nodes: [F1, E1]}}
  link2: {{mass: 150, com: {_p(COMS['link2'])}, inertia: 1200, nodes: [F2, E2]}}
  jib: {{mass: 500, com: {_p(COMS['jib'])}, inertia: 700, nodes: [B, E1, E2, D]}}
joints:
  - {{type: hinge, bodies: [ground, boom], at: O}}
  - {{type: hinge, bodies: [ground, link1], at: F1}}
  - {{type: hinge, bodies: [ground, link2], at: F2}}
  - {{type: hinge, bodies: [boom, jib], at: B}}
  - {{type: hinge, bodies: [link1, jib], at: E1}}
  - {{type: hinge, bodies: [link2, jib], at: E2}}
"""


def _rot(t, v):
    c, s = math.cos(t), math.sin(t)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def _hand_redundant(alpha):
    """{body: [(x, z, theta), d/dalpha, d2/dalpha2]} and the tip D's (X, X', X'')."""
    th = alpha - A_REF
    out = {}
    for name, P in PIVOTS.items():
        v = COMS[name] - P
        out[name] = [np.array([*(P + _rot(th, v)), th]),
                     np.array([*_rot(th + math.pi / 2, v), 1.0]),
                     np.array([*(-_rot(th, v)), 0.0])]
    dB = [_rot(th, B0) - B0, _rot(th + math.pi / 2, B0), -_rot(th, B0)]
    out["jib"] = [np.array([*(COMS["jib"] + dB[0]), 0.0]), np.array([*dB[1], 0.0]),
                  np.array([*dB[2], 0.0])]
    out["D"] = [B0 + TIP + dB[0], dB[1], dB[2]]
    return out


def test_a_redundant_joint_is_solved_by_the_pseudo_inverse():
    """Tolerances: poses 1e-10 (Newton stops at 1e-13 of the size, 10 m), derivatives
    1e-9 and 1e-8 (one and two more least-squares solves, condition ~10)."""
    m = load("redundant.yaml", REDUNDANT)
    lk = Linkage(m, "boom", "O", "B")
    names = [b.name for b in m.bodies]
    assert lk.n == 12 and lk.square is False
    F, J = lk.equations(lk.q_ref[None], np.array([A_REF]))
    assert J.shape == (1, 13, 12) and np.abs(F).max() < 1e-12
    degs = (12.0, 47.0, 71.0)           # below and above the model's 30 deg
    st = lk.state(np.radians(degs))
    assert np.all(st.residual <= 1e-10 * lk.scale)
    tol = (1e-10, 1e-9, 1e-8)
    for n, deg in enumerate(degs):
        hand = _hand_redundant(math.radians(deg))
        for b in lk.bodies:
            i = lk.local[b]
            for d, arr in enumerate((st.q, st.dq, st.ddq)):
                assert np.allclose(arr[n, 3 * i:3 * i + 3], hand[names[b]][d], rtol=0,
                                   atol=tol[d] * 10), (deg, names[b], d)
        X = st.point(m.node_index["D"])
        for d in range(3):
            assert np.allclose(X[d][n], hand["D"][d], rtol=0, atol=tol[d] * 10), (deg, d)
    # the continuation passed through the table both ways, at its step
    assert lk._A[0] <= math.radians(12.0) and lk._A[-1] >= math.radians(71.0)
    assert np.allclose(np.diff(lk._A), Linkage.STEP, rtol=1e-12)
    # Newton from a poor start closes the loops by least squares too
    q, res = lk.newton(lk.q_ref[None] + 0.01, np.array([math.radians(47.0)]))
    assert res[0] < 1e-10
    assert np.allclose(q[0], st.q[1], rtol=0, atol=1e-9)
    # the least-squares solve of a consistent system is its exact solution (the full
    # Jacobian, the driver's row included, has rank 12: one solution)
    y = np.linspace(-1.0, 1.0, 12)
    x = lk._lin_solve(J, np.einsum("nij,j->ni", J, y))
    assert np.allclose(x[0], y, rtol=0, atol=1e-12)


# =============================================================== luffing/analysis.py
# (tools/mutation.py luffing_analysis) A four-bar whose coupler turns, so that its
# points move on coupler curves, not circles: the boom O-E-B hinged to the ground at O,
# a tie E-Q-D hinged to the boom at E and to a rocker G-Q at Q, the rocker hinged to the
# ground at G; the jib tip D on the tie; a rack from A (ground) to C on the boom.
# By hand, with theta = alpha - alpha_ref (alpha: O -> B): E = O + Rot(theta)(E0 - O),
# Q = the intersection of |Q - G| = |Q0 - G| and |Q - E| = |Q0 - E0| on the model's
# side, the tie's and rocker's rotations (cos, sin) the ones taking Q0 - E0 to Q - E and
# Q0 - G to Q - G; every point X = Rot X0 + p of its body. All of it is analytic in
# alpha, so its alpha derivatives come from Cauchy's integral formula (32 samples on a
# circle of radius 0.02 rad: aliasing 0.02^32, round-off ~1e-16 / 0.02^2 of the size).
# J = sum m |dc/dalpha|^2 + I (dtheta/dalpha)^2 + J_rotor (i/R)^2 (ds/dalpha)^2
# (docs/luffing.md's complete inertia), dtheta/dalpha = c s' - s c'.
FB = {k: np.array(v, float) for k, v in dict(
    O=[1, 2], E=[5, 6], B=[11, 12], G=[-3, 8], Q=[-0.5, 10], D=[0.5, 12.5],
    C=[3, 4], A=[4, -1]).items()}
FB_BODIES = {"boom": (2000.0, 2.0e4, np.array([6.0, 7.0])),
             "tie": (100.0, 50.0, np.array([1.0, 9.5])),
             "rocker": (300.0, 100.0, np.array([-2.0, 9.0]))}
FB_REF = math.atan2(10.0, 10.0)
FB_K = 0.01 * (10.0 / 0.1) ** 2          # rotor 0.01 kg m^2 through gear 10 / pinion 0.1
FB_A0, FB_AK, FB_TK, FB_M = math.radians(35.0), math.radians(60.0), 8.0, 2000.0

FOURBAR = f"""cranefe: 1
name: four-bar with a turning coupler
plane: xz
nodes:
  O: {_p(FB['O'])}
  E: {_p(FB['E'])}
  B: {_p(FB['B'])}
  G: {_p(FB['G'])}
  Q: {_p(FB['Q'])}
  D: {_p(FB['D'])}
  C: {_p(FB['C'])}
  A: {_p(FB['A'])}
ground: [O, G, A]
bodies:
  boom: {{mass: 2000, com: [6, 0, 7], inertia: 2.0e4, nodes: [O, E, B, C]}}
  tie: {{mass: 100, com: [1, 0, 9.5], inertia: 50, nodes: [E, Q, D]}}
  rocker: {{mass: 300, com: [-2, 0, 9], inertia: 100, nodes: [G, Q]}}
joints:
  - {{type: hinge, bodies: [ground, boom], at: O}}
  - {{type: hinge, bodies: [boom, tie], at: E}}
  - {{type: hinge, bodies: [tie, rocker], at: Q}}
  - {{type: hinge, bodies: [ground, rocker], at: G}}
linear_drives:
  rack: {{nodes: [A, C], pinion_radius: 0.1, gear_ratio: 10, rotor_inertia: 0.01}}
"""


def _fb_flat(alpha):
    """Rows (per alpha, complex allowed): for each body (c_x, c_z, cos, sin), then the
    tip D (x, z) and the rack's length s."""
    a = np.asarray(alpha)
    th = a - FB_REF
    c, s = np.cos(th), np.sin(th)
    N = FB

    def rot(c, s, v):
        return np.stack([c * v[0] - s * v[1], s * v[0] + c * v[1]])
    E = N["O"][:, None] + rot(c, s, N["E"] - N["O"])
    r1, r2 = np.linalg.norm(N["Q"] - N["G"]), np.linalg.norm(N["Q"] - N["E"])
    dv = E - N["G"][:, None]
    L2 = dv[0] ** 2 + dv[1] ** 2
    aa = (r1 ** 2 - r2 ** 2 + L2) / (2 * L2)
    h = np.sqrt(r1 ** 2 / L2 - aa ** 2)
    Q = N["G"][:, None] + aa * dv + h * np.stack([-dv[1], dv[0]])

    def turn(u0, u):
        n = u0 @ u0
        return (u0[0] * u[0] + u0[1] * u[1]) / n, (u0[0] * u[1] - u0[1] * u[0]) / n
    rows = []
    frames = {"boom": ((c, s), N["O"], N["O"][:, None]),
              "tie": (turn(N["Q"] - N["E"], Q - E), N["E"], E),
              "rocker": (turn(N["Q"] - N["G"], Q - N["G"][:, None]), N["G"],
                         N["G"][:, None])}
    for name, ((cc, ss), X0, X) in frames.items():
        com = X + rot(cc, ss, FB_BODIES[name][2] - X0)
        rows += [com[0], com[1], cc, ss]
    (cc, ss), X0, X = frames["tie"]
    D = X + rot(cc, ss, N["D"] - X0)
    C = N["O"][:, None] + rot(c, s, N["C"] - N["O"])
    rows += [D[0], D[1], np.sqrt((C[0] - N["A"][0]) ** 2 + (C[1] - N["A"][1]) ** 2)]
    return np.stack(rows)


def _fb_hand(alpha):
    """J, dJ/dalpha, |dD/dalpha|^2 and its alpha derivative at the angles alpha (1-D),
    from the flattened quantities and their Cauchy derivatives (orders 1 to 3)."""
    alpha = np.atleast_1d(np.asarray(alpha, float))
    n, r = 32, 0.02
    z = alpha[None, :] + r * np.exp(2j * np.pi * np.arange(n) / n)[:, None]
    F = _fb_flat(z.ravel()).reshape(-1, n, len(alpha))
    cf = np.fft.fft(F, axis=1) / n
    f0 = _fb_flat(alpha)
    f1, f2 = (cf[:, 1] / r).real, (2 * cf[:, 2] / r ** 2).real
    J, dJ = 0.0, 0.0
    for k, (m, inertia, _) in enumerate(FB_BODIES.values()):
        x, zc, c, s = (4 * k + i for i in range(4))
        J = J + m * (f1[x] ** 2 + f1[zc] ** 2)
        dJ = dJ + 2 * m * (f1[x] * f2[x] + f1[zc] * f2[zc])
        w = f0[c] * f1[s] - f0[s] * f1[c]             # dtheta/dalpha
        dw = f0[c] * f2[s] - f0[s] * f2[c]            # (c' s' - s' c' = 0)
        J = J + inertia * w ** 2
        dJ = dJ + 2 * inertia * w * dw
    J = J + FB_K * f1[14] ** 2
    dJ = dJ + 2 * FB_K * f1[14] * f2[14]
    v2 = f1[12] ** 2 + f1[13] ** 2                    # |dD/dalpha|^2
    dv2 = 2 * (f1[12] * f2[12] + f1[13] * f2[13])
    return J, dJ, v2, dv2


@cache
def _fb_luffing(inertia="complete"):
    import cranefe.analysis.luffing.analysis as an
    folder = tempfile.mkdtemp(prefix="luff-fourbar-")
    path = os.path.join(folder, "fourbar.yaml")
    with open(path, "w") as f:
        f.write(FOURBAR)
    model = load(path)
    sc = an.Scene("boom", "O", "B", FB_TK, "rack", "D", FB_M, 6.0,
                  ("alpha", FB_A0, "alpha0_deg"), ("alpha", FB_AK, "alphak_deg"),
                  inertia, FB_TK / 25)
    return an.Luffing(model, sc)


def _quad(f, a, b):
    return quad(f, a, b, epsabs=0, epsrel=1e-13, limit=200)[0]


@cache
def _fb_S(m):
    """int sqrt(J + m |D'|^2) dalpha from FB_A0 to FB_AK."""
    def f(a):
        J, _, v2, _ = _fb_hand(a)
        return math.sqrt(J[0] + m * v2[0])
    return _quad(f, FB_A0, FB_AK)


@cache
def _fb_partial(m, b):
    """int sqrt(J + m |D'|^2) dalpha from FB_A0 to b."""
    def f(a):
        J, _, v2, _ = _fb_hand(a)
        return math.sqrt(J[0] + m * v2[0])
    return _quad(f, FB_A0, b)


@cache
def _fb_links(m):
    """int J / sqrt(J + m |D'|^2) dalpha from FB_A0 to FB_AK."""
    def f(a):
        J, _, v2, _ = _fb_hand(a)
        return J[0] / math.sqrt(J[0] + m * v2[0])
    return _quad(f, FB_A0, FB_AK)


def test_the_four_bar_tip_does_not_move_on_a_circle():
    """The configuration's point: d|D'|^2/dalpha is far from zero over the range (it is
    zero on any circle travelled at a rate proportional to alpha)."""
    al = np.linspace(FB_A0, FB_AK, 11)
    J, dJ, v2, dv2 = _fb_hand(al)
    assert np.abs(dv2).max() > 0.3 * v2.max()
    # the hand J against the code's reduced inertia (a check of the model's writing,
    # not of analysis.py): the Proxy's J at the same angles
    lf = _fb_luffing()
    np.testing.assert_allclose(lf.proxy("J", al), J, rtol=1e-9)
    np.testing.assert_allclose(lf.proxy("dJ", al), dJ, rtol=1e-7, atol=1e-7 * np.abs(dJ).max())


def test_the_optimum_with_the_load_carried_on_a_coupler_curve():
    """Luffing.optimal with extra_inertia m |dD/dalpha|^2 (the sensitivity report's
    load-mass law) on the non-circular tip path: S = int sqrt(J + Jx) dalpha; at the
    angles a_i reached at tau_i = S(a_i) / S the law gives alpha = a_i, alpha' = S /
    sqrt(J + Jx) and alpha'' = -(J' + Jx') / (2 (J + Jx)) alpha'^2 (eq. 16 with the
    extra inertia). Tolerances: the Chebyshev fits of 129 nodes of these smooth
    functions are exact to ~1e-13; alpha'' to 1e-8 relative (the fitted ratio's
    derivative terms, and Cauchy's J' to ~1e-10)."""
    lf = _fb_luffing()
    p = lf.proxy

    def extra(al):
        return (FB_M * (p("dx", al) ** 2 + p("dz", al) ** 2),
                2 * FB_M * (p("dx", al) * p("ddx", al) + p("dz", al) * p("ddz", al)))
    law = lf.optimal(extra_inertia=extra, name="with load")
    S = _fb_S(FB_M)
    assert law.name == "with load" and law.info["S"] == pytest.approx(S, rel=1e-10)
    a_i = np.radians([37.0, 44.0, 52.5, 58.0])
    tau = np.array([_fb_partial(FB_M, x) for x in a_i]) / S
    al, d1, d2 = law.evaluate(tau)
    J, dJ, v2, dv2 = _fb_hand(a_i)
    np.testing.assert_allclose(al, a_i, rtol=0, atol=1e-10)
    np.testing.assert_allclose(d1, S / np.sqrt(J + FB_M * v2), rtol=1e-9)
    want = -(dJ + FB_M * dv2) / (2 * (J + FB_M * v2)) * (S ** 2 / (J + FB_M * v2))
    np.testing.assert_allclose(d2, want, rtol=1e-7)
    # the paper's inertia (eq. 3) with the same extra inertia: (Jp + Jx) alpha'^2 = S^2
    # along the law (eq. 16 integrated once), Jp read from the proxy
    lawp = lf.optimal(which="paper", extra_inertia=extra)
    al, d1, d2 = lawp.evaluate(np.linspace(0, 1, 7))
    Jp = p("Jp", al) + FB_M * (p("dx", al) ** 2 + p("dz", al) ** 2)
    np.testing.assert_allclose(Jp * d1 ** 2, lawp.info["S"] ** 2, rtol=1e-9)


def test_the_sensitivity_reports_load_rows_on_a_coupler_curve(monkeypatch):
    """The load-mass rows carry the load rigidly at D: T_with = S_m^2 / (2 t_k^2),
    S_m = int sqrt(J + m |D'|^2); the links' energy of that law, (1/t_k^2) int 1/2 J
    alpha'^2 dtau = S_m / (2 t_k^2) int J / sqrt(J + m |D'|^2) dalpha (dtau = sqrt(J +
    Jx) dalpha / S_m); the largest difference of alpha(tau) from the optimum without the
    load, each law inverted by hand on 20001 angles (cumulative trapezoid, ~1e-9 rad).
    The swing-free law and the sway simulation (their own kill tests) are stand-ins."""
    import cranefe.analysis.luffing.analysis as an
    from cranefe.analysis.luffing import sway
    from cranefe.analysis.luffing.laws import standard_law

    def fake_sf(proxy, alpha0, alphak, t_k, H, g, guess, which="complete"):
        law = standard_law("cycloidal", alpha0, alphak)
        law.status, law.message = 0, "stand-in"
        return law
    monkeypatch.setattr(sway, "swing_free_law", fake_sf)
    monkeypatch.setattr(sway, "simulate", lambda *a, **k: {"residual": 0.0, "max": 0.0})
    lf = _fb_luffing()
    exact = lf.optimal()
    rep = an.sensitivity_report(lf, exact)
    rows = rep["load_mass"]
    assert [r["load_mass_kg"] for r in rows] == [0.0, 1000.0, 2000.0, 3000.0]
    al = np.linspace(FB_A0, FB_AK, 20001)
    J, _, v2, _ = _fb_hand(al)
    S0 = _fb_S(0.0)
    tau0 = cumulative_trapezoid(np.sqrt(J), al, initial=0.0)
    tau0 /= tau0[-1]
    u = np.linspace(0, 1, 201)
    for row in rows:
        m = row["load_mass_kg"]
        Sm = _fb_S(m)
        assert row["T_mean_with_load_J"] == pytest.approx(Sm ** 2 / (2 * FB_TK ** 2),
                                                          rel=1e-9)
        links = Sm / (2 * FB_TK ** 2) * _fb_links(m)
        assert row["T_links_of_that_law_J"] == pytest.approx(links, rel=1e-9)
        taum = cumulative_trapezoid(np.sqrt(J + m * v2), al, initial=0.0)
        taum /= taum[-1]
        diff = np.abs(np.interp(u, taum, al) - np.interp(u, tau0, al)).max()
        assert row["max_law_difference_deg"] == pytest.approx(math.degrees(diff),
                                                              rel=1e-6, abs=1e-7)
    assert rows[0]["T_mean_with_load_J"] == pytest.approx(S0 ** 2 / (2 * FB_TK ** 2),
                                                          rel=1e-9)
    assert rows[3]["max_law_difference_deg"] > 0.03


def test_the_collocation_report_of_a_scene_with_the_papers_inertia():
    """inertia: paper: every collocation of the report solves eq. 16 with Jp (the
    paper's eq. 3), so its errors against the exact Jp law fall as they do for J:
    collocation at n = 10 to 2e-10 (Chebyshev) and 3e-9 rad (equally spaced), solve_bvp
    (tol 1e-8) to 3e-11 rad; bounds 1e-8, 1e-7, 1e-8. Were J used instead, each would
    differ from the Jp law by about the two optima's difference (1.07e-4 rad here,
    checked > 5e-5)."""
    import cranefe.analysis.luffing.analysis as an
    lf = _fb_luffing("paper")
    exact = lf.optimal()
    other = lf.optimal("complete")
    u = np.linspace(0, 1, 101)
    assert np.abs(exact.evaluate(u)[0] - other.evaluate(u)[0]).max() > 5e-5
    rep = an.collocation_report(lf, exact, ns=(3, 10))
    assert rep["chebyshev"][-1]["error_rad"] < 1e-8
    assert rep["equally_spaced"][-1]["error_rad"] < 1e-7
    assert rep["solve_bvp"]["error_rad"] < 1e-8
