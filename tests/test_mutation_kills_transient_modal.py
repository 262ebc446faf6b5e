"""Kill tests for cranefe/analysis/transient/modal.py (tools/mutation.py transient_modal;
docs/testing.md, "Mutation testing"): modal superposition with the static correction,
written out independently of the code on a chain hung from a drum.

The model (sway off, physical coordinates q = (u_A, u_B, theta), u up, theta hauling in):
a drum (J, R) hauls the upper rope over a head sheave down to a mass A, a lower rope hangs
a mass B from A. With the stretches e1 = R theta - u_A, e2 = u_A - u_B (rope forces
S_i = S0_i + c_i e_i, c_i = EA_i / L_i):

    M = diag(m_A, m_B, J),  K = c1 a1 a1^T + c2 a2 a2^T,  a1 = (-1, 0, R), a2 = (1, -1, 0).

With the drum free there is one rigid motion (everything lifted with the drum,
u_A = u_B = R theta) and two elastic modes; with the drum held or prescribed the free
coordinates (u_A, u_B) have two elastic modes. The modes come from scipy's eigh of these
hand matrices (mass-normalised), not from cranefe. Keeping mode 1 only:

    q = Phi_r z + Phi_1 eta_1 + X F,  z'' = Phi_r^T F,
    eta_1'' + 2 zeta_1 w_1 eta_1' + w_1^2 eta_1 = Phi_1^T F,
    X = sum_left-out Phi_i Phi_i^T / w_i^2 = Phi_2 Phi_2^T / w_2^2   (static correction),

and X = 0 without the correction. The code integrates the principal coordinates with
the trapezoidal rule (Newmark's average acceleration), so the reference integrates the
same modal equations with the trapezoidal rule in first-order form, the Cayley map
z_{n+1} = (I - hA/2)^-1 ((I + hA/2) z_n + h/2 (f_n + f_{n+1})), written independently;
the step is coarse (w_2 h ~ 1) so that only this discrete solution matches to round-off
and a wrong frequency, load or correction shows at once. Tolerances 1e-9 relative to each
history's largest value: round-off of ~200 steps of 2 x 2 solves.
"""

import numpy as np
import pytest
import scipy.linalg as sla

from cranefe.analysis.transient.integrate import simulate
from cranefe.model import load

G = 9.81
MA, MB, J, R = 3000.0, 1000.0, 40.0, 0.3
EA1, EA2 = 2.0e7, 6.0e6
C1, C2 = EA1 / (30 + 20), EA2 / 6.0       # upper rope D-S-A: 30 + 20 m; lower A-B: 6 m
A1 = np.array([-1.0, 0.0, R])
A2 = np.array([1.0, -1.0, 0.0])
S0 = np.array([(MA + MB) * G, MB * G])    # hanging at rest


def model_text(psi1=0.0, psi2=0.0, drum=""):
    return f"""cranefe: 1
name: chain on a drum
plane: xz
nodes: {{D: [0, 0, 0], S: [0, 0, 30], A: [0, 0, 10], B: [0, 0, 4]}}
ground: [D, S]
masses: {{A: {MA}, B: {MB}}}
drums:
  hoist: {{node: D, radius: {R}, inertia: {J}{drum}}}
ropes:
  upper: {{EA: {EA1}, psi: {psi1}, path: [hoist, S, A]}}
  lower: {{EA: {EA2}, psi: {psi2}, path: [A, B]}}
effects: {{sway: false}}
"""


def run(tmp_path, analysis, effects="{sway: false}", psi=(0.0, 0.0), name="s", drum=""):
    model = tmp_path / f"{name}_model.yaml"
    model.write_text(model_text(*psi, drum=drum))
    path = tmp_path / f"{name}.yaml"
    path.write_text(f"cranefe: 1\nscene: t\nmodel: {model}\neffects: {effects}\n"
                    f"analysis:\n  type: transient\n{analysis}")
    return simulate(load(path))


def hand_matrices(J=J):
    K = C1 * np.outer(A1, A1) + C2 * np.outer(A2, A2)
    M = np.diag([MA, MB, J])
    return K, M


