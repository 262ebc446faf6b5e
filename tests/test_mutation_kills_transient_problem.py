"""Fast kill tests for cranefe/analysis/transient/problem.py (tools/mutation.py
transient_problem; docs/testing.md, "Mutation testing"): the equations `Problem` builds for
the two-mass hoist of cranefe/cases.py, compared with the ones written out by hand.

The hoist (cases.two_mass_hoist, sway off): coordinates q = (z, theta), z the load's
vertical displacement (up), theta the drum angle (hauling in > 0); drum radius r = 0.25,
inertia J = 500, load m = 5000 on n = 2 falls of one rope EA = 2e7 of length 30 + 20 n =
70 m over the reeving, so one rope row R = [-n, r] (stretch r theta - n z), c = EA / 70,
hanging force S0 = m g / n, holding torque r S0, weight f = (-m g, 0).
- drum driven by a torque: F0 = (0, -r S0) (the brake's holding torque released), load
  (e_theta, torque(t)); K_rest = K - R^T c R = 0 (the rope is the only stiffness);
- by a speed: theta prescribed; grounded: the load's z held (contact, up = +1), S0 = 0
  (the rope just taut), F0 = the weight the ground carries;
- by a motor through a gearbox i (rotor inertia I_r adds I_r i^2 to J): MotorLoad
  (e_theta, i); drum torque i M(i theta');
- not driven: theta held (prescribed 0), reaction torque r S0 + residual;
- highest natural frequency: free w^2 = k (n^2/m + r^2/J), drum held w^2 = n^2 k / m.
Comparisons to 1e-12 relative (a few roundings) unless said.
"""

import math

import numpy as np
import pytest
import scipy.sparse as sp

from cranefe import cases
from cranefe.analysis.transient.problem import Problem, highest_omega, subsystem
from cranefe.analysis.transient.scene import parse
from cranefe.errors import ModelError
from cranefe.model import load
from cranefe.system import assemble

G = 9.81
J, r, m, n, EA = 500.0, 0.25, 5000.0, 2, 2.0e7
k = EA / (30 + 20 * n)
S0 = m * G / n
TOL = 1e-12


def close(a, b, tol=TOL):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    assert a.shape == b.shape
    np.testing.assert_allclose(a, b, rtol=0, atol=tol * max(np.abs(b).max(initial=0), 1e-300))


def make(tmp_path, analysis, effects="{sway: false}", model_text=None, name="s.yaml"):
    text = model_text or cases.two_mass_hoist()[0]
    mp = tmp_path / (name + ".model.yaml")
    mp.write_text(text)
    sp_ = tmp_path / name
    sp_.write_text(f"cranefe: 1\nscene: t\nmodel: {mp}\neffects: {effects}\nanalysis:\n"
                   f"  type: transient\n{analysis}")
    model = load(sp_)
    return Problem(model, parse(model))


def common(p, J_=J):
    assert p.labels == ("node B z", "drum hoist") and p.n == 2
    close(p.eq.M, np.diag([m, J_]))
    close(p.eq.K, np.zeros((2, 2)), 1e-9)     # K - R^T c R: k n^2 = 1.1e6 cancelled
    assert np.abs(p.eq.K).max() <= 1e-9 * k * n * n
    close(p.eq.R, [[-n, r]])
    close(p.R.toarray(), [[-n, r]])
    close(p.eq.c, [k])
    close(p.hanging, [S0])
    assert p.drum_q == {0: 1}
    assert list(p.rope_of_row) == [0]
    close(p.system.f, [-m * G, 0.0])
    assert p.force_scale == pytest.approx(m * G, rel=TOL)
    assert p.length_scale == p.model.length_scale


