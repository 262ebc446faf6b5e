"""Input shapers: impulse trains (times t_i, amplitudes A_i, sum A_i = 1) that, convolved
with a command, cancel the residual vibration of a mode of frequency w and damping
ratio zeta (Singer & Seering 1990; Singhose, Seering & Singer 1994; docs/loads.md).

Residual vibration of an impulse train on the mode (w, zeta), relative to one unit
impulse, measured after the last impulse t_N (Singhose et al. 1994 eq. 1-3):
  V(w, zeta) = |sum_i A_i exp(w s (t_i - t_N))|,  s = zeta + i sqrt(1 - zeta^2),
since each impulse starts a decaying oscillation exp(-zeta w t) sin(w_d t) and the phase
factor exp(i w_d t_N) has modulus one.
"""

from dataclasses import dataclass
from math import comb

import numpy as np
import scipy.optimize as so

from ...errors import AnalysisError, ModelError


@dataclass(frozen=True)
class Shaper:
    """An impulse train: ``times`` (s, from 0, increasing) and ``amplitudes`` (sum 1)."""
    name: str
    times: np.ndarray
    amplitudes: np.ndarray
    omega: float = float("nan")      # design frequency(ies) [rad/s], informational
    zeta: float = 0.0

    @property
    def duration(self):
        """The move time the shaper adds: its last impulse time."""
        return float(self.times[-1])

    def residual(self, omega, zeta=None):
        """V(w, zeta) of the module docstring; omega may be an array."""
        z = self.zeta if zeta is None else zeta
        w = np.asarray(omega, float)[..., None]
        s = z + 1j * np.sqrt(1.0 - z * z)
        return np.abs(np.sum(self.amplitudes * np.exp(w * s * (self.times - self.times[-1])),
                             axis=-1))

    def _z(self, omega, zeta):
        z = self.zeta if zeta is None else zeta
        w = np.asarray(omega, float)[..., None]
        s = z + 1j * np.sqrt(1.0 - z * z)
        dt = self.times - self.times[-1]
        e = self.amplitudes * np.exp(w * s * dt)
        return np.sum(e, axis=-1), np.sum(e * s * dt, axis=-1)

    def residual_derivative(self, omega, zeta=None):
        """dV/dw where V > 0 (analytic: d|Z|/dw = Re(conj(Z) Z') / |Z|, Z the complex
        sum of the module docstring)."""
        Z, dZ = self._z(omega, zeta)
        return np.real(np.conj(Z) * dZ) / np.abs(Z)

    def slope(self, omega, zeta=None):
        """|dZ/dw|: bounds |dV/dw| and is its one-sided value at a zero of V (a ZV
        shaper's V has a kink there; ZVD's vanishes with its slope)."""
        return np.abs(self._z(omega, zeta)[1])


def _check(omega, zeta):
    if not omega > 0:
        raise ModelError(f"a shaper's frequency must be positive (got {omega} rad/s)")
    if not 0.0 <= zeta < 1.0:
        raise ModelError(f"a shaper's damping ratio must lie in [0, 1) (got {zeta})")
    wd = omega * np.sqrt(1 - zeta**2)
    return np.pi / wd, np.exp(-zeta * np.pi / np.sqrt(1 - zeta**2))   # half period, K


def unshaped():
    return Shaper("unshaped", np.zeros(1), np.ones(1))


def _binomial(name, omega, zeta, n):
    """ZV (n=1), ZVD (2), ZVDD (3): amplitudes C(n,i) K^i / (1+K)^n at i half periods
    (Singer & Seering 1990: the derivatives of V with respect to w vanish to order n-1)."""
    half, K = _check(omega, zeta)
    i = np.arange(n + 1)
    A = np.array([comb(n, k) for k in i], float) * K**i / (1 + K)**n
    return Shaper(name, i * half, A, float(omega), float(zeta))


def zv(omega, zeta=0.0):
    return _binomial("ZV", omega, zeta, 1)


def zvd(omega, zeta=0.0):
    return _binomial("ZVD", omega, zeta, 2)


def zvdd(omega, zeta=0.0):
    return _binomial("ZVDD", omega, zeta, 3)