def trapezoidal(Mm, Cm, Km, force, h, n):
    """Positions and velocities of M x'' + C x' + K x = force(t) from rest, by the
    trapezoidal rule in first-order form (the Cayley map); force(t) -> (k,) array."""
    k = len(Km)
    Mi = np.linalg.inv(Mm)
    A = np.block([[np.zeros((k, k)), np.eye(k)], [-Mi @ Km, -Mi @ Cm]])
    L_, R_ = np.eye(2 * k) - h / 2 * A, np.eye(2 * k) + h / 2 * A
    g = lambda t: np.r_[np.zeros(k), Mi @ force(t)]              # noqa: E731
    z, out = np.zeros(2 * k), [np.zeros(2 * k)]
    for i in range(n):
        z = np.linalg.solve(L_, R_ @ z + h / 2 * (g(i * h) + g((i + 1) * h)))
        out.append(z)
    out = np.array(out)
    return out[:, :k], out[:, k:]


def free_drum_modes(J=J):
    """Rigid shape (by hand) and the two elastic modes (eigh), mass-normalised."""
    K, M = hand_matrices(J)
    r = np.array([R, R, 1.0])
    r /= np.sqrt(r @ M @ r)
    w2, V = sla.eigh(K, M)
    assert abs(w2[0]) < 1e-6 * w2[1]                  # the rigid motion
    return r, np.sqrt(w2[1:]), V[:, 1:] * np.sign(V[2, 1:])


def close(a, b, rel=1e-9):
    np.testing.assert_allclose(a, b, rtol=0, atol=rel * max(np.abs(b).max(), 1e-300))


@pytest.mark.parametrize("correction", [True, False])
def test_free_drum_step_torque_one_mode_with_and_without_static_correction(tmp_path,
                                                                         correction):
    """Step torque dM at the free drum; one of two elastic modes kept. The rigid motion
    z = Phi_r^T F t^2 / 2 (constant acceleration: the trapezoidal rule is exact), mode 1
    by the Cayley map, and the static deflection of the left-out mode 2 (or none)."""
    torque, h, n = 1.5 * R * S0[0], 2e-3, 150
    r_, w, V = free_drum_modes()
    F = np.array([0.0, 0.0, torque - R * S0[0]])      # the brake's holding torque released
    res = run(tmp_path, f"  duration: {h * n}\n  time_step: {h}\n  method: modal\n"
                        f"  modes: 1\n  static_correction: {str(correction).lower()}\n"
                        f"  drums:\n    hoist: {{torque: {torque}}}\n")
    assert res.modes == 1 and res.labels == ("node A z", "node B z", "drum hoist")
    assert res.warnings == []                   # one mode asked, one kept: no warning
    t = h * np.arange(n + 1)
    z, zv = (r_ @ F) * t**2 / 2, (r_ @ F) * t
    eta, etav = trapezoidal(np.eye(1), np.zeros((1, 1)), np.diag([w[0] ** 2]),
                            lambda s: np.array([V[:, 0] @ F]), h, n)
    X = np.outer(V[:, 1], V[:, 1]) / w[1] ** 2 if correction else np.zeros((3, 3))
    q = np.outer(z, r_) + np.outer(eta[:, 0], V[:, 0]) + X @ F
    v = np.outer(zv, r_) + np.outer(etav[:, 0], V[:, 0])
    close(res.q, q)
    close(res.v, v)
    close(res.drum_speed[:, 0], v[:, 2])
    forces = S0 + np.c_[C1 * q @ A1, C2 * q @ A2]
    close(res.rope_force, forces)
    # the correction matters here: the left-out mode's static deflection in the lower rope
    assert C2 * abs(A2 @ np.outer(V[:, 1], V[:, 1]) @ F) / w[1] ** 2 > 1e-3 * S0[1]


