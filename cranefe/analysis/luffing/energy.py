"""Reduced inertia J(alpha), potential energy, drive ratio and jib-tip motion of a linkage.

With T = 1/2 J(alpha) alpha'^2 the kinetic energy of the links and of the drive's rotor:

- complete:  J = sum_k [m_k |dX_k/dalpha|^2 + I_k (dtheta_k/dalpha)^2]
             + J_rotor (i/R)^2 (ds/dalpha)^2,
  X_k the centre of mass of each body (and each point mass carried by a body), I_k its
  inertia about it, s the length of the drive (motor angle = i s / R, eq. 14);
- paper (Loveikin et al. (2013) eq. 3): each link turns "about its own axis": a link
  hinged to the ground with its inertia about that hinge, any other (the jib, the rod)
  with its inertia about its own centre of gravity and no translation.

For links hinged to the ground the two agree exactly; they differ by the translational
energy of the coupler links (the jib). dJ/dalpha follows from the second transfer
functions: dJ = sum 2 m dX.ddX + 2 I dtheta ddtheta + 2 J_rotor (i/R)^2 s' s''.
"""

from dataclasses import dataclass

import numpy as np

from ...model import GROUND

QUANTITIES = ("J", "dJ", "Jp", "dJp", "V", "dV", "s", "ds", "dds",
              "x", "dx", "ddx", "z", "dz", "ddz")


@dataclass(frozen=True)
class MassItem:
    body: int           # model body index
    offset: np.ndarray  # (2,) from the body's reference point, model geometry
    mass: float
    inertia: float      # about its own centre, about y


class Reduced:
    """Everything the luffing analysis needs as functions of the boom angle.

    Parameters
    ----------
    linkage : Linkage
    drive : LinearDrive (nodes A, C; gear_ratio i, pinion_radius R, rotor_inertia)
    jib_tip : int, node index of the jib tip (the load hangs from it)
    """

    def __init__(self, linkage, drive, jib_tip):
        self.linkage = linkage
        self.drive = drive
        self.jib_tip = jib_tip
        model = linkage.model
        g = model.gravity
        self.g = np.array([g[0], g[2]])
        self.ratio = drive.gear_ratio / drive.pinion_radius       # motor rad per m
        items = []
        for b in linkage.bodies:
            body = model.bodies[b]
            if body.mass > 0:
                items.append(MassItem(b, np.zeros(2), body.mass, float(body.inertia[1, 1])))
        pm = model.masses
        for node, m, inertia in zip(pm.nodes, pm.mass, pm.inertia):
            b = linkage.carrier(int(node))
            if b is not None and b != GROUND:
                items.append(MassItem(b, np.array([model.coords[node][0],
                                                   model.coords[node][2]])
                                      - linkage.ref[linkage.local[b]], float(m),
                                      float(inertia[1, 1])))
        self.items = tuple(items)
        self.own_inertia = self._own_axis()

    def _own_axis(self):
        """Inertia of each body about its own axis (eq. 3): about its hinge to the ground,
        or about its centre of gravity (rotation only) if it has none."""
        lk, model = self.linkage, self.linkage.model
        out = {}
        for b in lk.bodies:
            its = [it for it in self.items if it.body == b]
            if not its:
                continue
            hinge = next((j.at for j in lk.joints if GROUND in j.bodies and b in j.bodies
                          and j.type in ("hinge", "ball")), None)
            if hinge is not None:
                c = np.array([model.coords[hinge][0], model.coords[hinge][2]]) \
                    - lk.ref[lk.local[b]]
            else:
                m = sum(it.mass for it in its)
                c = sum(it.mass * it.offset for it in its) / m
            out[b] = sum(it.inertia + it.mass * float(np.sum((it.offset - c) ** 2))
                         for it in its)
        return out

    def evaluate(self, alpha):
        """dict of (N,) arrays (QUANTITIES) at the angles alpha, from the kinematics."""
        st = self.linkage.state(alpha)
        N = len(st.alpha)
        J, dJ, V, dV = (np.zeros(N) for _ in range(4))
        for it in self.items:
            X, dX, ddX = st.body_point(it.body, it.offset)
            _, w, dw = st.angle(it.body)
            J += it.mass * np.sum(dX**2, axis=1) + it.inertia * w**2
            dJ += 2 * (it.mass * np.sum(dX * ddX, axis=1) + it.inertia * w * dw)
            V -= it.mass * X @ self.g
            dV -= it.mass * dX @ self.g
        Jp, dJp = np.zeros(N), np.zeros(N)
        for b, I in self.own_inertia.items():
            _, w, dw = st.angle(b)
            Jp += I * w**2
            dJp += 2 * I * w * dw
        s, ds, dds = self.drive_length(st)
        rotor = self.drive.rotor_inertia * self.ratio**2
        for a, da in ((J, dJ), (Jp, dJp)):
            a += rotor * ds**2
            da += 2 * rotor * ds * dds
        X, dX, ddX = st.point(self.jib_tip)
        return {"J": J, "dJ": dJ, "Jp": Jp, "dJp": dJp, "V": V, "dV": dV,
                "s": s, "ds": ds, "dds": dds,
                "x": X[:, 0], "dx": dX[:, 0], "ddx": ddX[:, 0],
                "z": X[:, 1], "dz": dX[:, 1], "ddz": ddX[:, 1]}

    def drive_length(self, st):
        """Length s of the linear drive and ds/dalpha, d2s/dalpha2 (N,) each."""
        a, c = self.drive.nodes
        Xa, dXa, ddXa = st.point(a)
        Xc, dXc, ddXc = st.point(c)
        d, dd, ddd = Xc - Xa, dXc - dXa, ddXc - ddXa
        s = np.linalg.norm(d, axis=1)
        e = d / s[:, None]
        ds = np.sum(e * dd, axis=1)
        dds = np.sum(e * ddd, axis=1) + (np.sum(dd**2, axis=1) - ds**2) / s
        return s, ds, dds


