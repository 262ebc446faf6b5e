"""Equations of motion of a scene in the form the time stepper takes.

    M x'' + C x' + K x + R^T (s(x) - S0) = F0 + sum_j G_j g_j(t) + sum_m e_m tau_m(e_m . x')

with s(x) = taut * (S0 + c R x): the rows R of tension-only elements (ropes) that are not
in K, each taut or slack; g_j(t) known signals (torques, node forces, prescribed motions
seen by the other coordinates); tau_m the torque of a motor as a function of its speed.
Coordinates may be known functions of time (prescribed drum angles) or held at zero
while a load rests on the ground (contacts, unilateral: the ground only pushes).

The same form serves the direct integration (x = q, the model's generalised coordinates)
and modal superposition (x = principal coordinates, M = I, K = diag(w^2), no tension-only
rows); `to_full` maps x back to q.
"""

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

DENSE_OPS = 200       # up to this many coordinates the matrices are kept dense


@dataclass
class Signal:
    """A known function of time with its rate, both (t, left=False) -> (w,): left=True
    gives the left-hand limit where the function or its rate jumps."""

    value: object
    rate: object = None       # None: not known (taken as 0)

    def d(self, t, left=False):
        return self.rate(t, left) if self.rate is not None else 0.0 * self.value(t, left)


@dataclass
class MotorLoad:
    """tau(n) at the motor shaft acting through a gear on the coordinate direction e:
    generalised force e * i * M(i * e.x')."""

    e: np.ndarray             # (n,)
    motor: object             # scene.Motor
    gear: float
    name: str = ""

    def force(self, v):
        """(generalised force (n,), drum torque, d(drum torque)/d(drum speed))."""
        speed = float(self.e @ v)
        M, dM = self.motor.torque(self.gear * speed)
        return self.e * (self.gear * M), self.gear * M, self.gear**2 * dM