def rope_dampers(psi, w_sub, V_sub, free):
    """b_e = psi_e c_e / (2 pi w_e) (Heletiy 2016 eq. 12) with w_e the frequency of the
    mode of the sub-system (columns of V_sub on the coordinates `free`) that stores the
    largest share c_e (a_e v_j)^2 / w_j^2 of its strain energy (docs/transient.md)."""
    Cf = np.zeros((3, 3))
    for p, c, a in zip(psi, (C1, C2), (A1, A2)):
        share = c * (a[free] @ V_sub) ** 2 / w_sub**2
        Cf += p * c / (2 * np.pi * w_sub[np.argmax(share)]) * np.outer(a, a)
    return Cf


@pytest.mark.parametrize("kind", ["modal", "exact"])
def test_damped_free_drum_one_mode_with_static_correction(tmp_path, kind):
    """Both ropes absorb (psi 0.3 and 0.5). modal: eta_1 gets the decoupled ratio
    zeta_1 = sum_e psi_e c_e (a_e Phi_1)^2 / (4 pi w_1^2) (b_e = psi_e c_e / (2 pi w_1)),
    the rigid motion none; exact: the principal coordinates get Phi^T C Phi of the
    viscous matrix C = sum b_e a_e a_e^T, each rope at the frequency of the free-drum mode
    that most strains it; the rigid motion stretches no rope, so it stays undamped."""
    psi = (0.3, 0.5)
    torque, h, n = 1.5 * R * S0[0], 2e-3, 150
    r_, w, V = free_drum_modes()
    F = np.array([0.0, 0.0, torque - R * S0[0]])
    res = run(tmp_path, f"  duration: {h * n}\n  time_step: {h}\n  method: modal\n"
                        f"  modes: 1\n  drums:\n    hoist: {{torque: {torque}}}\n",
              effects=f"{{sway: false, damping: {kind}}}", psi=psi)
    if kind == "modal":
        zeta = sum(p * c * (a @ V[:, 0]) ** 2 for p, c, a in zip(psi, (C1, C2), (A1, A2))) \
            / (4 * np.pi * w[0] ** 2)
        c11 = 2 * zeta * w[0]
    else:
        c11 = V[:, 0] @ rope_dampers(psi, w, V, slice(None)) @ V[:, 0]
        assert abs(r_ @ rope_dampers(psi, w, V, slice(None)) @ r_) < 1e-12 * c11
    t = h * np.arange(n + 1)
    eta, etav = trapezoidal(np.eye(1), np.diag([c11]), np.diag([w[0] ** 2]),
                            lambda s: np.array([V[:, 0] @ F]), h, n)
    X = np.outer(V[:, 1], V[:, 1]) / w[1] ** 2
    q = np.outer((r_ @ F) * t**2 / 2, r_) + np.outer(eta[:, 0], V[:, 0]) + X @ F
    close(res.q, q)
    close(res.v, np.outer((r_ @ F) * t, r_) + np.outer(etav[:, 0], V[:, 0]))
    # the damping is felt: the undamped eta_1 differs by far more than the tolerance
    und, _ = trapezoidal(np.eye(1), np.zeros((1, 1)), np.diag([w[0] ** 2]),
                         lambda s: np.array([V[:, 0] @ F]), h, n)
    assert np.abs(und - eta).max() > 1e-2 * np.abs(eta).max()


def held_drum_modes():
    """The sub-system of a prescribed drum: (u_A, u_B), drum held."""
    K, M = hand_matrices()
    w2, V = sla.eigh(K[:2, :2], M[:2, :2])
    return np.sqrt(w2), V * np.sign(V[0])