class Proxy:
    """Chebyshev interpolants of the reduced quantities on [lo, hi] (rad).

    The quantities are analytic in alpha away from toggle positions, so the interpolants
    converge geometrically; the degree doubles from 32 until every quantity's last
    coefficients fall below ``tol`` times its largest value (``self.tail`` records it).
    """

    def __init__(self, reduced, lo, hi, tol=1e-13, max_points=513):
        from numpy.polynomial import chebyshev as C
        self.lo, self.hi = float(lo), float(hi)
        self.evaluations = 0
        n = 33
        while True:
            x = np.cos(np.pi * (np.arange(n) + 0.5) / n)           # Chebyshev points
            vals = reduced.evaluate(self._from_unit(x))
            self.evaluations += n
            vals["sqrtJ"] = np.sqrt(vals["J"])
            vals["sqrtJp"] = np.sqrt(vals["Jp"])
            V = C.chebvander(x, n - 1)
            coef = {k: np.linalg.solve(V, v) for k, v in vals.items()}
            tail = max(np.abs(c[-4:]).max() / max(np.abs(vals[k]).max(), 1e-300)
                       for k, c in coef.items())
            if tail < tol or n >= max_points:
                break
            n = 2 * n - 1
        self.coef, self.tail, self.degree = coef, float(tail), n - 1
        self._C = C

    def _from_unit(self, x):
        return 0.5 * (self.hi + self.lo) + 0.5 * (self.hi - self.lo) * x

    def _to_unit(self, a):
        return (2 * np.asarray(a, dtype=float) - self.hi - self.lo) / (self.hi - self.lo)

    def __call__(self, name, alpha):
        return self._C.chebval(self._to_unit(alpha), self.coef[name])

    def derivative(self, name, alpha):
        c = self._C.chebder(self.coef[name]) * 2 / (self.hi - self.lo)
        return self._C.chebval(self._to_unit(alpha), c)

    def antiderivative(self, name, alpha, start):
        """int_start^alpha of the quantity."""
        c = self._C.chebint(self.coef[name]) * (self.hi - self.lo) / 2
        return (self._C.chebval(self._to_unit(alpha), c)
                - self._C.chebval(self._to_unit(start), c))

    def f(self, alpha, which="complete"):
        """f = J'/(2J) of eq. 22 (complete inertia, or the paper's eq. 3)."""
        j = "J" if which == "complete" else "Jp"
        return 0.5 * self("d" + j, alpha) / self(j, alpha)
