"""An operation scene built in Exudyn (an independent multibody program; optional:
``pip install 'cranefe[peers]'``), for `cranefe study operations` (docs/operations.md,
"Comparison with Exudyn").

What is taken from cranefe: the loaded model (node coordinates, point masses, ropes' spans,
falls, EA, psi, drums, joints) and the scene's drive profiles (their s(t), as functions of
time). What is Exudyn's or computed here independently of the engine: the static rope
tensions (equilibrium of the point masses), the motion of the bodies (own composition of
hinge rotations and slider translations along the joint tree), the equations of motion
(Exudyn's mass points, spring-damper connectors and coordinate constraints) and their time
integration (Exudyn's implicit generalised-alpha at a fixed step, spectral radius 1: no
numerical damping, as the engine's trapezoidal rule).

The model:
- every point mass not on a body: an Exudyn mass point under gravity;
- every rope span that ends at a point mass: a spring-damper connector between the two
  ends, whose force is a user function of the span's length l and rate l': the rope's
  length `L = f l + L_k(t) + extra` (f falls of this span; L_k the spans between nodes
  moved by the drives, from their prescribed motion), unstretched length
  `L0(t) = L0_ref - sum R theta(t) / lambda_ref` (drums with a prescribed profile;
  lambda_ref = exp(S0 / EA), S0 the static tension), the Hencky law
  `S = EA ln(L / L0)` for L > L0, else 0 (tension only), a dashpot `b e'` with
  `e' = f l' + L_k'(t) + sum R omega(t)` and `b = psi c / (2 pi w)`, c = EA / L, with
  the engine's frequency w = w0 sqrt(c / c0) (w0 picked at rest, docs/operations.md
  "Damping": `b = beta sqrt(c)`, beta from cranefe's Mechanism, so the peer integrates
  the same equations); the connector's force is f (S + b e');
- a node moved by a drive that a rope span ends at: an Exudyn mass point whose three
  coordinates follow the prescribed motion by coordinate constraints to the ground, their
  offsets set before each step (a pre-step user function) to the position at the step's
  end.
A rope may have at most one span touching each point mass (the bundled scenes), so each
connector's force is a function of its own span and time only.
"""

import math
import time

import numpy as np

# Exudyn's Newton settings: its default relative tolerance, modified Newton, and the
# connectors' Jacobian as Exudyn forms it (its numerical differentiation of connectors off,
# its default): an approximate Jacobian changes how fast Newton converges, not where to
NEWTON_RTOL = 1e-8
MODIFIED = True
NUMDIFF = False


def motion_arrays(motion, t):
    """(s, s', s'') of a piecewise constant-jerk profile (its segment table) at the
    times t, vectorised: s = s_k + v_k tau + a_k tau^2/2 + j_k tau^3/6 on segment k,
    resting (or moving at the first speed) before the first time, at the last speed
    after the last."""
    t = np.asarray(t, float)
    tt = motion.t
    k = np.clip(np.searchsorted(tt, t, side="right") - 1, 0, len(tt) - 1)
    tau = t - tt[k]
    last = k == len(tt) - 1
    a = np.where(last, 0.0, motion.a[k])
    j = np.where(last, 0.0, motion.j[k])
    s = motion.s[k] + motion.v[k] * tau + a * tau**2 / 2 + j * tau**3 / 6
    v = motion.v[k] + a * tau + j * tau**2 / 2
    acc = a + j * tau
    before = t < tt[0]
    v0 = motion.v[0]
    return (np.where(before, v0 * t, s), np.where(before, v0, v),
            np.where(before, 0.0, acc))