@pytest.mark.parametrize("correction", [True, False])
def test_prescribed_drum_ramp_with_exact_damping_one_mode(tmp_path, correction):
    """The drum's speed ramps to wd over tr: theta(t) known. The free coordinates (u_A,
    u_B) see f(t) = -K_fp theta - C_fp theta' (M is diagonal: no inertial coupling),
    i.e. (c1 R theta + b1 R theta', 0) with the upper rope's damper b1; mode 1 of the
    held-drum sub-system kept, damped by Phi_1^T C_ff Phi_1, and the left-out mode's
    static deflection X f(t) (its velocity X f'(t)) with the correction."""
    wd, tr, h, n = 2.0, 0.1, 2e-3, 150
    psi = (0.3, 0.5)
    w, V = held_drum_modes()
    Cf = rope_dampers(psi, w, V, slice(0, 2))
    b1 = Cf[2, 2] / R**2                                    # C_dd = b1 R^2

    def theta(t):
        return np.where(t < tr, wd * t**2 / (2 * tr), wd * (t - tr / 2))

    def speed(t):
        return np.where(t < tr, wd * t / tr, wd)

    def accel(t):                                          # right limit at tr
        return np.where(t < tr, wd / tr, 0.0)

    def f(t):
        return np.array([C1 * R * theta(t) + b1 * R * speed(t), 0.0])

    res = run(tmp_path, f"  duration: {h * n}\n  time_step: {h}\n  method: modal\n"
                        f"  modes: 1\n  static_correction: {str(correction).lower()}\n"
                        f"  drums:\n    hoist: {{speed: {wd}, ramp: {tr}}}\n",
              effects="{sway: false, damping: exact}", psi=psi)
    t = h * np.arange(n + 1)
    p = V[:, 0]
    eta, etav = trapezoidal(np.eye(1), np.diag([p @ Cf[:2, :2] @ p]), np.diag([w[0] ** 2]),
                            lambda s: np.array([p @ f(s)]), h, n)
    X = np.outer(V[:, 1], V[:, 1]) / w[1] ** 2 if correction else np.zeros((2, 2))
    fs = np.array([f(s) for s in t])
    dfs = np.c_[C1 * R * speed(t) + b1 * R * accel(t), 0 * t]
    q = np.outer(eta[:, 0], p) + fs @ X
    v = np.outer(etav[:, 0], p) + dfs @ X
    close(res.q[:, :2], q)
    close(res.v[:, :2], v)
    close(res.q[:, 2], theta(t))
    close(res.drum_speed[:, 0], speed(t))
    close(res.rope_force, S0 + np.c_[C1 * (R * theta(t) - q[:, 0]), C2 * (q[:, 0] - q[:, 1])])
    warned = any("static_correction: false with a prescribed drum" in m for m in res.warnings)
    assert warned == (not correction)


def test_linear_motor_one_mode_with_static_correction(tmp_path):
    """A linear motor drives the free drum through a gear i = 3 (rotor 0.5 kg m^2: the
    drum's inertia J + 0.5 i^2): torque at the drum i Ms (1 - i w / ns) at the drum
    speed w of the retained modes, so the modal equations are linear, with the viscous
    term i^2 Ms / ns p p^T (p the drum's row of (Phi_r, Phi_1)); the static correction
    adds X e_drum (i Ms (1 - i w / ns) - R S0)."""
    Ms, ns, gear, h, n = 8000.0, 60.0, 3.0, 2e-3, 150
    Jd = J + 0.5 * gear**2
    r_, w, V = free_drum_modes(Jd)
    P = np.c_[r_, V[:, 0]]
    p = P[2]
    res = run(tmp_path, f"  duration: {h * n}\n  time_step: {h}\n  method: modal\n"
                        f"  modes: 1\n  drums:\n    hoist: {{motor: {{stall_torque: {Ms}, "
                        f"synchronous_speed: {ns}}}}}\n",
              drum=f", motor: {{rotor_inertia: 0.5, gear_ratio: {gear}}}")
    x, xv = trapezoidal(np.eye(2), gear**2 * Ms / ns * np.outer(p, p),
                        np.diag([0.0, w[0] ** 2]), lambda s: p * (gear * Ms - R * S0[0]),
                        h, n)
    X = np.outer(V[:, 1], V[:, 1]) / w[1] ** 2
    torque = gear * Ms * (1 - gear * (xv @ p) / ns) - R * S0[0]
    q = x @ P.T + np.outer(torque, X[:, 2])
    close(res.q, q)
    close(res.v, xv @ P.T)
    close(res.drum_torque[:, 0], gear * Ms * (1 - gear * res.drum_speed[:, 0] / ns))
    assert gear * xv[-1] @ p > 0.2 * ns                # the motor is well under way


