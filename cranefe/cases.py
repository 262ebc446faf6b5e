"""Validation cases with exact answers, shared by the tests and the studies.

Each function returns ``(yaml_text, exact)`` where exact holds the reference
frequencies (rad/s) and whatever else the case checks; the sources are in each
docstring. Load the text with ``cranefe.model.load(path, text)``.
"""

import numpy as np
import scipy.optimize as so
import scipy.special as ss

G = 9.81


def heavy_rope_end_mass(L=100.0, mu=5.0, M=2000.0, EA=1.0e7, modes=4):
    """Vertical heavy rope fixed at the top with an end mass, longitudinal modes.

    u_tt = (EA/mu) u_ss, u(0) = 0, EA u_s(L) = -M u_tt(L) gives
    beta tan beta = mu L / M, w = beta sqrt(EA/mu) / L.
    """
    a = mu * L / M
    beta = [so.brentq(lambda b: b * np.tan(b) - a, k * np.pi + 1e-12,
                      k * np.pi + np.pi / 2 - 1e-12, xtol=1e-15) for k in range(modes)]
    text = f"""cranefe: 1
name: heavy rope with end mass
plane: xz
nodes: {{S: [0, 0, {L}], B: [0, 0, 0]}}
ground: [S]
masses: {{B: {M}}}
ropes:
  r: {{EA: {EA}, mass_per_length: {mu}, path: [S, B]}}
effects: {{sway: false}}
"""
    return text, {"omega": np.array(beta) * np.sqrt(EA / mu) / L}


def hanging_chain(L=20.0, mu=2.0, EA=1.0e9, modes=4):
    """Rope fixed at the top, free lower end: lateral w_n = (j0_n / 2) sqrt(g / L),
    j0_n the zeros of J0 (tension mu g s at height s above the free end). EA is large so
    the lowest modes are the lateral ones."""
    text = f"""cranefe: 1
name: hanging chain
plane: xz
nodes: {{S: [0, 0, {L}], B: [0, 0, 0]}}
ground: [S]
ropes:
  r: {{EA: {EA}, mass_per_length: {mu}, path: [S, B]}}
"""
    return text, {"omega": ss.jn_zeros(0, modes) / 2 * np.sqrt(G / L)}


def tensioned_span(l=40.0, h=8.0, mu=3.0, W=3000.0, EA=1.0e9, modes=4):
    """Horizontal span A-P tensioned by a counterweight W hanging h below the frictionless
    sheave P: string modes w_n = (n pi / l) sqrt(S / mu) with S = (W + mu h) g, the
    counterweight plus the hanging fall. (In the straight reference geometry the span's
    transverse motion does not stretch it, so every n counts, not only the
    antisymmetric ones a sagging cable would have.)"""
    S = (W + mu * h) * G
    text = f"""cranefe: 1
name: span tensioned over a sheave
plane: xz
nodes: {{A: [0, 0, 10], P: [{l}, 0, 10], W: [{l}, 0, {10 - h}]}}
ground: [A, P]
masses: {{W: {W}}}
ropes:
  r: {{EA: {EA}, mass_per_length: {mu}, path: [A, P, W]}}
"""
    return text, {"omega": np.arange(1, modes + 1) * np.pi / l * np.sqrt(S / mu),
                  "tension": S, "pendulum": np.sqrt(G / h)}


ROPE_CASES = {"heavy_rope_end_mass": heavy_rope_end_mass, "hanging_chain": hanging_chain,
              "tensioned_span": tensioned_span}


def matched(omega, exact):
    """The computed frequency nearest each exact one (for cases with other modes too)."""
    omega = np.asarray(omega)
    return np.array([omega[np.argmin(np.abs(omega - w))] for w in exact])


def spring_chain(N, k=1.0e6, m=100.0):
    """Fixed-free chain of N equal masses m joined by N equal springs k (the first to the
    ground), sway off: the discrete system's exact frequencies are
    w_j = 2 sqrt(k/m) sin((2j - 1) pi / (2 (2N + 1)))  (e.g. Weaver, Timoshenko & Young,
    Vibration Problems in Engineering, lumped chains)."""
    nodes = "{G: [0, 0, 0], " + ", ".join(f"N{i}: [{i + 1}, 0, 0]" for i in range(N)) + "}"
    ends = ["G"] + [f"N{i}" for i in range(N)]
    springs = "\n".join(f"  - {{name: k{i}, type: axial, nodes: [{a}, {b}], stiffness: {k}}}"
                        for i, (a, b) in enumerate(zip(ends[:-1], ends[1:])))
    masses = "{" + ", ".join(f"N{i}: {m}" for i in range(N)) + "}"
    text = (f"cranefe: 1\nname: spring chain {N}\nplane: xz\ngravity: [0, 0, 0]\n"
            f"nodes: {nodes}\nground: [G]\nmasses: {masses}\nsprings:\n{springs}\n"
            "effects: {sway: false}\n")
    j = np.arange(1, N + 1)
    return text, {"omega": 2 * np.sqrt(k / m) * np.sin((2 * j - 1) * np.pi / (2 * (2 * N + 1)))}


