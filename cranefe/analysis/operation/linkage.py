"""Luffing by a linear drive in an operation scene: the closed linkage moved by a cylinder
or rack whose length follows a profile (docs/operations.md, "Luffing by a linear drive").

The linkage is the luffing analysis' (cranefe/analysis/luffing/kinematics.py): the
bodies joined to the ground, planar, one degree of freedom parametrised by the angle
alpha of the boom (pivot -> tip), with the poses q(alpha) and their derivatives
q'(alpha), q''(alpha) from Newton and implicit differentiation. The drive's length
d(alpha) = |X_C - X_A| must equal d_ref + s(t); alpha is found by Newton on that scalar
equation (d' = e . (X_C' - X_A')), then

    alpha' = s' / d',    alpha'' = (s'' - d'' alpha'^2) / d',
    d'' = e . (X_C'' - X_A'') + (|X_C' - X_A'|^2 - d'^2) / d,

and every body's motion X -> R X + p with its time derivatives follows from its pose
(x, z, theta): R = Rot(theta) (x turning toward z), p = (x, z) - R c_ref.
"""

import numpy as np

from ...errors import AnalysisError, ModelError
from ...model.model import GROUND
from ..luffing.kinematics import KinState, Linkage

NEWTON_MAX = 30
# the Taylor start from the last pose only this near it (rad): farther, Newton from it can
# close the loops on the linkage's other assembly or a turn off by 2 pi, so the pose comes
# from the analysis' continuation table, which follows the model's branch
TAYLOR_REACH = 4 * Linkage.STEP
# the largest change of alpha per Newton step on the drive's length (rad): a whole long
# stroke in one step can leave the angles the linkage reaches although the answer exists
ALPHA_STEP = 0.1


def _rot3(th):
    """Rotation in the x-z plane by theta, x turning toward z, and its first and second
    derivatives by theta."""
    c, s = np.cos(th), np.sin(th)
    R = np.array([[c, 0, -s], [0, 1.0, 0], [s, 0, c]])
    dR = np.array([[-s, 0, -c], [0, 0.0, 0], [c, 0, -s]])
    ddR = np.array([[-c, 0, s], [0, 0.0, 0], [-s, 0, -c]])
    return R, dR, ddR