def test_more_modes_asked_than_the_model_has(tmp_path):
    """modes: 5 on two elastic modes: all used, with the warning; with every mode kept
    the static correction is zero and the run is the full trapezoidal solution."""
    torque, h, n = 1.5 * R * S0[0], 2e-3, 100
    K, M = hand_matrices()
    F = np.array([0.0, 0.0, torque - R * S0[0]])
    res = run(tmp_path, f"  duration: {h * n}\n  time_step: {h}\n  method: modal\n"
                        f"  modes: 5\n  drums:\n    hoist: {{torque: {torque}}}\n")
    assert res.modes == 2
    assert any("modes: 5 asked, the model has 2 elastic modes; all are used" in m
               for m in res.warnings)
    q, v = trapezoidal(M, np.zeros((3, 3)), K, lambda s: F, h, n)
    close(res.q, q)
    w = free_drum_modes()[1]
    assert res.highest_frequency_hz == pytest.approx(w[1] / (2 * np.pi), rel=1e-9)


def test_sparse_eigen_path_on_a_small_model(tmp_path, monkeypatch):
    """Above DENSE_MAX coordinates the modes come from Lanczos, asking for k + 8 (at
    most n - 1) and more while too many are rigid; lowered to 1 here, the 3-coordinate
    model goes that way and must give the same one-mode solution as the dense path."""
    import cranefe.analysis.transient.modal as tm
    monkeypatch.setattr(tm, "DENSE_MAX", 1)
    torque, h, n = 1.5 * R * S0[0], 2e-3, 100
    r_, w, V = free_drum_modes()
    F = np.array([0.0, 0.0, torque - R * S0[0]])
    res = run(tmp_path, f"  duration: {h * n}\n  time_step: {h}\n  method: modal\n"
                        f"  modes: 1\n  drums:\n    hoist: {{torque: {torque}}}\n")
    t = h * np.arange(n + 1)
    eta, _ = trapezoidal(np.eye(1), np.zeros((1, 1)), np.diag([w[0] ** 2]),
                         lambda s: np.array([V[:, 0] @ F]), h, n)
    q = np.outer((r_ @ F) * t**2 / 2, r_) + np.outer(eta[:, 0], V[:, 0]) \
        + np.outer(V[:, 1], V[:, 1]) @ F / w[1] ** 2
    # Lanczos's tolerance (eigsh to machine precision on a 3 x 3 pencil): 1e-7
    close(res.q, q, rel=1e-7)


MASSLESS = f"""cranefe: 1
name: chain with a massless node
plane: xz
nodes: {{D: [0, 0, 0], S: [0, 0, 30], A: [0, 0, 10], B: [0, 0, 4], C: [0, 0, 1]}}
ground: [D, S]
masses: {{B: {MA}, C: {MB}}}
drums:
  hoist: {{node: D, radius: {R}, inertia: {J}}}
ropes:
  upper: {{EA: {EA1}, path: [hoist, S, A]}}
  middle: {{EA: {EA2}, path: [A, B]}}
  lower: {{EA: 3.0e6, path: [B, C]}}
effects: {{sway: false}}
"""