def two_mass_hoist(falls=2, J=500.0, R=0.25, m=5000.0, EA=2.0e7):
    """Drum (inertia J, radius R) hauling a load m on a tackle of `falls`, sway off.
    Coupled: w^2 = k (n^2/m + R^2/J); drive reduced (Heletiy 2016 eq. 10, drum held):
    w^2 = n^2 k / m; relative error of w^2: m r^2 / (m r^2 + J), r = R / n."""
    text = f"""cranefe: 1
name: two-mass hoist
plane: xz
nodes: {{D: [0, 0, 0], S: [0, 0, 30], B: [0, 0, 10]}}
ground: [D, S]
masses: {{B: {m}}}
drums:
  hoist: {{node: D, radius: {R}, inertia: {J}}}
ropes:
  hoist: {{EA: {EA}, path: [hoist, S, {{node: B, falls: {falls}}}]}}
effects: {{sway: false}}
"""
    k = EA / (30 + 20 * falls)
    r = R / falls
    return text, {"omega": np.array([np.sqrt(k * (falls**2 / m + R**2 / J))]),
                  "omega_reduced": np.array([np.sqrt(falls**2 * k / m)]),
                  "error_w2": m * r**2 / (m * r**2 + J)}


def double_pendulum(m1=1500.0, m2=700.0, l1=10.0, l2=4.0):
    """Two point masses on two ropes in series: the linearised double pendulum,
    m1 l1 l2 w^4 - (m1 + m2) g (l1 + l2) w^2 + (m1 + m2) g^2 = 0 (exact also for elastic
    ropes: hanging vertically, their stretch does not couple with the swing)."""
    text = f"""cranefe: 1
name: double pendulum
plane: xz
nodes: {{S: [0, 0, 20], A: [0, 0, {20 - l1}], B: [0, 0, {20 - l1 - l2}]}}
ground: [S]
masses: {{A: {m1}, B: {m2}}}
ropes:
  upper: {{EA: 5.0e7, path: [S, A]}}
  lower: {{EA: 5.0e7, path: [A, B]}}
"""
    w2 = np.sort(np.roots([m1 * l1 * l2, -(m1 + m2) * G * (l1 + l2), (m1 + m2) * G**2]))
    return text, {"omega": np.sqrt(w2)}


def loaded_column(L=12.0, M=2.0e4, E=2.1e11, A=1.0e-2, I=2.0e-4, elements=16):
    """A massless clamped column with a top mass M under its weight P = M g: P-delta.
    Tip stiffness under compression, exact: k = P / (L (tan kL / kL - 1)), k = sqrt(P/EI)."""
    text = f"""cranefe: 1
name: loaded column
plane: xz
nodes: {{O: [0, 0, 0], T: [0, 0, {L}]}}
ground: [O]
masses: {{T: {M}}}
members:
  col: {{type: beam, nodes: [O, T], E: {E}, A: {A}, Iy: {I}, rho: 0, elements: {elements}}}
effects: {{structure: flexible}}
"""
    P = M * G
    kl = np.sqrt(P / (E * I)) * L
    k = P / (L * (np.tan(kl) / kl - 1))
    return text, {"omega": np.array([np.sqrt(k / M)]),
                  "omega_no_sway": np.array([np.sqrt(3 * E * I / L**3 / M)])}


# ---------------------------------------------------------------- transient cases
# The two-mass hoist of `two_mass_hoist` (drum J, R; load m on n falls; k = EA / L of
# the whole rope), sway off, released from its static state or lifted off the ground.
# q = (theta, z), rope stretch e = R theta - n z, rope force S = S0 + k e.

def _hoist_numbers(falls, J, R, m, EA):
    k = EA / (30 + 20 * falls)
    return k, m * G / falls


def _with_rope_mass(text, mu):
    """The model text with mass_per_length mu on its rope (for effects.rope_mass; the
    closed forms are those of the massless rope)."""
    return text.replace("hoist: {EA:", f"hoist: {{mass_per_length: {mu}, EA:") if mu \
        else text