class Kinematics:
    """Positions and velocities of the nodes carried by bodies (or the ground), for
    arrays of times: each body's motion X -> R X + p composed from its joint's prescribed
    motion (hinge: Rodrigues' rotation by phi(t) about its axis through its point, dR/dt =
    phi' [n]x R; slider: translation s(t) along its axis) and then its parent's:
    R = R_p R_j, p = R_p p_j + p_p (and their time derivatives by the product rule)."""

    def __init__(self, model, spec):
        self.model = model
        self.joint_of = {}                    # body -> (parent body, joint index)
        for k, j in enumerate(model.joints):
            a, b = j.bodies
            self.joint_of[b] = (a, k)         # bodies[1] moves relative to bodies[0]
        self.drive = {d.index: d.motion for d in spec.drives if d.target != "drum"}
        depth = {}

        def level(b):
            if b < 0:
                return 0
            if b not in depth:
                depth[b] = level(self.joint_of[b][0]) + 1
            return depth[b]
        self.carrier = {int(i): -1 for i in model.ground}
        for bi, body in enumerate(model.bodies):
            for i in body.nodes:
                i = int(i)
                if i not in self.carrier or level(bi) > level(self.carrier[i]):
                    self.carrier[i] = bi

    def _body(self, b, t, memo):
        """(R, dR, p, dp) of body b at the times t: (nt, 3, 3) and (nt, 3)."""
        if b in memo:
            return memo[b]
        nt = len(t)
        if b < 0:
            out = (np.broadcast_to(np.eye(3), (nt, 3, 3)), np.zeros((nt, 3, 3)),
                   np.zeros((nt, 3)), np.zeros((nt, 3)))
            memo[b] = out
            return out
        parent, k = self.joint_of[b]
        Rp, dRp, pp, dpp = self._body(parent, t, memo)
        j = self.model.joints[k]
        motion = self.drive.get(k)
        Rj, dRj = np.broadcast_to(np.eye(3), (nt, 3, 3)), np.zeros((nt, 3, 3))
        pj, dpj = np.zeros((nt, 3)), np.zeros((nt, 3))
        if motion is not None:
            s, ds, _ = motion_arrays(motion, t)
            n = np.asarray(j.axis, float) / np.linalg.norm(j.axis)
            if j.type == "hinge":
                K = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
                Rj = np.eye(3) + np.sin(s)[:, None, None] * K + \
                    (1 - np.cos(s))[:, None, None] * (K @ K)
                dRj = ds[:, None, None] * (K @ Rj)
                a = np.asarray(self.model.coords[j.at], float)
                pj, dpj = a - Rj @ a, -dRj @ a
            elif j.type == "slider":
                pj, dpj = s[:, None] * n, ds[:, None] * n
        R = Rp @ Rj
        dR = dRp @ Rj + Rp @ dRj
        p = np.einsum("nij,nj->ni", Rp, pj) + pp
        dp = np.einsum("nij,nj->ni", dRp, pj) + np.einsum("nij,nj->ni", Rp, dpj) + dpp
        memo[b] = (R, dR, p, dp)
        return memo[b]

    def nodes(self, idx, t):
        """Positions and velocities {node: ((nt, 3), (nt, 3))} at the times t."""
        t = np.atleast_1d(np.asarray(t, float))
        memo, out = {}, {}
        for i in idx:
            R, dR, p, dp = self._body(self.carrier[i], t, memo)
            X = np.asarray(self.model.coords[i], float)
            out[i] = (R @ X + p, dR @ X + dp)
        return out


def _static_tensions(model, free, spans):
    """Rope tensions S0 that hold every point mass at rest in the model's geometry
    (least squares over the masses' equilibria; the geometry must be one)."""
    X, g = np.asarray(model.coords, float), np.asarray(model.gravity, float)
    mass = dict(zip(model.masses.nodes.tolist(), model.masses.mass.tolist()))
    row = {i: k for k, i in enumerate(free)}
    A = np.zeros((3 * len(free), len(model.ropes)))
    rhs = np.zeros(3 * len(free))
    for rope, a, b, f in spans:
        e = (X[b] - X[a]) / np.linalg.norm(X[b] - X[a])
        for n, sign in ((a, 1.0), (b, -1.0)):     # S f pulls a towards b, b towards a
            if n in row:
                A[3 * row[n]:3 * row[n] + 3, rope] += sign * f * e
    for n in free:
        rhs[3 * row[n]:3 * row[n] + 3] = -mass[n] * g
    S = np.linalg.lstsq(A, rhs, rcond=None)[0]
    if np.abs(A @ S - rhs).max() > 1e-9 * np.abs(rhs).max():
        raise ValueError("the peer model is not in static equilibrium with rope tensions")
    return S


