"""Large-motion kinematics of a planar linkage built from a model, driven by the boom angle.

The moving bodies are those the model's joints connect to the ground. Each has the pose
``(x, z, theta)`` of its reference point (its centre of mass in the model's geometry,
where ``theta = 0``; ``theta`` counter-clockwise in the x-z plane, x turning toward z). A
body point with offset ``c`` from the reference point is ``X = (x, z) + Rot(theta) c``.

The joints give the constraint equations ``Phi(q, alpha) = 0`` (docs/luffing.md):

- hinge (or ball) at node n: the two bodies' copies of n coincide (2 equations);
- slider along axis u: ``n(theta_a) . (X_b - X_a) = 0`` with n the normal of u carried
  by the first body, and ``theta_a - theta_b = 0`` (2 equations);
- fixed: the hinge equations and ``theta_a - theta_b = 0`` (3 equations);
- the driver: ``theta_boom - (alpha - alpha_ref) = 0``, alpha the angle of pivot->tip
  above the horizontal.

Positions follow by Newton (batched over many angles, each started from the nearest
configuration of a continuation table that follows the assembly branch of the model's
geometry). The transfer functions come from implicit differentiation, not finite
differences: ``Phi_q q' = -Phi_alpha`` and ``Phi_q q'' = -gamma`` with
``gamma = d2 Phi / d q2 [q', q']`` written out exactly (``Rot'' = -Rot``).
"""

from dataclasses import dataclass

import numpy as np

from ...errors import AnalysisError, ModelError
from ...model import GROUND


def _xz(v):
    return np.array([v[0], v[2]], dtype=float)