@pytest.mark.parametrize("correction", [True, False])
def test_massless_node_gets_its_direct_static_response(tmp_path, correction):
    """A massless node A between the upper and middle ropes, a step force F_A on it and
    a step torque at the free drum; q = (u_A, u_B, u_C, theta). The modes are those of the
    statically condensed pencil (Kc = K_rr - K_rA K_AA^-1 K_Ar, M_rr) with u_A recovered
    as -K_AA^-1 K_Ar phi; mode 1 kept. The flexibility of the elastic part is
    sum_elastic Phi_i Phi_i^T / w_i^2 + e_A e_A^T / K_AA, so the correction is
    Phi_2 Phi_2^T / w_2^2 + e_A e_A^T / K_AA, and without it only e_A e_A^T / K_AA
    (the massless coordinate's direct static response, which no mode carries)."""
    c = np.array([EA1 / 50, EA2 / 6, 3.0e6 / 3])
    a = np.array([[-1, 0, 0, R], [1, -1, 0, 0], [0, 1, -1, 0]], dtype=float)
    K = (a.T * c) @ a
    M = np.diag([0.0, MA, MB, J])
    Kc = K[1:, 1:] - np.outer(K[1:, 0], K[0, 1:]) / K[0, 0]
    w2, Vr = sla.eigh(Kc, M[1:, 1:])
    assert abs(w2[0]) < 1e-6 * w2[1]
    V = np.vstack([-K[0, 1:] @ Vr / K[0, 0], Vr])           # u_A recovered
    r_, w, V = V[:, 0], np.sqrt(w2[1:]), V[:, 1:]
    torque, FA, h, n = 1.5 * R * (MA + MB) * G, 8000.0, 2e-3, 150
    F = np.array([-FA, 0.0, 0.0, torque - R * (MA + MB) * G])
    model = tmp_path / "massless.yaml"
    model.write_text(MASSLESS)
    path = tmp_path / "s.yaml"
    path.write_text(f"cranefe: 1\nscene: t\nmodel: {model}\neffects: {{sway: false}}\n"
                    f"analysis:\n  type: transient\n  duration: {h * n}\n  time_step: {h}\n"
                    f"  method: modal\n  modes: 1\n"
                    f"  static_correction: {str(correction).lower()}\n"
                    f"  drums:\n    hoist: {{torque: {torque}}}\n"
                    f"  forces:\n    A: {{force: [0, 0, {-FA}]}}\n")
    res = simulate(load(path))
    assert res.labels == ("node A z", "node B z", "node C z", "drum hoist")
    t = h * np.arange(n + 1)
    eta, etav = trapezoidal(np.eye(1), np.zeros((1, 1)), np.diag([w[0] ** 2]),
                            lambda s: np.array([V[:, 0] @ F]), h, n)
    eA = np.eye(4)[0]
    X = np.outer(eA, eA) / K[0, 0]
    if correction:
        X += np.outer(V[:, 1], V[:, 1]) / w[1] ** 2
    q = np.outer((r_ @ F) * t**2 / 2, r_) + np.outer(eta[:, 0], V[:, 0]) + X @ F
    close(res.q, q)
    close(res.v, np.outer((r_ @ F) * t, r_) + np.outer(etav[:, 0], V[:, 0]))