def test_torque_drive(tmp_path):
    p = make(tmp_path, "  drums:\n    hoist: {torque: 1000, ramp: 0.2}\n")
    common(p)
    close(p.eq.S0, [S0])
    close(p.S0, [S0])
    close(p.hold, [-n * S0, r * S0])
    close(p.eq.F0, [0.0, -r * S0])
    assert p.eq.prescribed == {} and p.prescribed == {}
    assert len(p.eq.contacts) == 0 and len(p.eq.up) == 0
    assert list(p.free) == [0, 1] and p.sub is p.system
    assert p.eq.contacts.dtype.kind == "i" and p.contacts.dtype.kind == "i"
    assert p.eq.motors == [] and p.warnings == []
    assert p.drive_of[0][0] == "torque"
    assert p.C is None and p.eq.C is None and not p.eq.has_damping
    [(Gm, s)] = p.eq.loads
    close(Gm, [[0.0], [1.0]])
    close(s.value(0.1), [500.0])                    # the ramp 1000 t / 0.2
    close(s.d(0.1), [5000.0])
    close(s.d(0.2, True), [5000.0])
    close(s.d(0.2), [0.0])
    close(p.eq.force(0.1), [0.0, 500.0 - r * S0])
    q, v, a = np.array([0.01, 0.3]), np.array([0.1, 2.0]), np.array([1.0, 3.0])
    close(p.drum_torque(0.1, q, v, a, np.array([True])), [500.0])
    # free: w^2 = k (n^2/m + r^2/J)
    assert p.highest_omega() == pytest.approx(math.sqrt(k * (n * n / m + r * r / J)),
                                              rel=1e-12)


def test_held_drum_node_force_and_modal_damping(tmp_path):
    psi = 0.2
    text = cases.two_mass_hoist()[0].replace("hoist: {EA:", f"hoist: {{psi: {psi}, EA:")
    p = make(tmp_path, "  forces:\n    B: {force: [100, 0, -5000], ramp: 0.5}\n",
             "{sway: false, damping: modal}", text)
    common(p)
    close(p.eq.F0, [0.0, 0.0])
    assert list(p.eq.prescribed) == [1]
    pr = p.eq.prescribed[1]
    close(pr(0.7), [0.0]); close(pr.integral(0.7), [0.0])
    assert p.drive_of[0] == ("held", None)
    assert list(p.free) == [0]
    assert p.sub.dofs.labels == ("node B z",)
    [(Gm, s)] = p.eq.loads
    close(Gm, [[0.0, 0.0, 1.0], [0.0, 0.0, 0.0]])     # the node's (x, y, z) -> q: z only
    close(s.value(0.25), [50.0, 0.0, -2500.0])
    close(s.d(0.25), [200.0, 0.0, -10000.0])
    close(p.eq.force(0.25), [-2500.0, 0.0])
    assert p.warnings == ["force on node 'B': a part of it (100 N) acts where the node "
                          "has no coordinate (effects) and is carried rigidly"]
    # drum held: one mode z, w^2 = n^2 k / m, shape 1/sqrt(m); modal damping
    # C = M V diag(2 zeta w) V^T M = 2 zeta w m at z, zeta = psi / (4 pi) (one element)
    w = math.sqrt(n * n * k / m)
    assert p.highest_omega() == pytest.approx(w, rel=1e-12)
    close(p.eq.C, [[2 * psi / (4 * math.pi) * w * m, 0.0], [0.0, 0.0]], 1e-9)
    assert p.eq.U is None and p.eq.has_damping
    # reaction torque of the held drum: r S0 + residual; at rest and with a motion
    q0 = np.zeros(2)
    close(p.drum_torque(0.0, q0, q0, q0, np.array([True])), [r * S0])
    q, v, a = np.array([0.01, 0.0]), np.array([0.1, 0.0]), np.array([1.0, 3.0])
    hand = r * S0 + J * 3.0 + r * k * (-n * 0.01)
    close(p.drum_torque(0.5, q, v, a, np.array([True])), [hand])