def hoist_step_torque(ratio=1.6, falls=2, J=500.0, R=0.25, m=5000.0, EA=2.0e7, mu=0.0):
    """Step drum torque M = ratio x the holding torque R S0 from the static state.

    Heletiy (2016) eq. 7-8 with the quasi-cyclic drum angle: J theta'' = dM - R k e,
    m z'' = n k e give e'' + w^2 e = R dM / J, w^2 = k (R^2/J + n^2/m), so from rest
    S(t) = S0 + dS (1 - cos w t), dS = m R dM / (m R^2 + n^2 J) (twice that at the peak),
    and the drum speed theta' = dM t / J - (R dS / J) (t - sin(w t) / w).
    Returns (model yaml, exact) with callables force(t), drum_speed(t); mu > 0 gives the
    rope a mass per length (for rope_mass runs; the closed form is the massless one).
    """
    text, _ = two_mass_hoist(falls, J, R, m, EA)
    text = _with_rope_mass(text, mu)
    k, S0 = _hoist_numbers(falls, J, R, m, EA)
    torque = ratio * R * S0
    dM = torque - R * S0
    w = np.sqrt(k * (R**2 / J + falls**2 / m))
    dS = m * R * dM / (m * R**2 + falls**2 * J)
    return text, {"torque": torque, "S0": S0, "omega": w, "dS": dS,
                  "peak": S0 + 2 * dS, "peak_time": np.pi / w,
                  "force": lambda t: S0 + dS * (1 - np.cos(w * t)),
                  "drum_speed": lambda t: dM * t / J - R * dS / J * (t - np.sin(w * t) / w)}


def hoist_lift_off(drum_speed=2.0, falls=2, J=500.0, R=0.25, m=5000.0, EA=2.0e7):
    """A load resting on the ground lifted by its rope hauled in at a constant drum
    speed from t = 0 (rigid drive). The rope force rises as k R w_d t per fall until
    n S = m g at t_lift = m g / (n k R w_d); the load then starts from rest while the
    rope end moves at the hook speed v = R w_d / n, so the force overshoots by m v w:
    S_max = (m g / n)(1 + v w / g), w^2 = n^2 k / m (EN 13001-2's phi2 of a rigid drive).
    """
    text, _ = two_mass_hoist(falls, J, R, m, EA)
    k, S0 = _hoist_numbers(falls, J, R, m, EA)
    v = R * drum_speed / falls
    w = np.sqrt(falls**2 * k / m)
    return text, {"S0": S0, "omega": w, "hook_speed": v,
                  "lift_off_time": m * G / (falls * k * R * drum_speed),
                  "dynamic_factor": 1 + v * w / G, "peak": S0 * (1 + v * w / G)}


def hoist_slack(hook_speed=0.9, falls=2, J=500.0, R=0.25, m=5000.0, EA=2.0e7):
    """From the static state the drum pays out at a constant speed, the hook's rope end
    moving down at u > g / w: the load lags, the rope force S0 - (m u w / n) sin(w t)
    reaches zero at t_s = asin(g / (u w)) / w; the load then falls freely and the rope
    is taut again after 2 u cos(w t_s) / g (the relative motion is symmetric), with the
    force rising to (m g / n)(1 + u w / g). The relative motion conserves energy.
    """
    text, _ = two_mass_hoist(falls, J, R, m, EA)
    k, S0 = _hoist_numbers(falls, J, R, m, EA)
    w = np.sqrt(falls**2 * k / m)
    if hook_speed * w <= G:
        raise ValueError("the rope stays taut unless hook_speed * w > g")
    ts = np.arcsin(G / (hook_speed * w)) / w
    return text, {"S0": S0, "omega": w, "drum_speed": -hook_speed * falls / R,
                  "slack_time": ts, "taut_time": ts + 2 * hook_speed * np.cos(w * ts) / G,
                  "peak": S0 * (1 + hook_speed * w / G)}


# ---------------------------------------------------------------- structures