def test_prescribed_drum_with_rope_mass_couples_through_the_mass(tmp_path):
    """The upper rope with mass (2 elements per fall): the rope's mass couples the
    prescribed drum with the free coordinates, so they see f(t) = -K_fp theta -
    M_fp theta'' as well (theta'' jumps at t = 0 and at the ramp's end: the step ending
    there takes its left limit, the next one starts from the right one, and a stored
    state at the jump the right one). Here K and M are the assembled matrices (the
    assembly has its own kill tests; they are this test's input); the reference is
    the exact trapezoidal solution of the two retained modes of eigh(K_ff, M_ff) plus
    the static correction of each load shape by the three left-out modes."""
    from cranefe.system import assemble
    text = model_text().replace("upper: {EA:", "upper: {mass_per_length: 3.0, EA:")
    effects = "{sway: false, rope_mass: 2}"
    wd, tr, h, n = 2.0, 0.1, 2e-3, 100
    model = tmp_path / "rm_model.yaml"
    model.write_text(text.replace("effects: {sway: false}", f"effects: {effects}"))
    s = assemble(load(model))
    d = s.dofs.labels.index("drum hoist")
    free = [i for i in range(s.dofs.n) if i != d]
    K, M = s.K.toarray(), s.M.toarray()
    Kff, Mff, Kfp, Mfp = K[np.ix_(free, free)], M[np.ix_(free, free)], K[free, d], M[free, d]
    assert np.abs(Mfp).max() > 0 and np.linalg.eigvalsh(Mff).min() > 0
    w2, V = sla.eigh(Kff, Mff)
    keep, out = V[:, :2], V[:, 2:]
    X = out @ np.diag(1 / w2[2:]) @ out.T

    def theta(t):
        return np.where(t < tr, wd * t**2 / (2 * tr), wd * (t - tr / 2))

    def accel(t, left=False):
        return np.where((t < tr) | (left & (t <= tr)), wd / tr, 0.0) * (t > 0 or not left)

    # trapezoidal rule on the two modes: force at a step's start (right limit) and end
    # (left limit)
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-np.diag(w2[:2]), np.zeros((2, 2))]])
    L_, R_ = np.eye(4) - h / 2 * A, np.eye(4) + h / 2 * A

    def g(t, left):
        return np.r_[0, 0, keep.T @ (-Kfp * theta(t) - Mfp * accel(t, left))]

    z, zs = np.zeros(4), [np.zeros(4)]
    for i in range(n):
        z = np.linalg.solve(L_, R_ @ z + h / 2 * (g(i * h, False) + g((i + 1) * h, True)))
        zs.append(z)
    zs = np.array(zs)
    t = h * np.arange(n + 1)
    q = zs[:, :2] @ keep.T + np.outer(theta(t), X @ -Kfp) + \
        np.outer([accel(s_) for s_ in t], X @ -Mfp)
    path = tmp_path / "rm.yaml"
    path.write_text(f"cranefe: 1\nscene: t\nmodel: {model}\neffects: {effects}\n"
                    f"analysis:\n  type: transient\n  duration: {h * n}\n  time_step: {h}\n"
                    f"  method: modal\n  modes: 2\n"
                    f"  drums:\n    hoist: {{speed: {wd}, ramp: {tr}}}\n")
    res = simulate(load(path))
    close(res.q[:, free], q)
    close(res.v[:, free], zs[:, 2:] @ keep.T +
          np.outer(np.where(t < tr, wd * t / tr, wd), X @ -Kfp))
    # the inertial coupling matters: without it q differs by far more than 1e-9
    assert np.abs(np.outer([accel(s_) for s_ in t], X @ Mfp)).max() > 1e-6 * np.abs(q).max()


TWO_DRUMS = f"""cranefe: 1
name: a chain on a drum and a mass on a second drum
plane: xz
nodes: {{D: [0, 0, 0], S: [0, 0, 30], A: [0, 0, 10], B: [0, 0, 4], E: [5, 0, 0],
        T: [5, 0, 30], C: [5, 0, 20]}}
ground: [D, S, E, T]
masses: {{A: {MA}, B: {MB}, C: 2000}}
drums:
  aux: {{node: E, radius: 0.2, inertia: 10, brake: false}}
  hoist: {{node: D, radius: {R}, inertia: {J}, brake: false}}
ropes:
  upper: {{EA: {EA1}, path: [hoist, S, A]}}
  lower: {{EA: {EA2}, path: [A, B]}}
  third: {{EA: 4.0e6, path: [aux, T, C]}}
effects: {{sway: false}}
"""


def test_held_prescribed_drum_and_a_constant_speed(tmp_path):
    """Two prescribed drums: `aux` at speed 0 (held: it loads nothing) listed first,
    `hoist` at 1 rad/s from t = 0 (a constant profile), theta = t. The free coordinates
    (u_A, u_B, u_C) see (c1 R t, 0, 0); all three modes kept: the full trapezoidal
    solution of the held-drum system, by the Cayley map."""
    c3 = 4.0e6 / 20
    K = np.zeros((3, 3))
    K[:2, :2] = hand_matrices()[0][:2, :2]
    K[2, 2] = c3
    M = np.diag([MA, MB, 2000.0])
    h, n = 2e-3, 100
    model = tmp_path / "two.yaml"
    model.write_text(TWO_DRUMS)
    path = tmp_path / "s.yaml"
    path.write_text(f"cranefe: 1\nscene: t\nmodel: {model}\neffects: {{sway: false}}\n"
                    f"analysis:\n  type: transient\n  duration: {h * n}\n  time_step: {h}\n"
                    f"  method: modal\n  modes: 3\n"
                    f"  drums:\n    aux: {{speed: 0}}\n    hoist: {{speed: 1.0}}\n")
    res = simulate(load(path))
    lab = res.labels
    free = [lab.index(x) for x in ("node A z", "node B z", "node C z")]
    q, v = trapezoidal(M, np.zeros((3, 3)), K, lambda s: np.array([C1 * R * s, 0, 0]), h, n)
    close(res.q[:, free], q)
    close(res.q[:, lab.index("drum hoist")], h * np.arange(n + 1))
    assert np.abs(res.q[:, lab.index("drum aux")]).max() == 0
    assert np.abs(q[:, 0]).max() > 1e-3