def test_grounded_speed(tmp_path):
    p = make(tmp_path, "  initial: grounded\n  drums:\n    hoist: {speed: 2.0}\n")
    common(p)
    close(p.eq.S0, [0.0])
    close(p.hold, [0.0, 0.0])
    close(p.eq.F0, [-m * G, 0.0])                  # the weight the ground carries
    assert list(p.eq.contacts) == [0] and list(p.eq.up) == [1.0]
    assert p.eq.contacts.dtype.kind == "i"
    assert list(p.eq.prescribed) == [1] and p.drive_of[0][0] == "speed"
    close(p.eq.prescribed[1](0.3), [2.0])
    assert list(p.free) == [0] and p.eq.loads == []
    q, v, a = np.array([0.0, 0.4]), np.array([0.0, 2.0]), np.array([0.0, 1.5])
    # residual at theta: J a + r k (r theta) (the rope taut from zero force)
    close(p.drum_torque(0.2, q, v, a, np.array([True])), [J * 1.5 + r * k * r * 0.4])
    close(p.drum_torque(0.2, q, v, a, np.array([False])), [J * 1.5])


def test_grounded_downward_z(tmp_path):
    """Gravity along +z: the load's coordinate points down, up = -1."""
    text = cases.two_mass_hoist()[0].replace("nodes: {D: [0, 0, 0], S: [0, 0, 30], "
                                             "B: [0, 0, 10]}",
                                             "nodes: {D: [0, 0, 0], S: [0, 0, -30], "
                                             "B: [0, 0, -10]}\ngravity: [0, 0, 9.81]")
    p = make(tmp_path, "  initial: grounded\n  drums:\n    hoist: {speed: 2.0}\n",
             model_text=text)
    assert list(p.eq.up) == [-1.0]
    close(p.eq.F0, [m * G, 0.0])
    close(p.eq.S0, [0.0])


def test_motor_drive_through_a_gearbox(tmp_path):
    text = cases.two_mass_hoist()[0].replace(
        "inertia: 500.0}", "inertia: 500.0, motor: {rotor_inertia: 0.5, gear_ratio: 4}}")
    p = make(tmp_path, "  drums:\n    hoist: {motor: {stall_torque: 15000, "
                       "synchronous_speed: 10}}\n", model_text=text)
    common(p, J + 0.5 * 16)
    close(p.eq.F0, [0.0, -r * S0])
    [ml] = p.eq.motors
    close(ml.e, [0.0, 1.0])
    assert ml.gear == 4.0 and ml.name == "hoist"
    assert p.drive_of[0][0] == "motor" and p.eq.loads == [] and p.eq.prescribed == {}
    v = np.array([0.3, 1.5])
    torque = 4 * 15000 * (1 - 4 * 1.5 / 10)            # i M(i w)
    close(p.drum_torque(0.0, np.zeros(2), v, np.zeros(2), np.array([True])), [torque])
    close(p.eq.motor_force(v), [0.0, torque])
    assert p.highest_omega() == pytest.approx(math.sqrt(k * (n * n / m + r * r / 508.0)),
                                              rel=1e-12)


def test_no_rope_elasticity(tmp_path):
    with pytest.raises(ModelError, match="elastic ropes") as e:
        make(tmp_path, "  drums:\n    hoist: {torque: 1000}\n",
             "{sway: false, rope_elasticity: false}")
    msg = str(e.value)
    assert msg.startswith(str(tmp_path / "s.yaml") + ": effects.rope_elasticity: ")
    assert msg.endswith("a transient needs elastic ropes (their forces are what it "
                        "computes); remove rope_elasticity: false")


def test_grounded_node_on_a_body(tmp_path):
    text = cases.two_mass_hoist()[0].replace("ground: [D, S]", "ground: [D, S, B]")
    with pytest.raises(ModelError, match="carried by a body or fixed") as e:
        make(tmp_path, "  initial: grounded\n  grounded: [B]\n", model_text=text)
    assert str(e.value) == (f"{tmp_path / 's.yaml'}: analysis.grounded: node 'B' is carried "
                            "by a body or fixed; a load resting on the ground must be a "
                            "point mass at a node of its own")


def test_subsystem():
    text, _ = cases.two_mass_hoist()
    import tempfile, pathlib
    d = pathlib.Path(tempfile.mkdtemp())
    (d / "m.yaml").write_text(text)
    system = assemble(load(d / "m.yaml"))
    sub = subsystem(system, [1])
    assert sub.dofs.labels == ("drum hoist",)
    assert sub.dofs.kinds == (system.dofs.kinds[1],)
    close(sub.K.toarray(), [[k * r * r]])
    close(sub.M.toarray(), [[J]])
    close(sub.f, [0.0])
    close(sub.dofs.T.toarray(), system.dofs.T.toarray()[:, [1]])
    assert sp.issparse(sub.K) and sp.issparse(sub.M)