@dataclass
class Equations:
    M: object                 # (n, n) csr or ndarray
    K: object                 # (n, n) the linear stiffness (tension-only rows excluded)
    C: object = None          # (n, n) csr/ndarray viscous damping, or None
    U: np.ndarray = None      # (n, r) low-rank damping C += U diag(W) U^T
    W: np.ndarray = None      # (r,)
    R: object = None          # (m, n) csr rows of tension-only elements, or None
    c: np.ndarray = None      # (m,)
    S0: np.ndarray = None     # (m,) initial forces of those rows
    F0: np.ndarray = None     # (n,) constant generalised force
    loads: list = field(default_factory=list)      # (G (n, w), Signal)
    motors: list = field(default_factory=list)     # MotorLoad
    prescribed: dict = field(default_factory=dict)  # index -> speed Profile
    contacts: np.ndarray = None   # (nc,) coordinates held by the ground while on
    up: np.ndarray = None         # (nc,) +1/-1: sign of "up" along each contact coordinate
    to_full: object = None        # (t, x, x') -> (q, q') in the model's coordinates

    def __post_init__(self):
        self.n = self.M.shape[0]
        if sp.issparse(self.M) and self.n <= DENSE_OPS:     # small: numpy is faster
            self.M, self.K = self.M.toarray(), self.K.toarray()
            if self.C is not None:
                self.C = self.C.toarray()
            if self.R is not None:
                self.R = self.R.toarray()
        self.dense = not sp.issparse(self.M)
        if self.F0 is None:
            self.F0 = np.zeros(self.n)
        if self.contacts is None:
            self.contacts = np.zeros(0, dtype=int)
            self.up = np.zeros(0)
        if self.R is None:
            self.R = sp.csr_matrix((0, self.n))
            self.c = np.zeros(0)
            self.S0 = np.zeros(0)
        self.RT = self.R.T.copy() if self.dense else self.R.T.tocsr()
        if self.dense and sp.issparse(self.R):
            self.R = self.R.toarray()
            self.RT = self.R.T.copy()
        self.mass = (np.diag(self.M) if self.dense else self.M.diagonal()) > 0
        self.has_damping = self.C is not None or self.U is not None

    # ------------------------------------------------------------- forces
    def force(self, t, left=False):
        """Known generalised forces at t (motors excluded)."""
        F = self.F0.copy()
        for G, s in self.loads:
            F += G @ s.value(t, left)
        return F

    def motor_force(self, v):
        F = np.zeros(self.n)
        for m in self.motors:
            F += m.force(v)[0]
        return F

    def damp(self, v):
        out = np.zeros(self.n)
        if self.C is not None:
            out += self.C @ v
        if self.U is not None:
            out += self.U @ (self.W * (self.U.T @ v))
        return out

    def tension(self, x):
        return self.S0 + self.c * (self.R @ x)

    def internal(self, x, taut):
        """K x + R^T (s(x) - S0)."""
        f = self.K @ x
        if len(self.c):
            f = f + self.RT @ (np.where(taut, self.tension(x), 0.0) - self.S0)
        return f

    def residual(self, t, x, v, a, taut, left=False):
        """M a + C v + f(x) - F(t) - motors: the force the constraints (prescribed
        coordinates, the ground) supply."""
        return self.M @ a + self.damp(v) + self.internal(x, taut) - self.force(t, left) \
            - self.motor_force(v)

    def energy(self, x, v):
        """Kinetic energy plus the potential whose gradient is `internal`."""
        e = 0.5 * v @ (self.M @ v) + 0.5 * x @ (self.K @ x)
        if len(self.c):
            with np.errstate(divide="ignore", invalid="ignore"):
                stretch = np.where(self.c > 0, np.maximum(self.tension(x), 0.0) / self.c, 0)
                e += float(np.sum(0.5 * self.c * stretch**2 - np.where(
                    self.c > 0, 0.5 * self.S0**2 / np.where(self.c > 0, self.c, 1), 0)
                    - self.S0 * (self.R @ x)))
        return float(e)

    # ------------------------------------------------------------- known coordinates
    def known(self, t, on, left=True):
        """Indices and (x, x', x'') of the coordinates known at t: prescribed ones (their
        speed Profile integrated; x'' its left or right slope) and the contacts that are
        on (x = x' = x'' = 0)."""
        idx = list(self.prescribed) + list(self.contacts[on])
        xq, xv, xa = (np.zeros(len(idx)) for _ in range(3))
        for k, p in enumerate(self.prescribed.values()):
            xq[k], xv[k], xa[k] = p.integral(t)[0], p(t)[0], p.rate(t, left)[0]
        return np.array(idx, dtype=int), xq, xv, xa

    def matrix(self, h, taut, alpha):
        """alpha M + (2/h) C + K + R^T diag(c taut) R (without the low-rank damping)."""
        A = alpha * self.M + self.K
        if self.C is not None:
            A = A + (2.0 / h) * self.C
        if len(self.c) and taut.any():
            Rt = self.R[taut]
            if self.dense:
                A = A + Rt.T @ (Rt * self.c[taut][:, None])
            else:
                A = A + Rt.T @ sp.diags(self.c[taut]) @ Rt
        return A


class Factor:
    """Solves with A_ff + V_f D V_f^T (Woodbury on a sparse or dense LU of A_ff)."""

    def __init__(self, A, free, V=None, D=None):
        self.free = free
        Aff = A[np.ix_(free, free)] if not sp.issparse(A) else A.tocsr()[free][:, free]
        if sp.issparse(Aff):
            self.lu = spla.splu(Aff.tocsc())
            self._solve = self.lu.solve
        else:
            lu = sla.lu_factor(np.asarray(Aff), check_finite=False)
            self._solve = lambda b: sla.lu_solve(lu, b, check_finite=False)
        self.V, self.D = V, D
        self.Z = self._solve(V) if V is not None and V.shape[1] else None
        self._Z = {}

    def solve_lowrank(self, b, V, D, Z):
        """(A + V diag(D) V^T)^-1 b = y - Z D (I + V^T Z D)^-1 V^T y, y = A^-1 b."""
        y = self._solve(b)
        if Z is None:
            return y
        S = np.eye(len(D)) + (V.T @ Z) * D[None, :]
        return y - Z @ (D * np.linalg.solve(S, V.T @ y))

    def solve(self, b, extra=None):
        """Solve; `extra` = (E (nf, k), d (k,)) adds E diag(d) E^T (motor tangents)."""
        V, D, Z = self.V, self.D, self.Z
        if extra is not None:
            E, d = extra
            key = E.tobytes()
            if key not in self._Z:
                self._Z[key] = self._solve(E)
            ZE = self._Z[key]
            V = E if V is None else np.hstack([V, E])
            D = d if D is None else np.concatenate([D, d])
            Z = ZE if Z is None else np.hstack([Z, ZE])
        if Z is None:
            return self._solve(b)
        return self.solve_lowrank(b, V, D, Z)