def timoshenko_simply_supported(L=10.0, h=2.0, E=200.0e9, nu=0.3, rho=8000.0, kappa=None,
                                elements=16, modes=3, shear=True):
    """A simply supported Timoshenko beam of square section h x h, planar, flexural modes.

    v = V sin(a x), psi = P cos(a x), a = n pi / L, solve the Timoshenko equations
    k G A (v'' - psi') = rho A v_tt, E I psi'' + k G A (v' - psi) = rho I psi_tt exactly
    with pinned ends (Han, Benaroya & Wei, J. Sound Vib. 225 (1999) 935, the
    simply supported case): their determinant is
    rho^2 I / (k G) w^4 - (rho A + rho I a^2 + E I rho a^2 / (k G)) w^2 + E I a^4 = 0,
    whose lower root is the flexural mode (the upper one the shear spectrum). kappa defaults to Cowper's 10 (1 + nu) / (12 + 11 nu) for a
    rectangle. This is the NAFEMS FV5 deep beam (L = 10 m, h = 2 m; published
    42.65, 148.15 Hz), whose Euler-Bernoulli frequencies are (n pi / L)^2 sqrt(EI / rho A).
    The pins are massless bodies hinged to the ground at the ends.
    """
    kappa = 10 * (1 + nu) / (12 + 11 * nu) if kappa is None else kappa
    G_ = E / (2 * (1 + nu))
    A, I = h * h, h**4 / 12
    shear_key = f", shear_coefficient: {kappa!r}" if shear else ""
    text = f"""cranefe: 1
name: simply supported deep beam
plane: xz
gravity: [0, 0, 0]
nodes: {{A: [0, 0, 0], B: [{L}, 0, 0]}}
bodies:
  pin_a: {{mass: 0, nodes: [A]}}
  pin_b: {{mass: 0, nodes: [B]}}
joints:
  - {{type: hinge, bodies: [ground, pin_a], at: A, axis: [0, 1, 0]}}
  - {{type: hinge, bodies: [ground, pin_b], at: B, axis: [0, 1, 0]}}
members:
  beam: {{type: beam, nodes: [A, B], E: {E!r}, G: {G_!r}, A: {A!r}, Iy: {I!r},
         rho: {rho!r}, elements: {elements}{shear_key}}}
effects: {{structure: flexible}}
"""
    a = np.arange(1, modes + 1) * np.pi / L
    c2 = rho**2 * I / (kappa * G_)
    c1 = rho * A + rho * I * a**2 + E * I * rho * a**2 / (kappa * G_)
    c0 = E * I * a**4
    w2 = 2 * c0 / (c1 + np.sqrt(c1**2 - 4 * c2 * c0))      # the lower root, no cancellation
    return text, {"omega": np.sqrt(w2), "omega_euler_bernoulli": a**2 * np.sqrt(E * I / (rho * A)),
                  "published_hz": np.array([42.65, 148.15])}


def cantilever_tip_mass(L=10.0, E=2.1e11, A=1.0e-2, I=2.0e-4, rho=7850.0, M=1000.0,
                        J=2.0e4, elements=16, modes=3):
    """A planar Euler-Bernoulli cantilever with a tip mass M and rotary inertia J.

    v = a cosh bx + b sinh bx + c cos bx + d sin bx, b^4 = rho A w^2 / (E I), with
    v(0) = v'(0) = 0 and, from the variation of the kinetic energy of the tip,
    E I v''(L) - J w^2 v'(L) = 0 and E I v'''(L) + M w^2 v(L) = 0 (e.g. Blevins, Formulas
    for Natural Frequency and Mode Shape, table 8-8, with J). The frequencies are the
    zeros of the 2 x 2 determinant left after the clamped end, found by bracketing and
    Brent's method to 1e-15.
    """
    text = f"""cranefe: 1
name: cantilever with a tip mass and rotary inertia
plane: xz
gravity: [0, 0, 0]
nodes: {{O: [0, 0, 0], T: [{L}, 0, 0]}}
ground: [O]
masses: {{T: {{mass: {M!r}, inertia: {J!r}}}}}
members:
  beam: {{type: beam, nodes: [O, T], E: {E!r}, A: {A!r}, Iy: {I!r}, rho: {rho!r},
         elements: {elements}}}
effects: {{structure: flexible}}
"""
    EI, m = E * I, rho * A

    def det(beta):
        w2 = EI * beta**4 / m
        bl = beta * L
        ch, sh, c, s = np.cosh(bl), np.sinh(bl), np.cos(bl), np.sin(bl)
        # v = a (cosh - cos) + b (sinh - sin) satisfies the clamped end
        d2 = beta**2 * np.array([ch + c, sh + s])
        d1 = beta * np.array([sh + s, ch - c])
        d3 = beta**3 * np.array([sh - s, ch + c])
        d0 = np.array([ch - c, sh - s])
        r1 = EI * d2 - J * w2 * d1
        r2 = EI * d3 + M * w2 * d0
        return (r1[0] * r2[1] - r1[1] * r2[0]) / np.cosh(bl) ** 2 / (EI**2 * beta**5)

    grid = np.linspace(1e-3, (modes + 1.5) * np.pi, 4000) / L
    vals = np.array([det(b) for b in grid])
    roots = [so.brentq(det, grid[k], grid[k + 1], xtol=1e-15 / L)
             for k in np.flatnonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))][:modes]
    beta = np.array(roots)
    return text, {"omega": beta**2 * np.sqrt(EI / m)}