def chain(masses, kk=1.0e6):
    """A fixed-free chain of springs kk along x with the given masses (0: massless)."""
    N = len(masses)
    nodes = "{G: [0, 0, 0], " + ", ".join(f"N{i}: [{i + 1}, 0, 0]" for i in range(N)) + "}"
    ends = ["G"] + [f"N{i}" for i in range(N)]
    springs = "\n".join(f"  - {{name: k{i}, type: axial, nodes: [{a}, {b}], stiffness: {kk}}}"
                        for i, (a, b) in enumerate(zip(ends[:-1], ends[1:])))
    mass = "{" + ", ".join(f"N{i}: {mm}" for i, mm in enumerate(masses) if mm) + "}"
    return (f"cranefe: 1\nname: chain\nplane: xz\ngravity: [0, 0, 0]\nnodes: {nodes}\n"
            f"ground: [G]\nmasses: {mass}\nsprings:\n{springs}\neffects: {{sway: false}}\n")


def system_of(tmp_path, text, name):
    (tmp_path / name).write_text(text)
    return assemble(load(tmp_path / name))


def test_highest_omega_massless_node(tmp_path):
    """G -k- m -k- (massless) -k- m: condensed, the two masses see k and k/2 in series:
    K* = k [[3/2, -1/2], [-1/2, 1/2]], lambda = (k/m)(1 +- 1/sqrt 2)."""
    s = system_of(tmp_path, chain([100.0, 0.0, 100.0]), "c.yaml")
    assert highest_omega(s) == pytest.approx(math.sqrt(1e4 * (1 + 1 / math.sqrt(2))),
                                             rel=1e-12)
    s = system_of(tmp_path, chain([0.0, 0.0]), "z.yaml")
    assert highest_omega(s) == 0.0


def test_highest_omega_large(tmp_path):
    """> 400 coordinates: Lanczos (tol 1e-4 on lambda, so 1e-4 on w) against the chain's
    exact w_N = 2 sqrt(k/m) sin((2N - 1) pi / (2 (2N + 1)))."""
    N = 402
    text, ex = cases.spring_chain(N)
    s = system_of(tmp_path, text, "big.yaml")
    assert highest_omega(s) == pytest.approx(ex["omega"][-1], rel=1e-4)
    # one massless node (the 3rd): condensed by its Schur complement, against a dense
    # reference (the masses' K - K_ab K_bb^-1 K_ba, numpy's eigvalsh)
    masses = [100.0] * N
    masses[2] = 0.0
    s = system_of(tmp_path, chain(masses), "bigb.yaml")
    K = s.K.toarray()
    a = np.flatnonzero(np.array(masses) > 0)
    b = np.flatnonzero(np.array(masses) == 0)
    Ks = K[np.ix_(a, a)] - K[np.ix_(a, b)] @ np.linalg.solve(K[np.ix_(b, b)], K[np.ix_(b, a)])
    lam = np.linalg.eigvalsh(Ks / 100.0)[-1]
    assert highest_omega(s) == pytest.approx(math.sqrt(lam), rel=1e-4)


SHEAVE = """cranefe: 1
name: sheave block
plane: xz
nodes: {D: [0, 0, 0], T: [0, 0, 30], N: [0, 0, 20], B: [0, 0, 10]}
ground: [D, T]
masses: {N: 1000.0, B: 5000.0}
drums:
  hoist: {node: D, radius: 0.25, inertia: 500.0}
ropes:
HANG  hoist: {EA: 2.0e7, path: [hoist, N, B]}
effects: {sway: false}
"""