def simulate(model, spec, step, output_times):
    """Run the scene in Exudyn at a fixed `step` (s).

    Returns a dict: times (every step), positions {NODE: (nt, 3)} of the point masses,
    rope_force {ROPE: (nt,)} (S + dashpot, per fall), sway_deg {NODE: (nt,)} (angle of the
    span above the mass from the vertical), samples at `output_times` (index into the
    step times), peak rope forces over the steps, the wall time of the integration
    (wall_s) and of the setup (setup_s: the model and the tables of the prescribed
    motions), and the CPU time of both (cpu_s).

    Length: the whole peer model (masses, drives, ropes with their user functions,
    sensors, solver settings) in one piece, so that it reads as one Exudyn script.
    """
    import exudyn as exu
    from exudyn.itemInterface import (CoordinateConstraint, MarkerNodeCoordinate,
                                      MarkerNodePosition, MassPoint, NodePoint,
                                      NodePointGround, ObjectConnectorSpringDamper,
                                      SensorNode, SensorObject)
    t_start, c_start = time.perf_counter(), time.process_time()
    names = model.node_names
    X0 = np.asarray(model.coords, float)
    g = np.asarray(model.gravity, float)
    kin = Kinematics(model, spec)
    mass = dict(zip(model.masses.nodes.tolist(), model.masses.mass.tolist()))
    free = [i for i in sorted(mass) if i not in kin.carrier]
    freeset = set(free)
    spans = [(k, int(a), int(b), float(f)) for k, r in enumerate(model.ropes)
             for a, b, f in zip(r.span_a, r.span_b, r.falls)]
    active = sorted({k for k, a, b, f in spans if a in freeset or b in freeset})
    S0 = _static_tensions(model, free, [s for s in spans if s[0] in active])
    drum_motion = {d.index: d.motion for d in spec.drives if d.target == "drum"}
    for d in spec.drives:
        if d.kind != "profile":
            raise NotImplementedError("the Exudyn peer drives profiles only")
    if model.effects.damping not in ("none", "exact"):
        raise NotImplementedError("the Exudyn peer has damping none or exact")
    damped = model.effects.damping == "exact"
    beta = {}
    if damped:
        # the engine's dashpot law b = beta sqrt(c), with its frequencies picked at rest
        # (Mechanism._dashpot_frequencies): the peer compares the integration, not rules
        from ..analysis.operation.mechanism import Mechanism
        mech = Mechanism(model, spec)
        beta = dict(zip(mech.ropes.tolist(), mech.beta.tolist()))

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    node = {}
    for i in free:
        n = mbs.AddNode(NodePoint(referenceCoordinates=list(X0[i])))
        mbs.AddObject(MassPoint(mass=mass[i], nodeNumber=n))
        mbs.AddLoad(_gravity(mbs, n, mass[i] * g))
        node[i] = n
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0]))
    mground = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
    T = spec.duration
    nsteps = int(round(T / step))
    step = T / nsteps
    grid = np.arange(nsteps + 1) * step
    kinematic = sorted({n for k, a, b, f in spans if k in active for n in (a, b)} - freeset)

    def table(t):
        """What the user functions read at the times t: positions of the driven nodes and,
        per rope, (L_k, L_k', L0, sum R omega) (module docstring)."""
        kn = kin.nodes(kinematic, t)
        ropes = {}
        for k in active:
            r = model.ropes[k]
            lk = np.zeros(len(t))
            dlk = np.zeros(len(t))
            for _, a, b, f in spans:
                if _ == k and a not in freeset and b not in freeset:
                    d = kn[b][0] - kn[a][0]
                    ln = np.linalg.norm(d, axis=1)
                    lk += f * ln
                    dlk += f * np.einsum("ni,ni->n", d, kn[b][1] - kn[a][1]) / ln
            L0 = np.full(len(t), L0_ref[k])
            Rw = np.zeros(len(t))
            for dd in r.end_drums:
                if dd in drum_motion:
                    th, om, _ = motion_arrays(drum_motion[dd], t)
                    L0 -= model.drums[dd].radius * th / lam[k]
                    Rw += model.drums[dd].radius * om
            ropes[k] = np.stack([lk, dlk, L0, Rw], axis=1)
        return {i: kn[i][0] for i in kinematic}, ropes

    lam, L0_ref = {}, {}
    for k in active:
        r = model.ropes[k]
        L_ref = sum(f * np.linalg.norm(X0[b] - X0[a]) for kk, a, b, f in spans if kk == k)
        lam[k] = np.exp(S0[k] / model.ropes[k].EA)          # static stretch
        L0_ref[k] = (L_ref + r.extra_length) / lam[k]
    pos_table, rope_table = table(grid)

    def at(t):
        """The row of the tables at t (a step time: Exudyn's generalised-alpha evaluates
        its equations at the end of each step), else computed there."""
        n = int(round(t / step))
        if 0 <= n <= nsteps and abs(grid[n] - t) <= 1e-9 * step:
            return n, None
        return None, table(np.array([t]))

    constraints = []
    for i in kinematic:
        n = mbs.AddNode(NodePoint(referenceCoordinates=list(X0[i])))
        mbs.AddObject(MassPoint(mass=1.0, nodeNumber=n))
        node[i] = n
        for c in range(3):
            mc = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n, coordinate=c))
            o = mbs.AddObject(CoordinateConstraint(markerNumbers=[mground, mc], offset=0.0))
            constraints.append([o, pos_table[i][:, c] - X0[i][c], 0.0])

    def prescribe(mbs_, t):
        """Before each step (t: the step's end): the driven coordinates' offsets."""
        n = int(round(t / step))
        for cons in constraints:
            o, values, last = cons
            x = values[min(n, nsteps)] if abs(grid[min(n, nsteps)] - t) <= 1e-9 * step \
                else np.interp(t, grid, values)
            if x != last:
                mbs_.SetObjectParameter(o, "offset", x)
                cons[2] = x
        return True

    mbs.SetPreStepUserFunction(prescribe)
    connectors = []
    for k in active:
        r = model.ropes[k]
        load = [s for s in spans if s[0] == k and (s[1] in freeset or s[2] in freeset)]
        touched = [n for s in load for n in (s[1], s[2]) if n in freeset]
        if len(touched) != len(set(touched)):
            raise NotImplementedError(f"rope {r.name}: two spans at one point mass")
        for _, a, b, f in load:
            def force(mbs_, t, item, l, dl, stiffness, damping, f0, f=f, k=k,
                      EA=r.EA, bk=beta.get(k, 0.0), extra=r.extra_length):
                n, tab = at(t)
                lk, dlk, L0, Rw = rope_table[k][n] if tab is None else tab[1][k][0]
                L = f * l + lk + extra
                if L <= L0:
                    return 0.0                       # slack: no force, no dashpot
                S = EA * math.log(L / L0)            # Hencky
                if damped:
                    # b = beta sqrt(c), c = EA / L (docs/operations.md "Damping")
                    S += bk * math.sqrt(EA / L) * (f * dl + dlk + Rw)
                return f * S

            ma = mbs.AddMarker(MarkerNodePosition(nodeNumber=node[a]))
            mb = mbs.AddMarker(MarkerNodePosition(nodeNumber=node[b]))
            o = mbs.AddObject(ObjectConnectorSpringDamper(
                markerNumbers=[ma, mb], referenceLength=0.0, stiffness=0.0, damping=0.0,
                springForceUserFunction=force))
            connectors.append((r.name, f, o))
    sensors = {}
    for i in free:
        sensors[names[i]] = mbs.AddSensor(SensorNode(
            nodeNumber=node[i], outputVariableType=exu.OutputVariableType.Position,
            storeInternal=True, writeToFile=False))
    for i in node:
        if i not in freeset:
            sensors[names[i]] = mbs.AddSensor(SensorNode(
                nodeNumber=node[i], outputVariableType=exu.OutputVariableType.Position,
                storeInternal=True, writeToFile=False))
    force_sensors = [(rn, f, mbs.AddSensor(SensorObject(
        objectNumber=o, outputVariableType=exu.OutputVariableType.Force,
        storeInternal=True, writeToFile=False))) for rn, f, o in connectors]
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ti = ss.timeIntegration
    ti.numberOfSteps = nsteps
    ti.endTime = T
    ti.generalizedAlpha.spectralRadius = 1.0        # no numerical damping
    ti.adaptiveStep = False
    ti.verboseMode = 0
    ti.newton.relativeTolerance = NEWTON_RTOL
    ti.newton.useModifiedNewton = MODIFIED
    ti.newton.numericalDifferentiation.forODE2Connectors = NUMDIFF
    ss.solution.file.write = False
    ss.solution.sensors.writePeriod = step
    ss.show.statistics = False
    ss.show.computationTime = False
    ss.show.globalTimers = False
    t_setup = time.perf_counter()
    mbs.SolveDynamic(ss, showHints=True)
    t_end, c_end = time.perf_counter(), time.process_time()
    data = {n: mbs.GetSensorStoredData(s) for n, s in sensors.items()}
    times = data[names[free[0]]][:, 0]
    pos = {n: d[:, 1:4] for n, d in data.items()}
    forces = {}
    for rn, f, s in force_sensors:
        # the connector's force vector: its length is f (S + b e'); per fall / f
        forces.setdefault(rn, np.linalg.norm(mbs.GetSensorStoredData(s)[:, 1:4],
                                             axis=1) / f)
    up = -g / np.linalg.norm(g)
    sway = {}
    for i in free:
        above = _above(model, i, spans, freeset)
        d = (pos[names[above]] if above in node else
             kin.nodes([above], times)[above][0]) - pos[names[i]]
        c = d @ up / np.linalg.norm(d, axis=1)
        sway[names[i]] = np.degrees(np.arccos(np.clip(c, -1.0, 1.0)))
    idx = np.clip(np.searchsorted(times, np.asarray(output_times) - 1e-9 * step), 0,
                  len(times) - 1)
    return {"times": times, "positions": {names[i]: pos[names[i]] for i in free},
            "rope_force": forces, "sway_deg": sway, "samples": idx,
            "rope_force_max": {rn: float(v.max()) for rn, v in forces.items()},
            "rope_force_static": {model.ropes[k].name: float(S0[k]) for k in active},
            "steps": ti.numberOfSteps, "wall_s": t_end - t_setup,
            "setup_s": t_setup - t_start, "cpu_s": c_end - c_start}


def _gravity(mbs, n, F):
    from exudyn.itemInterface import Force, MarkerNodePosition
    m = mbs.AddMarker(MarkerNodePosition(nodeNumber=n))
    return Force(markerNumber=m, loadVector=list(F))


def _above(model, i, spans, free):
    """The node a point mass hangs from: the other end of its span pointing most nearly
    against gravity."""
    X, g = np.asarray(model.coords, float), np.asarray(model.gravity, float)
    best, score = None, -np.inf
    for _, a, b, f in spans:
        if i in (a, b):
            o = b if a == i else a
            d = X[o] - X[i]
            s = -(d @ g) / np.linalg.norm(d)
            if s > score:
                best, score = o, s
    return best