def test_sparse_path_with_a_prescribed_drum_and_too_many_modes(tmp_path, monkeypatch):
    """On the Lanczos path the modes are those of the sub-system (drum held), not of the
    whole model; asking more modes than it has stops at n - 1 Lanczos pairs (eigsh's
    limit: here the rigid motion and mode 1 of the 3-coordinate free-drum model) with
    the warning, instead of looping for ever."""
    import cranefe.analysis.transient.modal as tm
    monkeypatch.setattr(tm, "DENSE_MAX", 1)
    wd, tr, h, n = 2.0, 0.1, 2e-3, 100
    w, V = held_drum_modes()
    res = run(tmp_path, f"  duration: {h * n}\n  time_step: {h}\n  method: modal\n"
                        f"  modes: 1\n  drums:\n    hoist: {{speed: {wd}, ramp: {tr}}}\n")
    assert res.highest_frequency_hz == pytest.approx(w[0] / (2 * np.pi), rel=1e-7)
    t = h * np.arange(n + 1)
    theta = np.where(t < tr, wd * t**2 / (2 * tr), wd * (t - tr / 2))
    p = V[:, 0]
    eta, _ = trapezoidal(np.eye(1), np.zeros((1, 1)), np.diag([w[0] ** 2]),
                         lambda s: np.array([p[0] * C1 * R * np.where(
                             s < tr, wd * s**2 / (2 * tr), wd * (s - tr / 2))]), h, n)
    X = np.outer(V[:, 1], V[:, 1]) / w[1] ** 2
    q = np.outer(eta[:, 0], p) + np.outer(C1 * R * theta, X[:, 0])
    close(res.q[:, :2], q, rel=1e-7)                   # Lanczos's tolerance
    res = run(tmp_path, f"  duration: {h * 10}\n  time_step: {h}\n  method: modal\n"
                        f"  modes: 5\n  drums:\n    hoist: {{torque: 20000}}\n", name="m5")
    assert res.modes == 1
    assert any("modes: 5 asked" in m for m in res.warnings)


def test_automatic_step_of_a_slow_model(tmp_path):
    """No time_step: a twentieth of the shortest retained period, pi / (10 w_1), for a
    soft rope whose only retained mode is below 1 rad/s (w_1 = 0.68 rad/s here, by
    eigh of the held-drum matrices with EA 100 times smaller)."""
    text = model_text().replace(f"EA: {EA1}", f"EA: {EA1 / 100}").replace(
        f"EA: {EA2}", f"EA: {EA2 / 100}")
    model = tmp_path / "soft.yaml"
    model.write_text(text)
    K = (C1 * np.outer(A1, A1) + C2 * np.outer(A2, A2))[:2, :2] / 100
    w1 = np.sqrt(sla.eigh(K, np.diag([MA, MB]), eigvals_only=True)[0])
    assert w1 < 1.0
    h = np.pi / (10 * w1)
    path = tmp_path / "s.yaml"
    path.write_text(f"cranefe: 1\nscene: t\nmodel: {model}\neffects: {{sway: false}}\n"
                    f"analysis:\n  type: transient\n  duration: {100 * h}\n"
                    f"  method: modal\n  modes: 1\n"
                    f"  drums:\n    hoist: {{speed: 0.1, ramp: {10 * h}}}\n")
    res = simulate(load(path))
    assert res.time_step == pytest.approx(h, rel=1e-9)
    assert res.highest_frequency_hz == pytest.approx(w1 / (2 * np.pi), rel=1e-9)
