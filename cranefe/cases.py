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