def test_grounded_tensions_of_a_structure(tmp_path):
    """A sheave block N (1000 kg) hung from T by the rope `hang` (EA 1e7, 10 m); the hoist
    rope (EA 2e7, 30 m) runs from the drum up over N and down to the load B (5000 kg) on
    the ground. q = (z_N, z_B, theta); rows hang [-1, 0, 0], hoist [2, -1, r].
    Grounded: the hoist row is left out but for 1e-9 of its stiffness, so
    S_hang = k_h m_N g / (k_h + 4e-9 k_hoist) (N's one equation), S_hoist = 0;
    hanging: S_hoist = m_B g, S_hang = m_N g + 2 m_B g."""
    kh, kho = 1.0e7 / 10, 2.0e7 / 30
    text = SHEAVE.replace("HANG", "  hang: {EA: 1.0e7, path: [T, N]}\n")
    p = make(tmp_path, "  initial: grounded\n  grounded: [B]\n", model_text=text)
    assert p.labels == ("node N z", "node B z", "drum hoist")
    close(p.R.toarray(), [[-1.0, 0.0, 0.0], [2.0, -1.0, r]])
    close(p.c, [kh, kho])
    close(p.S0, [kh * 1000 * G / (kh + 4e-9 * kho), 0.0])
    close(p.hanging, [1000 * G + 2 * 5000 * G, 5000 * G])
    close(p.eq.F0, [0.0, -5000 * G, 0.0])
    assert list(p.eq.contacts) == [1] and list(p.eq.up) == [1.0]
    close(p.hold, p.R.toarray().T @ p.S0)
    assert p.force_scale == pytest.approx(1000 * G + 2 * 5000 * G, rel=TOL)
    assert list(p.eq.prescribed) == [2] and list(p.free) == [0, 1]
    close(p.eq.K, [[0.0] * 3] * 3, 1e-9)


def test_grounded_mechanism(tmp_path):
    """A mass N hung below the load B by a rope `tail`: with B on the ground (and N not)
    the tail rope touches B and is left out, so nothing holds N."""
    text = cases.two_mass_hoist()[0].replace(
        "B: [0, 0, 10]}", "B: [0, 0, 10], N: [0, 0, 5]}").replace(
        "masses: {B: 5000.0}", "masses: {B: 5000.0, N: 100.0}").replace(
        "effects:", "  tail: {EA: 1.0e7, path: [B, N]}\neffects:")
    with pytest.raises(ModelError, match="not held") as e:
        make(tmp_path, "  initial: grounded\n  grounded: [B]\n", model_text=text)
    assert str(e.value) == (f"{tmp_path / 's.yaml'}: analysis.initial: with the loads on "
                            "the ground the crane is not held (a mechanism once the hoist "
                            "ropes carry nothing); check the model's supports")


def test_exact_damping(tmp_path):
    """damping: exact, drum held: the rope is a dashpot b = psi k / (2 pi w) at the
    hoisting frequency w = sqrt(n^2 k / m) (the one mode, which strains it), over its
    whole row: C = b R^T R with R = [-n, r] (the drum's column too)."""
    psi = 0.3
    text = cases.two_mass_hoist()[0].replace("hoist: {EA:", f"hoist: {{psi: {psi}, EA:")
    p = make(tmp_path, "  duration: 0.1\n", "{sway: false, damping: exact}", text)
    w = math.sqrt(n * n * k / m)
    b = psi * k / (2 * math.pi * w)
    close(p.eq.C.toarray() if sp.issparse(p.eq.C) else p.eq.C,
          b * np.array([[n * n, -n * r], [-n * r, r * r]]), 1e-12)
    assert p.eq.U is None and p.eq.W is None
    assert p.C is p.eq.C or np.array_equal(np.asarray(p.C.todense()), np.asarray(p.eq.C))
    model = p.model
    q = Problem(model, parse(model), damping=False)    # modal superposition damps itself
    assert q.C is None and q.eq.C is None and not q.eq.has_damping


def test_force_along_the_coordinate_no_warning(tmp_path):
    """A force along the load's coordinate loses nothing: no warning (the part lost is
    rounding, far below 1e-9 of the force)."""
    p = make(tmp_path, "  forces:\n    B: {force: [0, 0, 3000]}\n")
    assert p.warnings == []
    close(p.eq.force(1.0), [3000.0, 0.0])