def ei(omega, zeta=0.0, V=0.05):
    """Extra-insensitive shaper (Singhose et al. 1994): three impulses with residual V at
    the design frequency, a zero slope there (V is a local maximum) and zero residual at
    two frequencies either side. Undamped: A = ((1+V)/4, (1-V)/2, (1+V)/4) at 0, T/2, T
    (symmetric about T/2, the residual is |A2 + 2 A1 cos(w T/2)|: the zeros at
    w T/2 = pi +/- arccos((1-V)/(1+V))). Damped: the same six conditions solved by Newton
    from the undamped train with each impulse scaled by K^i."""
    half, K = _check(omega, zeta)
    if not 0.0 < V < 1.0:
        raise ModelError(f"EI's tolerable vibration V must lie in (0, 1) (got {V})")
    A0 = np.array([(1 + V) / 4, (1 - V) / 2, (1 + V) / 4])
    if zeta == 0.0:
        return Shaper("EI", np.array([0.0, half, 2 * half]), A0, float(omega), 0.0)
    return _ei_damped(omega, zeta, V, A0)


def _ei_equations(omega, zeta, V):
    """The six EI conditions in p = (A1, A3, t2/T, t3/T, w_lo/w, w_hi/w), T the damped
    period: |Z(w)|^2 = V^2, d|Z|^2/dw = 0, Z(w_lo) = Z(w_hi) = 0 (real and imaginary)."""
    s = zeta + 1j * np.sqrt(1 - zeta**2)
    T = 2 * np.pi / (omega * np.sqrt(1 - zeta**2))

    def Z(p, w, d=False):
        A = np.array([p[0], 1 - p[0] - p[1], p[1]])
        t = np.array([0.0, p[2], p[3]]) * T
        e = A * np.exp(w * s * (t - t[-1]))
        return np.sum(e * s * (t - t[-1])) if d else np.sum(e)

    def F(p):
        z0, z1, z2 = Z(p, omega), Z(p, p[4] * omega), Z(p, p[5] * omega)
        return [abs(z0)**2 - V**2, np.real(np.conj(z0) * Z(p, omega, True)) * omega,
                z1.real, z1.imag, z2.real, z2.imag]
    return F, T


def _ei_damped(omega, zeta, V, A0):
    """Newton (fsolve) on `_ei_equations`, continued in zeta from the undamped solution
    in steps of at most 0.05 (a direct start fails for heavy damping)."""
    c = np.arccos((1 - V) / (1 + V)) / np.pi          # zeros at (1 -/+ c) w (undamped)
    p = np.array([A0[0], A0[2], 0.5, 1.0, 1 - c, 1 + c])
    steps = int(np.ceil(zeta / 0.05))
    for z in np.linspace(zeta / steps, zeta, steps):
        F, T = _ei_equations(omega, z, V)
        p, info, ok, msg = so.fsolve(F, p, xtol=1e-13, full_output=True)
    if np.max(np.abs(F(p))) > 1e-12:       # fsolve may stop at round-off before xtol
        raise AnalysisError(f"no EI shaper found for zeta = {zeta}, V = {V}: {msg}")
    A = np.array([p[0], 1 - p[0] - p[1], p[1]])
    return Shaper("EI", np.array([0.0, p[2], p[3]]) * T, A, float(omega), float(zeta))


def convolve(*shapers, name=None):
    """Multi-mode shaper: the convolution of single-mode ones (times add, amplitudes
    multiply). Its residual at each mode is that mode's shaper's residual times the
    others' gains, so it cancels every mode its factors cancel."""
    t, A = np.zeros(1), np.ones(1)
    for sh in shapers:
        t = (t[:, None] + sh.times[None, :]).ravel()
        A = (A[:, None] * sh.amplitudes[None, :]).ravel()
    order = np.argsort(t, kind="stable")
    t, A = t[order], A[order]
    keep = np.concatenate([[True], np.diff(t) > 1e-12 * max(t[-1], 1.0)])
    idx = np.cumsum(keep) - 1
    A = np.bincount(idx, weights=A)
    return Shaper(name or "*".join(s.name for s in shapers), t[keep], A,
                  float("nan"), shapers[0].zeta if shapers else 0.0)


SHAPERS = {"unshaped": lambda w, z=0.0, **k: unshaped(), "ZV": zv, "ZVD": zvd,
           "ZVDD": zvdd, "EI": ei}


def make(name, omega, zeta=0.0, **options):
    """A shaper by name (registry ``SHAPERS``)."""
    if name not in SHAPERS:
        raise ModelError(f"unknown shaper {name!r}: use one of {', '.join(SHAPERS)}")
    return SHAPERS[name](omega, zeta, **options)
