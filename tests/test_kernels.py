"""Element kernels at any geometry (issue 14; style.md 13): `rope_force` against closed
forms and against finite differences of its own energy, so the linear core (which calls
it at the reference positions) and the large-motion engine share one verified kernel."""

import numpy as np

from cranefe.elements import hencky_energy, rope_force


def _tackle():
    """A rope from a drum anchor A over a sheave S down a 3-fall tackle to a hook H, and
    a second rope of one span; arbitrary (non-symmetric) positions."""
    x = np.array([[0.0, 0.0, 0.0], [4.0, 1.0, 20.0], [5.0, 0.5, 3.0], [9.0, -2.0, 7.0]])
    a, b = np.array([0, 1, 3]), np.array([1, 2, 2])
    falls, rope = np.array([1, 3, 1]), np.array([0, 0, 1])
    return x, a, b, falls, rope


def _energy(x, a, b, f, rope, EA, L0):
    st = rope_force(x, a, b, f, rope, EA, L0)
    return float(np.sum(np.where(st.L > L0, hencky_energy(EA, st.L, L0), 0.0)))


def test_length_tension_and_slack():
    x, a, b, f, rope = _tackle()
    l = np.linalg.norm(x[b] - x[a], axis=1)
    L = np.array([l[0] + 3 * l[1], l[2]])
    EA = np.array([1.0e7, 2.0e6])
    L0 = np.array([L[0] / 1.002, (L[1] + 0.5) * 1.01])  # rope 0 stretched, rope 1 slack
    st = rope_force(x, a, b, f, rope, EA, L0, extra=0.5)
    np.testing.assert_allclose(st.L, L + 0.5, rtol=1e-15)
    np.testing.assert_allclose(st.S[0], EA[0] * np.log((L[0] + 0.5) / L0[0]), rtol=1e-14)
    assert st.S[1] == 0.0 and st.c[1] == 0.0
    np.testing.assert_allclose(st.c[0], EA[0] / (L[0] + 0.5), rtol=1e-15)


def test_force_and_tangent_are_derivatives_of_the_energy():
    """-dU/dx is the span force, d2U/dx2 the tangent c r r^T + geometric blocks
    (central differences, h = 1e-6 m: truncation ~1e-12 relative, round-off ~1e-9)."""
    x, a, b, f, rope = _tackle()
    EA = np.array([1.0e7, 2.0e6])
    st0 = rope_force(x, a, b, f, rope, EA, np.ones(2))
    L0 = st0.L / np.array([1.003, 1.001])
    st = rope_force(x, a, b, f, rope, EA, L0)
    n = x.size
    force = np.zeros(n)
    for s in range(len(a)):
        idx = np.r_[3 * a[s]:3 * a[s] + 3, 3 * b[s]:3 * b[s] + 3]
        force[idx] += st.span_force(rope)[s]
    # tangent: c r r^T per rope + the span geometric blocks
    R = np.zeros((2, n))
    K = np.zeros((n, n))
    G = st.geometric(rope, f)
    for s in range(len(a)):
        idx = np.r_[3 * a[s]:3 * a[s] + 3, 3 * b[s]:3 * b[s] + 3]
        R[rope[s], idx] += st.grad[s]
        K[np.ix_(idx, idx)] += G[s]
    K += R.T @ (st.c[:, None] * R)
    h = 1e-6
    fd_force, fd_K = np.zeros(n), np.zeros((n, n))
    for i in range(n):
        xp, xm = x.copy().ravel(), x.copy().ravel()
        xp[i] += h
        xm[i] -= h
        fd_force[i] = -(_energy(xp.reshape(-1, 3), a, b, f, rope, EA, L0)
                        - _energy(xm.reshape(-1, 3), a, b, f, rope, EA, L0)) / (2 * h)
        fp = np.zeros(n)
        fm = np.zeros(n)
        for xx, out in ((xp, fp), (xm, fm)):
            s2 = rope_force(xx.reshape(-1, 3), a, b, f, rope, EA, L0)
            for s in range(len(a)):
                idx = np.r_[3 * a[s]:3 * a[s] + 3, 3 * b[s]:3 * b[s] + 3]
                out[idx] += s2.span_force(rope)[s]
        fd_K[:, i] = -(fp - fm) / (2 * h)
    np.testing.assert_allclose(force, fd_force, rtol=1e-6, atol=1e-6 * np.abs(force).max())
    np.testing.assert_allclose(K, fd_K, rtol=1e-6, atol=1e-7 * np.abs(K).max())