def test_highest_omega_lanczos_condenses_the_massless_node(tmp_path, monkeypatch):
    """The Lanczos path (forced on the small chain by DENSE_OMEGA = 0) condenses the
    massless node by its Schur complement: the same (k/m)(1 + 1/sqrt 2) as the dense
    path, to Lanczos' 1e-4 (on two coordinates it is exact to rounding; without the
    complement the masses would see K_aa = k diag(2, 1): w^2 = 2 k/m, 17 % off)."""
    import cranefe.analysis.transient.problem as problem
    monkeypatch.setattr(problem, "DENSE_OMEGA", 0)
    s = system_of(tmp_path, chain([100.0, 0.0, 100.0]), "c.yaml")
    assert highest_omega(s) == pytest.approx(math.sqrt(1e4 * (1 + 1 / math.sqrt(2))),
                                             rel=1e-8)


@pytest.mark.parametrize("dense", [True, False])
def test_highest_omega_below_one_radian_per_second(tmp_path, monkeypatch, dense):
    """A soft chain G -k- m -k- m (k = 1 N/m, m = 100 kg): w^2 = (k/m)(3 + sqrt 5)/2,
    w = 0.162 rad/s, on both paths (nothing may floor the eigenvalue at 1)."""
    import cranefe.analysis.transient.problem as problem
    if not dense:
        monkeypatch.setattr(problem, "DENSE_OMEGA", 0)
    s = system_of(tmp_path, chain([100.0, 100.0], kk=1.0), "soft.yaml")
    assert highest_omega(s) == pytest.approx(math.sqrt(0.01 * (3 + math.sqrt(5)) / 2),
                                             rel=1e-8)


def _sheave_damped(tmp_path, psi=0.2):
    """The sheave block (test_grounded_tensions_of_a_structure) hanging, drum held by a
    speed profile, both ropes psi: free q = (z_N, z_B), M = diag(1000, 5000),
    K = k_h [[1, 0], [0, 0]] + k_hoist [[4, -2], [-2, 1]] (rows [-1, 0], [2, -1]);
    modal damping zeta = psi / (4 pi) in every mode (one psi for all elements), so
    C = M V diag(2 zeta w) V^T M over the modes V (V^T M V = I) of that 2 x 2 problem."""
    kh, kho = 1.0e7 / 10, 2.0e7 / 30
    text = SHEAVE.replace("HANG", f"  hang: {{psi: {psi}, EA: 1.0e7, path: [T, N]}}\n")
    text = text.replace("hoist: {EA:", f"hoist: {{psi: {psi}, EA:")
    p = make(tmp_path, "  drums:\n    hoist: {speed: 0.0}\n",
             "{sway: false, damping: modal}", text)
    M = np.diag([1000.0, 5000.0])
    K = kh * np.array([[1.0, 0.0], [0.0, 0.0]]) + kho * np.array([[4.0, -2.0], [-2.0, 1.0]])
    lam, V = np.linalg.eigh(np.linalg.inv(np.sqrt(M)) @ K @ np.linalg.inv(np.sqrt(M)))
    V = np.linalg.inv(np.sqrt(M)) @ V            # M-orthonormal mode shapes
    return p, M, V, np.sqrt(lam), psi / (4 * math.pi)


def test_modal_damping_kept_low_rank_above_dense_damping(tmp_path, monkeypatch):
    """Above DENSE_DAMPING coordinates (forced: 0) the damping is handed to the
    equations as U diag(W) U^T, U = M V, W = 2 zeta w (the drum's row zero), not formed."""
    import cranefe.analysis.transient.problem as problem
    monkeypatch.setattr(problem, "DENSE_DAMPING", 0)
    p, M, V, w, zeta = _sheave_damped(tmp_path)
    assert p.eq.C is None and p.eq.has_damping
    C = p.eq.U @ (p.eq.W[:, None] * p.eq.U.T)
    hand = np.zeros((3, 3))
    hand[:2, :2] = M @ V @ np.diag(2 * zeta * w) @ V.T @ M
    close(C, hand, 1e-9)
    assert p.warnings == []


