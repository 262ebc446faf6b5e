"""Kill tests for cranefe/analysis/transient/newmark.py (tools/mutation.py newmark;
docs/testing.md, "Mutation testing"): the integrator's every step against the exact
discrete solution of the trapezoidal rule, written independently in first-order form.

For a linear system z' = A z + f (z = (q, q'), f constant) the trapezoidal rule
z_{n+1} = z_n + h/2 (A z_n + f + A z_{n+1} + f) is the Cayley map
z_{n+1} = (I - hA/2)^-1 ((I + hA/2) z_n + h f), the same recurrence as Newmark's average
acceleration (beta = 1/4, gamma = 1/2) in its incremental second-order form, but written
differently: the code's displacement and velocity updates, its step matrix 4/h^2 M +
2/h C + K and its right-hand side must all be right to match it to round-off.

The case is tests/test_values.py's load on a hoist rope and a tagline (sway on, damping
exact: each rope a dashpot psi c / (2 pi w_e)), both ropes taut throughout, so the
system is linear; the step h = 0.02 s is coarse (w h = 0.64 for the hoisting mode: the
trapezoidal rule's period is 3.4 % long there), so the discrete solution is far from the
exact continuous one and only the trapezoidal rule itself matches it.
"""

import numpy as np
import scipy.linalg as sla

from cranefe.analysis.transient.integrate import simulate
from cranefe.model import load

from test_values import TAGLINE, tagline_matrices


def test_every_step_is_the_cayley_map_of_the_trapezoidal_rule(tmp_path):
    """q at every step (output_step = h) to 1e-10 m against the Cayley recurrence (the
    response is ~1e-2 m; round-off of 120 steps is ~1e-14 m), the tagline force to
    1e-6 N, and the energy balance: the work of the step force F . q_N and the dissipated
    energy sum h vbar^T C vbar (vbar the step's mean velocity: exact for the trapezoidal
    rule) to 1e-9 relative."""
    K, M, e, c, S = tagline_matrices()
    w2, V = sla.eigh(K, M)
    w = np.sqrt(w2)
    # the dashpots: hoist rope at the hoisting mode (w[1]), tagline at the pendulum (w[0])
    # (the frequency choice is tests/test_values.py's subject; here it only builds C)
    psi = (0.2, 0.4)
    C = sum(p * ci / (2 * np.pi * wi) * np.outer(ei, ei)
            for p, ci, wi, ei in zip(psi, c, (w[1], w[0]), e))
    h, n = 0.02, 120
    (path := tmp_path / "tagline.yaml").write_text(TAGLINE)
    (scene := tmp_path / "step.yaml").write_text(
        f"cranefe: 1\nscene: step\nmodel: {path}\neffects: {{damping: exact}}\n"
        f"analysis:\n  type: transient\n  duration: {h * n}\n  time_step: {h}\n"
        f"  output_step: {h}\n  forces:\n    L: {{force: [-2000, 0, 0]}}\n")
    r = simulate(load(scene))
    F = np.array([-2000.0, 0.0])
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-np.linalg.solve(M, K),
                                                  -np.linalg.solve(M, C)]])
    f = np.r_[0.0, 0.0, np.linalg.solve(M, F)]
    I4 = np.eye(4)
    L_, R_ = I4 - h / 2 * A, I4 + h / 2 * A
    z = np.zeros(4)
    zs, dissipated = [z], 0.0
    for _ in range(n):
        z1 = np.linalg.solve(L_, R_ @ z + h * f)
        vbar = (z[2:] + z1[2:]) / 2
        dissipated += h * vbar @ C @ vbar
        z = z1
        zs.append(z)
    zs = np.array(zs)
    assert len(r.times) == n + 1 and np.allclose(r.times, h * np.arange(n + 1), atol=1e-12)
    np.testing.assert_allclose(r.q, zs[:, :2], rtol=0, atol=1e-10)
    tag = S[1] - c[1] * (zs[:, :2] @ e[1])
    assert tag.min() > 18e3                                         # taut throughout
    np.testing.assert_allclose(r.rope_force[:, 1], tag, rtol=0, atol=1e-6)
    assert abs(r.energy["work_loads"] / (F @ zs[-1, :2]) - 1) < 1e-9
    assert abs(r.energy["dissipated"] / dissipated - 1) < 1e-9
    assert r.energy_error < 1e-10
    # the coarse step matters: the continuous solution differs by far more than 1e-10
    q_exact = np.linalg.solve(A, (sla.expm(A * h * n) - I4) @ f)[:2]
    assert np.abs(q_exact - zs[-1, :2]).max() > 1e-4