class LinkageDrive:
    def __init__(self, model, drive, driven_joints):
        file = model.scene_file or model.file
        self.model, self.drive = model, drive
        if not model.planar:
            raise ModelError("luffing by a linear drive needs a planar model (plane: xz) "
                             "in this version", file, drive.entry)
        ld = model.linear_drives[drive.index]
        self.A, self.C = ld.nodes
        # the boom: a body hinged to the ground, preferably the one carrying the drive
        hinges = [j for j in model.joints if j.type == "hinge" and GROUND in j.bodies]
        if not hinges:
            raise ModelError("a linear drive luffs a boom hinged to the ground; the model "
                             "has no hinge to the ground", file, drive.entry)
        carried = {b for b, body in enumerate(model.bodies)
                   if self.A in body.nodes or self.C in body.nodes}
        j = next((h for h in hinges if set(h.bodies) & carried), hinges[0])
        boom = j.bodies[1] if j.bodies[0] == GROUND else j.bodies[0]
        nodes = model.bodies[boom].nodes
        far = max(nodes, key=lambda i: np.linalg.norm(model.coords[i] - model.coords[j.at]))
        names = model.node_names
        try:
            self.link = Linkage(model, model.bodies[boom].name, names[j.at], names[far],
                                file=file, entry=drive.entry)
        except ModelError as exc:
            raise ModelError(f"the linkage the linear drive moves: {exc.message}", file,
                             drive.entry) from None
        self.bodies = self.link.bodies
        self.joints = {k for k, jj in enumerate(model.joints)
                       if all(b == GROUND or b in self.link.local for b in jj.bodies)}
        for k, d in driven_joints.items():
            if k in self.joints:
                raise ModelError(f"drive '{d.name}' moves a joint of the linkage that the "
                                 f"linear drive '{drive.name}' luffs; drive one of them",
                                 file, d.entry)
        self.carrier = (self.link.carrier(self.A), self.link.carrier(self.C))
        if None in self.carrier:
            raise ModelError(f"linear drive '{ld.name}': its nodes must be on the linkage's "
                             "bodies or the ground", model.file, f"linear_drives.{ld.name}")
        self.d_ref = float(np.linalg.norm(model.coords[self.C] - model.coords[self.A]))
        self.scale = self.link.scale
        self._last_solution = (0.0, self.link.alpha_ref, 0.0, 0.0)
        self._key = self._last = self._pose = None

    def _state(self, t, alpha):
        """The linkage's poses and transfer functions at alpha: Newton (the luffing
        analysis' own) from the last pose carried to alpha by its Taylor series (one or
        two iterations) within TAYLOR_REACH of it, else the analysis' table; the branch
        and its locking checked by the table."""
        try:
            self.link.cover(alpha, alpha)
            if self._pose is None or abs(alpha - self._pose[0]) > TAYLOR_REACH:
                st = self.link.state([alpha])
            else:
                a0, q0, dq0, ddq0 = self._pose
                da = alpha - a0
                A = np.array([alpha])
                q, res = self.link.newton((q0 + dq0 * da + 0.5 * ddq0 * da * da)[None], A)
                if res[0] > 1e-10 * self.scale:
                    st = self.link.state([alpha])
                else:
                    dq, ddq, _ = self.link._derivatives(q, A)
                    st = KinState(self.link, A, q, dq, ddq, res)
        except AnalysisError as exc:
            raise AnalysisError(f"at t = {t:.6g} s the linear drive '{self.drive.name}' "
                                f"moves the linkage too far: {exc}; shorten the stroke; the "
                                f"results up to t = {t:.6g} s are kept") from None
        self._pose = (alpha, st.q[0], st.dq[0], st.ddq[0])
        return st

    def _points(self, st):
        """X, X', X'' (2,) of the drive's ends by alpha."""
        out = []
        q, dq, ddq = st.q, st.dq, st.ddq
        for body, node in zip(self.carrier, (self.A, self.C)):
            X, Rc = self.link._point(q, body, node)
            if body == GROUND:
                out.append((X[0], np.zeros(2), np.zeros(2)))
                continue
            i = 3 * self.link.local[body]
            perp = np.array([-Rc[0, 1], Rc[0, 0]])
            dth, ddth = dq[0, i + 2], ddq[0, i + 2]
            out.append((X[0], dq[0, i:i + 2] + perp * dth,
                        ddq[0, i:i + 2] + perp * ddth - Rc[0] * dth ** 2))
        return out

    def solve(self, t):
        """(alpha, alpha', alpha'', state) at t: the drive's length d_ref + s(t); Newton
        on alpha from the last solution carried forward by its rates (one or two poses
        per time), each step at most ALPHA_STEP and halved back toward the last pose
        the linkage reached when it overshoots the angles the linkage can take (a time
        far from the last one)."""
        s, ds, dds = self.drive.motion(t)
        target = self.d_ref + s
        t0, a0, a1, a2 = self._last_solution
        dt = t - t0
        alpha = a0 + a1 * dt + 0.5 * a2 * dt * dt
        reached = a0                        # the last solution's angle: reached
        for _ in range(NEWTON_MAX):
            try:
                st = self._state(t, alpha)
            except AnalysisError:
                alpha = 0.5 * (alpha + reached)
                continue
            reached = alpha
            (XA, dA, ddA), (XC, dC, ddC) = self._points(st)
            D = XC - XA
            d = float(np.hypot(*D))
            e = D / d
            dD = dC - dA
            d1 = float(e @ dD)
            if abs(d1) < 1e-12 * self.scale:
                raise AnalysisError(f"at t = {t:.6g} s the linear drive '{self.drive.name}' "
                                    "is at a dead point of the linkage (its length does not "
                                    "change with the boom angle); shorten the stroke")
            if abs(d - target) < 1e-13 * self.scale:
                break
            alpha -= float(np.clip((d - target) / d1, -ALPHA_STEP, ALPHA_STEP))
        else:
            raise AnalysisError(f"at t = {t:.6g} s Newton did not find the boom angle for "
                                f"the linear drive '{self.drive.name}' length {target:.6g} m:"
                                " the stroke passes a toggle or dead point of the linkage "
                                "(where the length stops changing with the boom angle) or "
                                "leaves the lengths the linkage can reach; shorten the "
                                f"stroke; the results up to t = {t:.6g} s are kept")
        ddD = ddC - ddA
        d2 = float(e @ ddD) + (float(dD @ dD) - d1 ** 2) / d
        a1 = ds / d1
        a2 = (dds - d2 * a1 ** 2) / d1
        self._last_solution = (t, alpha, a1, a2)
        return alpha, a1, a2, st

    def motions(self, t):
        """{body: (R, R', R'', p, p', p'')} of the linkage's bodies at t."""
        key = tuple(self.drive.motion(t))
        if key == self._key:
            return self._last
        alpha, a1, a2, st = self.solve(t)
        q, dq, ddq = st.q[0], st.dq[0], st.ddq[0]
        qt = dq * a1                       # time derivatives of the poses
        qtt = ddq * a1 ** 2 + dq * a2
        out = {}
        for b in self.bodies:
            i = 3 * self.link.local[b]
            R0, R1, R2 = _rot3(q[i + 2])
            w, dw = qt[i + 2], qtt[i + 2]
            R, dR, ddR = R0, R1 * w, R1 * dw + R2 * w ** 2
            c = np.array([self.link.ref[self.link.local[b]][0], 0.0,
                          self.link.ref[self.link.local[b]][1]])
            xz = lambda v: np.array([v[i], 0.0, v[i + 1]])
            out[b] = (R, dR, ddR, xz(q) - R @ c, xz(qt) - dR @ c, xz(qtt) - ddR @ c)
        self._key, self._last = key, out
        return out

    def angle(self, t):
        """The boom angle alpha (rad) at t (pivot -> tip above the horizontal)."""
        return self.solve(t)[0]

    def check_range(self, duration):
        """Before integrating: the hinges of the linkage with a range (range or
        range_deg in the model) stay in it over the profile. Each hinge's turn about its
        axis n is -(theta_child - theta_parent) n_y (theta: the poses' rotation from the
        reference, x turning toward z; a turn about +y turns x toward -z), found by
        following the drive's length through the run as the integrator does (times of
        the profile's breakpoints and 400 in between: the turn is monotonic in the
        length between dead points, whose extremes are at breakpoints or rests)."""
        ranged = [k for k in sorted(self.joints) if self.model.joints[k].type == "hinge"
                  and self.model.joints[k].range is not None]
        if not ranged:
            return
        m = self.drive.motion
        ts = np.unique(np.concatenate([np.linspace(0.0, duration, 401),
                                       m.t[(m.t >= 0) & (m.t <= duration)]]))
        turns = np.zeros((len(ts), len(ranged)))
        n = len(ts)
        try:
            for i, t in enumerate(ts):
                q = self.solve(float(t))[3].q[0]
                for c, k in enumerate(ranged):
                    j = self.model.joints[k]
                    th = [0.0 if b == GROUND else q[3 * self.link.local[b] + 2]
                          for b in j.bodies]
                    turns[i, c] = -(th[1] - th[0]) * np.sign(j.axis[1])
        except AnalysisError:           # a toggle or dead point: the run reports it
            n = i
        finally:
            self._last_solution = (0.0, self.link.alpha_ref, 0.0, 0.0)
            self._key = self._last = self._pose = None
        file = self.model.scene_file or self.model.file
        for c, k in enumerate(ranged):
            if not n:
                break
            j = self.model.joints[k]
            lo, hi = turns[:n, c].min(), turns[:n, c].max()
            if lo < j.range[0] - 1e-9 or hi > j.range[1] + 1e-9:
                f = 180 / np.pi
                raise ModelError(
                    f"the linear drive '{self.drive.name}' turns {j.label} over "
                    f"[{lo * f + 0.0:.6g}, {hi * f + 0.0:.6g}] deg within {ts[n - 1]:g} s, "
                    f"past the end of its range [{j.range[0] * f:g}, {j.range[1] * f:g}] deg "
                    f"({self.model.file}, {j.range_entry}); shorten the stroke "
                    "or extend the range", file, f"{self.drive.entry}.profile")