def _perp(v):
    """Rotate (..., 2) vectors by +90 degrees: d Rot(theta) c / d theta = perp(Rot c)."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def _rotate(theta, c):
    """Rot(theta) c for theta (N,) and c (2,) -> (N, 2)."""
    ct, st = np.cos(theta), np.sin(theta)
    return np.stack([ct * c[0] - st * c[1], st * c[0] + ct * c[1]], axis=-1)


@dataclass
class KinState:
    """Poses and transfer functions at N boom angles.

    alpha : (N,) boom angles (rad); q, dq, ddq : (N, 3 nb) poses and their first and
    second derivatives with respect to alpha; residual : (N,) largest |Phi| (m or rad).
    """

    linkage: "Linkage"
    alpha: np.ndarray
    q: np.ndarray
    dq: np.ndarray
    ddq: np.ndarray
    residual: np.ndarray

    def angle(self, body):
        """Absolute angle of a body's line above its model direction, and d/dalpha,
        d2/dalpha2 (N,) each (body: model body index)."""
        k = 3 * self.linkage.local[body] + 2
        return self.q[:, k], self.dq[:, k], self.ddq[:, k]

    def point(self, node, body=None):
        """Position, d/dalpha, d2/dalpha2 (N, 2) each of a node (x, z)."""
        lk = self.linkage
        b = lk.carrier(node) if body is None else body
        if b == GROUND:
            X = np.broadcast_to(_xz(lk.model.coords[node]), (len(self.alpha), 2))
            return X.copy(), np.zeros_like(X), np.zeros_like(X)
        return self.body_point(b, _xz(lk.model.coords[node]) - lk.ref[lk.local[b]])

    def body_point(self, body, c):
        """Position and its alpha derivatives of the point at offset c of a model body."""
        i = self.linkage.local[body]
        th, dth, ddth = self.q[:, 3 * i + 2], self.dq[:, 3 * i + 2], self.ddq[:, 3 * i + 2]
        Rc = _rotate(th, c)
        P = _perp(Rc)
        X = self.q[:, 3 * i:3 * i + 2] + Rc
        dX = self.dq[:, 3 * i:3 * i + 2] + P * dth[:, None]
        ddX = (self.ddq[:, 3 * i:3 * i + 2] + P * ddth[:, None]
               - Rc * (dth**2)[:, None])
        return X, dX, ddX


class Linkage:
    """The moving bodies of a planar model as a one-degree-of-freedom linkage.

    Parameters
    ----------
    model : Model (plane: xz)
    boom : str, the driving body; pivot, tip : str, nodes (alpha = angle of pivot->tip)
    file : str, the file named in error messages (the scene)
    """

    STEP = np.radians(0.5)          # continuation step of the table

    def __init__(self, model, boom, pivot, tip, file=None, entry="analysis"):
        self.model = model
        file = file or model.file
        if not model.planar:
            raise ModelError("the luffing analysis needs a planar model (plane: xz)",
                             model.file, "plane")
        names = [b.name for b in model.bodies]
        if boom not in names:
            raise ModelError(f"unknown body '{boom}'; bodies: {', '.join(names)}", file,
                             f"{entry}.boom")
        idx = model.node_index
        for key, n in (("pivot", pivot), ("tip", tip)):
            if n not in idx:
                raise ModelError(f"unknown node '{n}'", file, f"{entry}.{key}")
        self.boom_body = names.index(boom)
        self.pivot, self.tip = idx[pivot], idx[tip]

        # bodies reachable from the ground through joints form the linkage
        moving, frontier = [], [GROUND]
        while frontier:
            b = frontier.pop()
            for j in model.joints:
                if b in j.bodies:
                    other = j.bodies[1] if j.bodies[0] == b else j.bodies[0]
                    if other != GROUND and other not in moving:
                        moving.append(other)
                        frontier.append(other)
        moving.sort()
        if self.boom_body not in moving:
            raise ModelError(f"body '{boom}' is not joined to the ground", file,
                             f"{entry}.boom")
        self.bodies = tuple(moving)                     # model body indices
        self.local = {b: i for i, b in enumerate(moving)}
        self.nb = len(moving)
        self.n = 3 * self.nb
        self.ref = np.array([_xz(model.bodies[b].com) for b in moving])
        self.q_ref = np.concatenate([[*c, 0.0] for c in self.ref])
        self.joints = tuple(j for j in model.joints
                            if all(b == GROUND or b in self.local for b in j.bodies))
        if not any(GROUND in j.bodies and self.boom_body in j.bodies and j.at == self.pivot
                   for j in self.joints):
            raise ModelError(f"node '{pivot}' is not a joint between '{boom}' and the "
                             "ground", file, f"{entry}.pivot")
        if self.carrier(self.tip) != self.boom_body:
            raise ModelError(f"node '{tip}' is not carried by body '{boom}'", file,
                             f"{entry}.tip")
        d = _xz(model.coords[self.tip] - model.coords[self.pivot])
        self.alpha_ref = float(np.arctan2(d[1], d[0]))
        self.scale = max(float(np.abs(self.ref).max()), 1.0)

        F, Jac = self.equations(self.q_ref[None], np.array([self.alpha_ref]))
        if np.abs(F).max() > 1e-9 * self.scale:
            raise ModelError("the model's geometry does not close the joints",
                             model.file, "joints")
        rank = np.linalg.matrix_rank(Jac[0, :-1], tol=1e-9 * self.scale)
        if rank != self.n - 1:
            raise ModelError(
                f"the linkage ({', '.join(names[b] for b in moving)}) has "
                f"{self.n - rank} degree(s) of freedom with the drive free; the luffing "
                "analysis needs exactly one, the boom angle: add or fix joints",
                model.file, "joints")
        self.square = Jac.shape[1] == Jac.shape[2]
        self._A = np.array([self.alpha_ref])
        self._Q = self.q_ref[None].copy()
        self._dQ = self._derivatives(self._Q, self._A)[0]
        self.limits = [None, None]                   # toggle positions found, if any

    # ------------------------------------------------------------------ topology
    def carrier(self, node):
        """The linkage body (model index) that carries a node, or GROUND."""
        if node in self.model.ground:
            return GROUND
        for b in self.bodies:
            if node in self.model.bodies[b].nodes:
                return b
        for j in self.joints:
            if j.at == node:
                return j.bodies[0] if j.bodies[0] != GROUND else j.bodies[1]
        return None

    # ------------------------------------------------------------------ equations
    def _point(self, q, body, node):
        """X (N, 2), Rot c (N, 2) of a node carried by body (model index or GROUND)."""
        X0 = _xz(self.model.coords[node])
        if body == GROUND:
            X = np.broadcast_to(X0, (len(q), 2)).copy()
            return X, np.zeros_like(X)
        i = self.local[body]
        Rc = _rotate(q[:, 3 * i + 2], X0 - self.ref[i])
        return q[:, 3 * i:3 * i + 2] + Rc, Rc

    def _theta(self, q, body):
        return q[:, 3 * self.local[body] + 2] if body != GROUND else np.zeros(len(q))

    def _cols(self, body):
        i = self.local[body]
        return 3 * i, 3 * i + 1, 3 * i + 2

    def equations(self, q, alpha):
        """Phi (N, m) and Phi_q (N, m, n) at poses q (N, n) and angles alpha (N,)."""
        N = len(q)
        F, rows = [], []

        def point_rows(body, Rc, sign, J):
            if body == GROUND:
                return
            cx, cz, ct = self._cols(body)
            J[:, 0, cx] += sign
            J[:, 1, cz] += sign
            J[:, :, ct] += sign * _perp(Rc)

        for jt in self.joints:
            a, b = jt.bodies
            Xa, Ra = self._point(q, a, jt.at)
            Xb, Rb = self._point(q, b, jt.at)
            if jt.type in ("hinge", "ball", "fixed"):
                J = np.zeros((N, 2, self.n))
                point_rows(a, Ra, 1.0, J)
                point_rows(b, Rb, -1.0, J)
                F.append(Xa - Xb)
                rows.append(J)
            if jt.type == "slider":
                u = _xz(jt.axis)
                nrm = _rotate(self._theta(q, a), np.array([-u[1], u[0]]))   # (N, 2)
                d = Xb - Xa
                J = np.zeros((N, 2, self.n))
                point_rows(b, Rb, 1.0, J)
                point_rows(a, Ra, -1.0, J)
                row = np.einsum("ni,nij->nj", nrm, J)
                if a != GROUND:
                    row[:, self._cols(a)[2]] += np.sum(_perp(nrm) * d, axis=1)
                F.append(np.sum(nrm * d, axis=1)[:, None])
                rows.append(row[:, None, :])
            if jt.type in ("slider", "fixed"):
                J = np.zeros((N, 1, self.n))
                if a != GROUND:
                    J[:, 0, self._cols(a)[2]] += 1.0
                if b != GROUND:
                    J[:, 0, self._cols(b)[2]] -= 1.0
                F.append((self._theta(q, a) - self._theta(q, b))[:, None])
                rows.append(J)
        J = np.zeros((N, 1, self.n))
        J[:, 0, self._cols(self.boom_body)[2]] = 1.0
        F.append((self._theta(q, self.boom_body) - (alpha - self.alpha_ref))[:, None])
        rows.append(J)
        return np.concatenate(F, axis=1), np.concatenate(rows, axis=1)

    def _gamma(self, q, dq):
        """d2 Phi / dq2 [dq, dq] (N, m): the curvature terms of the equations."""
        N = len(q)
        out = []

        def curv(body, Rc):          # d2 (Rot c) along dq = -Rot c theta'^2
            if body == GROUND:
                return np.zeros((N, 2))
            return -Rc * (dq[:, self._cols(body)[2]] ** 2)[:, None]

        def vel(body, Rc):           # d X along dq
            if body == GROUND:
                return np.zeros((N, 2))
            cx, cz, ct = self._cols(body)
            return dq[:, [cx, cz]] + _perp(Rc) * dq[:, ct][:, None]

        for jt in self.joints:
            a, b = jt.bodies
            Xa, Ra = self._point(q, a, jt.at)
            Xb, Rb = self._point(q, b, jt.at)
            if jt.type in ("hinge", "ball", "fixed"):
                out.append(curv(a, Ra) - curv(b, Rb))
            if jt.type == "slider":
                u = _xz(jt.axis)
                nrm = _rotate(self._theta(q, a), np.array([-u[1], u[0]]))
                w = dq[:, self._cols(a)[2]] if a != GROUND else np.zeros(N)
                d, dd = Xb - Xa, vel(b, Rb) - vel(a, Ra)
                g = (np.sum(nrm * (curv(b, Rb) - curv(a, Ra)), axis=1)
                     + 2 * w * np.sum(_perp(nrm) * dd, axis=1)
                     - w**2 * np.sum(nrm * d, axis=1))
                out.append(g[:, None])
            if jt.type in ("slider", "fixed"):
                out.append(np.zeros((N, 1)))
        out.append(np.zeros((N, 1)))                 # the driver is linear
        return np.concatenate(out, axis=1)

    def _lin_solve(self, J, rhs):
        if self.square:
            return np.linalg.solve(J, rhs[..., None])[..., 0]
        return np.einsum("nij,nj->ni", np.linalg.pinv(J), rhs)

    def _derivatives(self, q, alpha):
        F, J = self.equations(q, alpha)
        Fa = np.zeros_like(F)
        Fa[:, -1] = -1.0                              # d Phi_driver / d alpha
        dq = self._lin_solve(J, -Fa)
        ddq = self._lin_solve(J, -self._gamma(q, dq))
        return dq, ddq, J

    def newton(self, q, alpha, tol=1e-13, maxiter=30):
        """Newton on Phi(q, alpha) = 0 from q (N, n); returns (q, residual (N,))."""
        q = q.copy()
        for _ in range(maxiter):
            F, J = self.equations(q, alpha)
            step = self._lin_solve(J, -F)
            q += step
            if np.abs(step).max() <= tol * self.scale:
                break
        F, _ = self.equations(q, alpha)
        return q, np.abs(F).max(axis=1)

    # ------------------------------------------------------------------ continuation
    def cover(self, lo, hi):
        """Extend the continuation table to cover [lo, hi] (rad), following the assembly
        branch of the model's geometry. Raises if the linkage locks up (toggle) first."""
        for direction, target in ((1, hi), (-1, lo)):
            while (self._A[-1] < target) if direction > 0 else (self._A[0] > target):
                end = -1 if direction > 0 else 0
                a0, q0, dq0 = self._A[end], self._Q[end], self._dQ[end]
                h = direction * self.STEP
                a1 = a0 + h
                q1, res = self.newton((q0 + h * dq0)[None], np.array([a1]))
                dq1, _, J = self._derivatives(q1, np.array([a1]))
                cond = np.linalg.cond(J[0]) if self.square else 0.0
                jump = np.abs(q1[0] - q0 - h * dq0).max()
                if not np.isfinite(res[0]) or res[0] > 1e-10 * self.scale or \
                        cond > 1e10 or jump > 0.25 * self.scale * self.STEP:
                    self.limits[0 if direction < 0 else 1] = float(a0)
                    raise AnalysisError(
                        f"the linkage cannot follow the boom beyond alpha = "
                        f"{np.degrees(a0):.2f} deg (it locks or leaves its branch there); "
                        f"asked for {np.degrees(target):.2f} deg")
                if direction > 0:
                    self._A = np.append(self._A, a1)
                    self._Q = np.vstack([self._Q, q1])
                    self._dQ = np.vstack([self._dQ, dq1])
                else:
                    self._A = np.insert(self._A, 0, a1)
                    self._Q = np.vstack([q1, self._Q])
                    self._dQ = np.vstack([dq1, self._dQ])

    def state(self, alpha):
        """Poses and transfer functions at the angles alpha (any shape -> flattened)."""
        alpha = np.atleast_1d(np.asarray(alpha, dtype=float)).ravel()
        self.cover(alpha.min(), alpha.max())
        k = np.clip(np.searchsorted(self._A, alpha), 1, len(self._A) - 1)
        k = np.where(np.abs(self._A[k - 1] - alpha) < np.abs(self._A[k] - alpha), k - 1, k) \
            if len(self._A) > 1 else np.zeros(len(alpha), dtype=int)
        guess = self._Q[k] + (alpha - self._A[k])[:, None] * self._dQ[k]
        q, res = self.newton(guess, alpha)
        if np.any(res > 1e-10 * self.scale):
            raise AnalysisError(f"Newton did not close the linkage (residual "
                                f"{res.max():.3g}) at alpha = "
                                f"{np.degrees(alpha[np.argmax(res)]):.3f} deg")
        dq, ddq, _ = self._derivatives(q, alpha)
        return KinState(self, alpha, q, dq, ddq, res)
