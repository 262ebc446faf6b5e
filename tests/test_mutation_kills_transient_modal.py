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


def model_text(psi1=0.0, psi2=0.0):
    return f"""cranefe: 1
name: chain on a drum
plane: xz
nodes: {{D: [0, 0, 0], S: [0, 0, 30], A: [0, 0, 10], B: [0, 0, 4]}}
ground: [D, S]
masses: {{A: {MA}, B: {MB}}}
drums:
  hoist: {{node: D, radius: {R}, inertia: {J}}}
ropes:
  upper: {{EA: {EA1}, psi: {psi1}, path: [hoist, S, A]}}
  lower: {{EA: {EA2}, psi: {psi2}, path: [A, B]}}
effects: {{sway: false}}
"""


def run(tmp_path, analysis, effects="{sway: false}", psi=(0.0, 0.0), name="s"):
    model = tmp_path / f"{name}_model.yaml"
    model.write_text(model_text(*psi))
    path = tmp_path / f"{name}.yaml"
    path.write_text(f"cranefe: 1\nscene: t\nmodel: {model}\neffects: {effects}\n"
                    f"analysis:\n  type: transient\n{analysis}")
    return simulate(load(path))


def hand_matrices():
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


def free_drum_modes():
    """Rigid shape (by hand) and the two elastic modes (eigh), mass-normalised."""
    K, M = hand_matrices()
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
    """A linear motor (gear 1) drives the free drum: torque Ms (1 - w / ns) at the drum
    speed w of the retained modes, so the modal equations are linear, with the viscous
    term Ms / ns p p^T (p the drum's row of (Phi_r, Phi_1)); the static correction adds
    X e_drum (Ms (1 - w / ns) - R S0)."""
    Ms, ns, h, n = 20000.0, 20.0, 2e-3, 150
    r_, w, V = free_drum_modes()
    P = np.c_[r_, V[:, 0]]
    p = P[2]
    res = run(tmp_path, f"  duration: {h * n}\n  time_step: {h}\n  method: modal\n"
                        f"  modes: 1\n  drums:\n    hoist: {{motor: {{stall_torque: {Ms}, "
                        f"synchronous_speed: {ns}}}}}\n")
    x, xv = trapezoidal(np.eye(2), Ms / ns * np.outer(p, p), np.diag([0.0, w[0] ** 2]),
                        lambda s: p * (Ms - R * S0[0]), h, n)
    X = np.outer(V[:, 1], V[:, 1]) / w[1] ** 2
    torque = Ms * (1 - xv @ p / ns) - R * S0[0]
    q = x @ P.T + np.outer(torque, X[:, 2])
    close(res.q, q)
    close(res.v, xv @ P.T)
    close(res.drum_torque[:, 0], Ms * (1 - res.drum_speed[:, 0] / ns))
    assert xv[-1] @ p > 0.2 * ns                      # the motor is well under way


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