def nafems_fv2(elements=16, E=200.0e9, rho=8000.0, h=0.125, R=5.0, axial_factor=1.0):
    """NAFEMS FV2, the pin-ended double cross, in-plane vibration (here in the x-z plane):
    eight arms of square section h x h from the centre C to pinned ends at radius R, 45
    degrees apart, written with `supports: {Pk: pinned}`.

    The published family (11.336; 17.709 x 7; 45.345; 57.390 x 7 Hz) is that of arms with
    the centre fixed in translation: pinned-pinned arms (beta L = pi, 2 pi) when the
    centre turns, clamped-pinned (beta L = 3.9266, 7.0686, from tan bL = tanh bL) when
    it does not; f = (beta L)^2 / (2 pi R^2) sqrt(E I / (rho A)). Axially flexible arms
    let the centre translate in two of the clamped-pinned modes of each family, which
    moves the arms' axial inertia and lowers those pairs; `axial_factor` multiplies A and
    divides rho (rho A and E I unchanged) to stiffen the arms axially.
    """
    ang = np.arange(8) * np.pi / 4
    nodes = ", ".join(f"P{k}: [{float(R * np.cos(a))!r}, 0, {float(R * np.sin(a))!r}]"
                      for k, a in enumerate(ang))
    A, I = h * h, h**4 / 12
    arms = "\n".join(f"  arm{k}: {{type: beam, nodes: [C, P{k}], E: {E!r}, "
                     f"A: {A * axial_factor!r}, Iy: {I!r}, rho: {rho / axial_factor!r}, "
                     f"elements: {elements}}}" for k in range(8))
    text = (f"cranefe: 1\nname: NAFEMS FV2 pin-ended double cross\nplane: xz\n"
            f"gravity: [0, 0, 0]\nnodes: {{C: [0, 0, 0], {nodes}}}\n"
            "supports: {" + ", ".join(f"P{k}: pinned" for k in range(8)) + "}\n"
            f"members:\n{arms}\neffects: {{structure: flexible}}\n")
    bl_cp = [so.brentq(lambda b: np.tan(b) - np.tanh(b), k * np.pi + 0.1, k * np.pi + 1.5,
                       xtol=1e-15) for k in (1, 2)]
    bl = np.array([np.pi] + [bl_cp[0]] * 7 + [2 * np.pi] + [bl_cp[1]] * 7)
    f = bl**2 / (2 * np.pi * R**2) * np.sqrt(E * I / (rho * A))
    return text, {"omega": 2 * np.pi * f,
                  "published_hz": np.array([11.336] + [17.709] * 7 + [45.345] + [57.390] * 7),
                  "centre_translates": np.array([1, 2, 9, 10])}


def self_weight_column(L=10.0, E=2.1e11, A=1.0e-2, rho=7850.0, elements=16,
                       parameter=1.0):
    """A vertical column clamped at its foot, free at its top, buckling under its own
    weight q = rho A g per length (Greenhill 1881; Timoshenko & Gere, Theory of Elastic
    Stability, section 2.13): (q L^3 / E I)_cr = (9/4) j^2 with j the first zero of
    J_{-1/3}, 7.8373. I is chosen so that q L^3 / (E I) = `parameter`: the critical
    factor on gravity is then 7.8373 / parameter."""
    q = rho * A * G
    I = q * L**3 / (E * parameter)
    text = f"""cranefe: 1
name: column under its own weight
plane: xz
nodes: {{O: [0, 0, 0], T: [0, 0, {L}]}}
ground: [O]
members:
  col: {{type: beam, nodes: [O, T], E: {E!r}, A: {A!r}, Iy: {I!r}, rho: {rho!r},
        elements: {elements}}}
effects: {{structure: flexible}}
"""
    j = so.brentq(lambda x: ss.jv(-1 / 3, x), 1.0, 2.5, xtol=1e-15)
    critical = 9 / 4 * j**2
    return text, {"critical": critical, "factor": critical / parameter}