def test_only_the_lowest_modes_damped_above_sparse_damping(tmp_path, monkeypatch):
    """Above SPARSE_DAMPING free coordinates (forced: 0) only the SPARSE_DAMPED_MODES
    (forced: 1) lowest modes are damped, C = 2 zeta w_1 M v_1 v_1^T M, and the scene is
    warned; formed densely (DENSE_DAMPING coordinates or fewer)."""
    import cranefe.analysis.transient.problem as problem
    monkeypatch.setattr(problem, "SPARSE_DAMPING", 0)
    monkeypatch.setattr(problem, "SPARSE_DAMPED_MODES", 1)
    p, M, V, w, zeta = _sheave_damped(tmp_path)
    C = p.eq.C.toarray() if sp.issparse(p.eq.C) else np.asarray(p.eq.C)
    hand = np.zeros((3, 3))
    hand[:2, :2] = 2 * zeta * w[0] * np.outer(M @ V[:, 0], M @ V[:, 0])
    close(C, hand, 1e-9)
    assert p.warnings == ["damping: the 1 lowest modes are damped, the others not"]
    # the same model below the limit: both modes damped, no warning
    monkeypatch.setattr(problem, "SPARSE_DAMPING", 1500)
    p, M, V, w, zeta = _sheave_damped(tmp_path)
    C = p.eq.C.toarray() if sp.issparse(p.eq.C) else np.asarray(p.eq.C)
    hand[:2, :2] = M @ V @ np.diag(2 * zeta * w) @ V.T @ M
    close(C, hand, 1e-9)
    assert p.warnings == []



CANTILEVER = """cranefe: 1
name: cantilever
plane: xz
gravity: [0, 0, 0]
nodes: {O: [0, 0, 0], T: [4, 0, 0]}
ground: [O]
masses: {T: 100.0}
members:
  arm: {type: beam, nodes: [O, T], E: 2.1e11, A: 1.0e-3, Iy: 1.0e-6, rho: 0,
        elements: 2, psi: 0.3}
"""


def test_exact_damping_of_beams_at_their_own_frequencies(tmp_path):
    """damping: exact on a massless two-element cantilever (L = 4 m, tip mass m = 100 kg,
    gravity off; the middle node and the rotations massless): two modes, bending
    w_b^2 = 3 EI / (L^3 m) (cubic elements: exact for a tip load) and axial
    w_a^2 = EA / (L m). Each element takes the mode that stores the larger share of its
    strain energy (mass-normalised modes store w^2 in all, so the shares are the
    fractions per element): bending, M = F (L - x), gives the root half
    int_0^2 (4 - x)^2 / int_0^4 (4 - x)^2 = 7/8, the tip half 1/8; axial (uniform strain)
    1/2 each. So the root element is a dashpot at w_b, the tip element at w_a:
    C = psi / (2 pi) (K_root / w_b + K_tip / w_a), with the elements' stiffness matrices
    (the assembly's, tested on their own) placed by the coordinate map."""
    p = make(tmp_path, "  duration: 0.1\n", "{structure: flexible, damping: exact}",
             CANTILEVER)
    EI, EA, L, m = 2.1e11 * 1.0e-6, 2.1e11 * 1.0e-3, 4.0, 100.0
    wb, wa = math.sqrt(3 * EI / (L**3 * m)), math.sqrt(EA / (L * m))
    b, T = p.system.beams, p.system.dofs.T
    Ke = []
    for e in range(len(b.mat)):
        Te = T[b.idx[e]].toarray()
        Ke.append(Te.T @ b.mat[e] @ Te)
    assert len(Ke) == 2
    # the root element is the one with a grounded end: its matrix touches fewer
    # coordinates (6 of the node pair are fixed at O)
    root = int(np.argmin([np.count_nonzero(np.abs(k).sum(axis=0)) for k in Ke]))
    C = p.eq.C.toarray() if sp.issparse(p.eq.C) else np.asarray(p.eq.C)
    hand = 0.3 / (2 * math.pi) * (Ke[root] / wb + Ke[1 - root] / wa)
    close(C, hand, 1e-9)
