"""The equations of an operation scene in its coordinates (docs/operations.md).

Coordinates q: the Cartesian positions of the point masses not carried by bodies (3 each,
2 in a plane: xz model; with `sway: false` only the height), then the positions of
joints driven by a torque, force or motor or free (the arc rho phi of a hinge, the
travel of a slider; the bodies they carry, with any joints moving below them, enter by
their exact kinetic energy: a configuration- and time-dependent block M_J of the mass
matrix, joints.JointChain), then the displacements of the elastic structure's nodes in
their body's frame (effects.structure: flexible; flexible.py), then the angles of drums
driven by a torque or a motor. A linear drive
moves its planar linkage kinematically (linkage.py). Bodies move rigidly by the prescribed joint motions
(exact rotations, `cranefe.elements.hinge_motion`); a prescribed drum's angle is a known function
of time; every other joint and drum is held. Ropes and axial springs that touch a
point mass carry force; the others only connect bodies whose motion is prescribed.

Ropes: S = EA ln(L/L0) (tension only), L through all falls at the current geometry,
L0 = L0_ref - sum R theta / lambda_ref (a drum winds R theta of rope at the static
stretch lambda_ref = L_ref / L0_ref), torque on the drum (S + S_damping) R;
L0_ref from the static tension S0 of the reference geometry, so the loads hang at rest
at t = 0.
"""

from dataclasses import dataclass

import numpy as np
from scipy.linalg import eigh

from ...errors import AnalysisError, ModelError
from ...model.model import GROUND
from ... import elements as kernels
from . import flexible
from .joints import JointChain, subtree_mass
from .linkage import LinkageDrive


@dataclass
class Eval:
    """Forces and tangents at one (t, q, v)."""

    t: float
    F: np.ndarray            # (n,) generalised force (gravity, ropes, springs, damping, drives)
    K: np.ndarray            # (n, n) -dF/dq
    C: np.ndarray            # (n, n) -dF/dv
    X: np.ndarray            # (nn, 3) node positions
    V: np.ndarray            # (nn, 3) node velocities
    L: np.ndarray            # (nr,) rope lengths
    L0: np.ndarray           # (nr,) unstretched lengths
    S: np.ndarray            # (nr,) elastic rope forces
    Sd: np.ndarray           # (nr,) damping forces (along the rope)
    edot: np.ndarray         # (nr,) elongation rate (m/s)
    N: np.ndarray            # (ns,) spring forces (elastic + damping)
    theta: np.ndarray        # (nd,) all drum angles
    omega: np.ndarray        # (nd,) all drum speeds
    drive_torque: np.ndarray  # (nd,) torque of torque/motor drives on their drums
    P_drive: float           # power fed in by the drives (W)
    P_diss: float            # power dissipated by the dashpots (W)
    P_wound: float           # elastic energy carried onto the drums with the rope (W)
    T_guided: float = 0.0    # horizontal kinetic energy of loads without sway (J)
    joint_torque: np.ndarray = None   # (nJ,) torque (N m) / force (N) of joint drives
    MJ: np.ndarray = None    # (nJ, nJ) mass matrix of the joint coordinates at (t, q)
    dMJ: np.ndarray = None   # (nJ, nJ, nJ) its derivatives dM_ij / du_k


class Mechanism:
    def __init__(self, model, spec):
        self.model, self.spec = model, spec
        self.nn = len(model.node_names)
        g = np.asarray(model.gravity, float)
        self.g = g
        gn = np.linalg.norm(g)
        self.up = -g / gn if gn > 0 else np.array([0.0, 0.0, 1.0])
        self.sway = model.effects.sway
        self.warnings = []
        self.left_at = None          # a breakpoint approached from the left (joint_motions)
        if model.effects.rope_mass:
            self.warnings.append("rope_mass is not used by operation scenes yet: ropes are "
                                 "massless")
        self.warnings += spec.late_drives()
        self._tree(model)
        self._nodes(model)
        self._joint_setup(model)
        self._elements(model)
        self._drums(model)
        self._projections()
        self._chain_setup(model)
        self._joint_mass()
        self._static(model)
        self.inextensible = not model.effects.rope_elasticity
        if self.inextensible:
            self._inextensible(model)
        if self.flex is not None:        # the static state with the elastic structure
            self.flex.settle(self)
        self._dashpot_frequencies()

    # ----------------------------------------------------------------- kinematics
    def _tree(self, model):
        """Spanning tree of bodies from the ground over the joints; a driven joint must
        be a tree joint whose loop (if any) is closed only by held joints of static
        bodies."""
        driven = {d.index: d for d in self.spec.drives if d.target in ("hinge", "slider")}
        linear = [d for d in self.spec.drives if d.target == "linear"]
        self.linear = LinkageDrive(model, linear[0], driven) if linear else None
        if self.linear is not None:
            self.linear.check_range(self.spec.duration)
        parent = {}
        order = []
        frontier = [GROUND]
        used = set()
        while frontier:
            b = frontier.pop(0)
            for k, j in enumerate(model.joints):
                if k in used or b not in j.bodies:
                    continue
                other = j.bodies[1] if j.bodies[0] == b else j.bodies[0]
                if other == GROUND or other in parent:
                    continue
                used.add(k)
                parent[other] = (b, k)
                order.append(other)
                frontier.append(other)
        self.parent, self.order = parent, order
        moving = set()
        for b in order:
            p, k = parent[b]
            if k in driven or p in moving:
                moving.add(b)
        if self.linear is not None:
            moving |= set(self.linear.bodies)
        for k, j in enumerate(model.joints):
            if k in used or (self.linear is not None and k in self.linear.joints):
                continue
            if any(b in moving for b in j.bodies if b != GROUND):
                raise ModelError(
                    f"{j.label} closes a loop of bodies that the drives move; closed "
                    "linkages are not solved by operation scenes yet (drive a joint "
                    "outside the loop)", model.scene_file or model.file,
                    driven[next(iter(driven))].entry if driven else None)
        for k, d in driven.items():
            if k not in used:
                raise ModelError(f"{model.joints[k].label} closes a loop of bodies: "
                                 "driving it is not supported", model.scene_file, d.entry)
        self.driven_joints = driven

    def poses(self, t, joints):
        """(every body's motion (R, dR, ddR, p, dp, ddp), the positions X (nn, 3) of the
        nodes the bodies carry) at t, the joint coordinates at `joints` (drive name ->
        (position, speed), as a result reports them; their accelerations taken 0: poses
        and velocities only), the profiles' joints as they prescribe; the nodes of an
        elastic structure (flexible.py) with their frame, without their deflection."""
        states = [(*joints[d.name], 0.0) if d.coordinate else d.motion(t)
                  for d in self._chain_drives]
        mot = self.body_motions(t, states)
        X = np.zeros((self.nn, 3))
        for b, idx, Xr in self._groups:
            R, p = mot[b][0], mot[b][3]
            X[idx] = Xr @ R.T + p
        if self.flex is not None:           # elastic nodes: with their frame, undeflected
            for f, k in self.flex.frames:
                idx = np.array([i for i in self.flex.en[k] if i < self.nn], dtype=int)
                R, p = mot[f][0], mot[f][3]           # (the ground: f = GROUND)
                X[idx] = self.model.coords[idx] @ R.T + p
        return mot, X

    def body_motions(self, t, states=None):
        """(R, dR, ddR, p, dp, ddp) of every body at t (ground: identity); `states`:
        the driven joints' (s, s', s'') at t in the order of the chain, if known."""
        out = {GROUND: kernels.IDENTITY_MOTION}
        if states is None:
            states = [self._rest if d.coordinate else d.motion(t)
                      for d in self._chain_drives]
        c = 0
        link = self.linear.motions(t) if self.linear is not None else None
        for b, p, d, sign, hinge, K, K2, point, axis in self._chain:
            if link is not None and b in link:
                out[b] = link[b]
                continue
            if d is None:
                out[b] = out[p]
                continue
            s, ds, dds = states[c]
            c += 1
            s, ds, dds = sign * s, sign * ds, sign * dds
            if hinge:
                # kernels.hinge_motion with its skew matrices K, K2 made once at setup
                sn, cs = np.sin(s), np.cos(s)
                R = self._I3 + sn * K + (1 - cs) * K2
                A = cs * K + sn * K2
                dR = ds * A
                ddR = dds * A + ds**2 * (-sn * K + cs * K2)
                jm = (R, dR, ddR, point - R @ point, -dR @ point, -ddR @ point)
                # composing with the ground's identity motion changes nothing: skipped
                par = out[p]
                out[b] = jm if par is kernels.IDENTITY_MOTION else kernels.compose(par, jm)
            else:
                # kernels.compose(parent, slider_motion(axis, s, ds, dds)) without the
                # products by the slider's R = I, dR = ddR = 0 (the same numbers)
                Rp, dRp, ddRp, pp, dpp, ddpp = out[p]
                pj, dpj, ddpj = s * axis, ds * axis, dds * axis
                out[b] = (Rp, dRp, ddRp, Rp @ pj + pp, dRp @ pj + Rp @ dpj + dpp,
                          ddRp @ pj + 2 * dRp @ dpj + Rp @ ddpj + ddpp)
        return out

    def _chain_setup(self, model):
        """Constant per-body data of `body_motions` and `kinematics` (hot path)."""
        from ...elements.bodies import skew
        self._I3 = np.eye(3)
        chain = []
        for b in self.order:
            p, k = self.parent[b]
            j = model.joints[k]
            d = self.driven_joints.get(k)
            sign = 1.0 if j.bodies[1] == b else -1.0    # motion of bodies[1] rel. bodies[0]
            hinge = j.type == "hinge"
            K = skew(j.axis) if hinge else None
            chain.append((b, p, d, sign, hinge, K, None if K is None else K @ K,
                          np.asarray(model.coords[j.at], float), j.axis))
        self._chain = chain
        self._chain_drives = [c[2] for c in chain if c[2] is not None]
        self._rest = (0.0, 0.0, 0.0)
        self._kin_key = self._kin_last = None
        groups = []
        for b in [GROUND] + list(self.order):
            idx = self.kin[self.carrier[self.kin] == b]
            if len(idx):
                groups.append((b, idx, model.coords[idx]))
        self._groups = groups
        self._H = np.eye(3) - np.outer(self.up, self.up)   # horizontal projection
        self._X0_free = model.coords[self.free]
        self._X0_root = model.coords[self.root]
        self._qd = np.array(self.qdrums, dtype=int)
        self._profile_drums = [(k, d) for k, d in enumerate(self.drum_drive)
                               if d is not None and d.kind == "profile"]

    def _joint_mass(self):
        """The joint coordinates' chain (joints.JointChain: the bodies below them and
        their ancestors, the rigid sets with their mass properties, the nodes they
        carry) and the diagonal of the mass matrix at the reference state (the joint
        block M_J(u, t) is made at every evaluation: Eval.MJ)."""
        if not self.nJ:
            self.chain = None
            self.MJ_rotor = np.zeros(0)
            return
        model = self.model
        coord = {id(jc["drive"]): c for c, jc in enumerate(self.jc)}
        owner = {}                              # body -> the body whose motion it has
        for b, p, d, *_ in self._chain:
            link = self.linear is not None and b in self.linear.bodies
            owner[b] = owner.get(p, p) if (d is None and not link) else b
        under = set()
        for b, p, d, *_ in self._chain:
            if p in under or (d is not None and d.coordinate):
                under.add(b)
        need = set(under)
        for b in under:
            a = b
            while a != GROUND:
                need.add(a)
                a = self.parent[a][0]
        chain = [(b, p, d, sign, hinge, K, K2, point, axis,
                  coord.get(id(d)) if d is not None else None)
                 for b, p, d, sign, hinge, K, K2, point, axis in self._chain if b in need]
        sets, groups = [], []
        for o in sorted({owner[b] for b in under}):
            bodies = [b for b in under if owner[b] == o]
            nodes = np.array([i for i in range(self.nn) if self.carrier[i] in bodies],
                             dtype=int)
            m, s1, Th = subtree_mass(model, bodies, nodes)
            if m > 0:
                sets.append((o, m, s1, Th, None, True))
            if len(nodes):
                groups.append((o, nodes, model.coords[nodes].astype(float), None))
        # sway off: a load guided horizontally by a body the coordinates carry has its
        # horizontal inertia on them (projected by H), its height its own coordinate
        self.guided_joint = np.zeros(len(self.free), bool)
        if not self.sway:
            H = self._H
            for k, i in enumerate(self.free):
                r = int(self.root[k])
                if r < 0 or r not in self.jnodes:
                    continue
                o = owner[self.carrier[r]]
                X = np.asarray(model.coords[r], float)
                mk = float(self.free_mass[k])
                sets.append((o, mk, mk * X, mk * np.outer(X, X), H, False))
                groups.append((o, np.array([i]), X[None], H))
                self.guided_joint[k] = True
        self.chain = JointChain(chain, [jc["rho"] for jc in self.jc], sets, groups,
                                self.g, self.linear)
        self.MJ_rotor = np.array([jc["drive"].rotor_inertia * jc["drive"].gear_ratio ** 2
                                  / jc["rho"] ** 2 for jc in self.jc])
        st = self.chain.state(0.0, np.zeros(self.nJ), np.zeros(self.nJ), tangent=False)
        self.MJ = np.diag(st.M) + self.MJ_rotor
        self.M = np.concatenate([(self.E.T ** 2) @ np.repeat(self.free_mass, 3),
                                 self.MJ, self._Mu(), self.J])
        self._refuse_joint_springs(model)

    def _refuse_joint_springs(self, model):
        """An axial spring from a load or a massless block to a body that a joint
        coordinate moves: the spring's rows have the loads' columns only, so its force
        would not reach the coordinate (a load hung by it took its weight off the joint);
        refused (exit 2). Springs between bodies carry no force in operation scenes
        (what holds a joint in the linear analyses; the scene drives or holds it)."""
        for s in model.springs:
            if s.type != "axial":
                continue
            on = [i for i in s.nodes if i in self.jnodes]
            if not on or all(self.carrier[i] != -2 for i in s.nodes):
                continue
            d = [jc["drive"] for jc in self.jc if on[0] in jc["nodes"]][-1]
            raise ModelError(f"spring '{s.name}' joins a load or a massless block to body "
                             f"'{model.bodies[self.carrier[on[0]]].name}', which drive "
                             f"'{d.name}' moves as a coordinate; the spring's force on the "
                             "coordinate is not computed by operation scenes yet: hang the "
                             "load by a rope, or prescribe the joint's motion by a profile",
                             model.file, f"springs.{s.name}")

    def _Mu(self):
        """The elastic nodes' lumped masses, one per elastic coordinate."""
        return np.zeros(0) if self.flex is None else self.flex.Mu

    def _nodes(self, model):
        nn = self.nn
        depth = {GROUND: 0}
        for b in self.order:
            depth[b] = depth[self.parent[b][0]] + 1
        carrier = np.full(nn, -2)          # body index, GROUND, or -2 (not kinematic)
        for i in model.ground:
            carrier[i] = GROUND
        for bi, b in enumerate(model.bodies):
            if bi not in depth:
                continue
            for i in b.nodes:
                if carrier[i] == -2 or (carrier[i] != GROUND and depth[bi] > depth.get(
                        carrier[i], -1)):
                    carrier[i] = bi
        for k, j in enumerate(model.joints):
            if carrier[j.at] == -2:
                carrier[j.at] = j.bodies[0] if j.bodies[0] in depth else j.bodies[1]
        for bi, b in enumerate(model.bodies):
            if bi not in depth:
                raise ModelError(f"body '{b.name}' has no joint to the ground or to other "
                                 "bodies: free bodies are not solved by operation scenes "
                                 "yet", model.file, f"bodies.{b.name}")
        self.carrier = carrier
        # the elastic structure (effects.structure: flexible): member nodes no body
        # carries get coordinates in their frame (flexible.py)
        self.flex = None
        if flexible.active(model):
            fl = flexible.ElasticStructure(self, model)
            if fl.nu:
                self.flex = fl
                carrier[fl.model_nodes] = flexible.ELASTIC
        mass_of = dict(zip(model.masses.nodes.tolist(), model.masses.mass.tolist()))
        self.free = np.array([i for i in model.masses.nodes if carrier[i] == -2], dtype=int)
        self.free_mass = np.array([mass_of[i] for i in self.free])
        self.kin = np.flatnonzero(carrier != -2)
        self.mass_nodes = np.array(sorted(mass_of), dtype=int)

    def _joint_setup(self, model):
        """Joint coordinates (torque, force, motor, free joints): the child body, the
        rigid subtree it carries (bodies, nodes, mass properties) and the length scale
        rho of a hinge (its coordinate is the arc u = rho phi, in metres like the
        others; rho: the farthest point of the subtree from the axis)."""
        self.jc = []
        for b in self.order:
            k = self.parent[b][1]
            d = self.driven_joints.get(k)
            if d is None or not d.coordinate:
                continue
            j = model.joints[k]
            sub, stack = {b}, [b]
            while stack:
                x = stack.pop()
                for c in self.order:
                    if self.parent[c][0] == x and c not in sub:
                        sub.add(c)
                        stack.append(c)
            nodes = np.array([i for i in range(self.nn) if self.carrier[i] in sub],
                             dtype=int)
            m = subtree_mass(model, sorted(sub), nodes)[0]
            hinge = j.type == "hinge"
            a = np.asarray(model.coords[j.at], float)
            pts = [model.coords[i] for i in nodes] + [model.bodies[x].com for x in sub
                                                       if model.bodies[x].mass > 0]
            if hinge:
                r = [np.linalg.norm(np.cross(np.asarray(x, float) - a, j.axis))
                     for x in pts]
                rho = max(r + [0.0])
                rho = rho if rho > 1e-9 * model.length_scale else model.length_scale
            else:
                rho = 1.0
            if m <= 0:
                raise ModelError(f"drive '{d.name}' moves {j.label} as a coordinate, but "
                                 "the bodies it carries have no mass; give them mass "
                                 "(bodies.NAME.mass) or prescribe a profile",
                                 model.scene_file or model.file, d.entry)
            self.jc.append({"drive": d, "joint": k, "hinge": hinge, "nodes": nodes,
                            "rho": rho})
        self.nJ = len(self.jc)
        self.jnodes = {int(i) for c in self.jc for i in c["nodes"]}

    def _elements(self, model):
        """Ropes and axial springs that touch a point mass (the others join bodies whose
        motion is prescribed: no force is computed for them).

        Length: gathers every element kind's arrays (ropes, springs, point masses,
        drums) in the order the state vector lists them.
        """
        self._massless_nodes(model)
        free = set(self.free.tolist())
        kin = set(self.kin.tolist())
        ok = free | kin
        elastic = set() if self.flex is None else set(self.flex.model_nodes.tolist())
        act, a, b, f, rid = [], [], [], [], []
        for k, rp in enumerate(model.ropes):
            nodes = set(rp.span_a.tolist()) | set(rp.span_b.tolist())
            if not nodes & (free | self.jnodes | elastic):
                continue
            bad = nodes - ok
            if bad:
                raise ModelError(f"rope '{rp.name}' runs over the massless free node(s) "
                                 f"{', '.join(model.node_names[i] for i in sorted(bad))}; "
                                 "operation scenes need every rope node on a body, the "
                                 "ground or a point mass (massless blocks: not yet)",
                                 model.file, f"ropes.{rp.name}")
            rid += [len(act)] * len(rp.falls)
            act.append(k)
            a += rp.span_a.tolist()
            b += rp.span_b.tolist()
            f += rp.falls.tolist()
        self.ropes = np.array(act, dtype=int)
        self.span_a, self.span_b = np.array(a, dtype=int), np.array(b, dtype=int)
        self.falls = np.array(f, dtype=float)
        self.span_rope = np.array(rid, dtype=int)
        self.span_ref = np.linalg.norm(model.coords[self.span_b] - model.coords[self.span_a],
                                       axis=1) if len(b) else np.zeros(0)
        R = [model.ropes[k] for k in act]
        self.EA = np.array([r.EA for r in R])
        self.extra = np.array([r.extra_length for r in R])
        self.psi = np.array([r.psi for r in R])
        inactive = [r.name for k, r in enumerate(model.ropes) if k not in act]
        self.inactive_ropes = inactive
        sp = [(k, s) for k, s in enumerate(model.springs) if s.type == "axial"
              and set(s.nodes) & free]
        for k, s in sp:
            bad = set(s.nodes) - ok
            if bad:
                raise ModelError(f"spring '{s.name}' ends at a massless free node; not "
                                 "supported by operation scenes yet", model.file,
                                 f"springs.{s.name}")
        self.sp_a = np.array([s.nodes[0] for _, s in sp], dtype=int)
        self.sp_b = np.array([s.nodes[1] for _, s in sp], dtype=int)
        self.sp_k = np.array([s.stiffness for _, s in sp])
        self.sp_psi = np.array([s.psi for _, s in sp])
        self.sp_dref = np.linalg.norm(model.coords[self.sp_b] - model.coords[self.sp_a],
                                      axis=1) if sp else np.zeros(0)
        # coordinates of the point masses; with sway off the height only, the horizontal
        # position following the node the mass hangs from
        nf = len(self.free)
        planar = model.planar
        dirs = []          # (mass k, unit vector)
        self.hang = np.full(nf, -1)
        for k, i in enumerate(self.free):
            above = self._above(model, i)
            self.hang[k] = above
            if self.sway:
                axes = [np.array([1.0, 0, 0]), np.array([0, 0, 1.0])] if planar else \
                    list(np.eye(3))
                dirs += [(k, ax) for ax in axes]
            else:
                dx = model.coords[above] - model.coords[i]
                hor = dx - (dx @ self.up) * self.up
                if np.linalg.norm(hor) > 1e-6 * np.linalg.norm(dx):
                    raise ModelError(
                        f"with sway: false the load at node '{model.node_names[i]}' must "
                        f"hang vertically below '{model.node_names[above]}' (it is off by "
                        f"{np.linalg.norm(hor):.4g} m); move it or turn sway on",
                        model.file, f"nodes.{model.node_names[i]}")
                dirs.append((k, self.up.copy()))
        self.nc = len(dirs)                 # Cartesian coordinates of the point masses
        self.nu = 0 if self.flex is None else self.flex.nu    # elastic structure
        self.nx = self.nc + self.nJ + self.nu   # coordinates in metres (then drum angles)
        self.jb = slice(self.nc, self.nc + self.nJ)     # the joint coordinates
        E = np.zeros((3 * nf, self.nc))
        for c, (k, ax) in enumerate(dirs):
            E[3 * k:3 * k + 3, c] = ax
        self.E = E
        # coordinates of massless blocks: algebraic (equilibrium) rows
        self.qy = np.array([c for c, (k, _) in enumerate(dirs) if self.free_mass[k] == 0],
                           dtype=int)
        self.qx_ref = E.T @ model.coords[self.free].ravel()
        if self.flex is not None:
            self.flex.setup(self, model)
        # with sway off: the kinematic root each mass's horizontal position follows
        self.root = np.array([self._root(model, k) for k in range(nf)], dtype=int)

    def _massless_nodes(self, model):
        """Free nodes without mass that ropes or axial springs join to the point masses
        or to the bodies of joint coordinates (a hook block whose mass is neglected, a
        free sheave): coordinates whose position is the equilibrium of the falls and
        springs on them at every instant (docs/operations.md "Massless blocks"),
        appended to the point masses with mass 0."""
        ends = [set(rp.span_a.tolist()) | set(rp.span_b.tolist()) for rp in model.ropes]
        ends += [set(s.nodes) for s in model.springs if s.type == "axial"]
        reach = set(self.free.tolist()) | self.jnodes
        new = []
        grow = True
        while grow:
            grow = False
            for nodes in ends:
                if not nodes & reach:
                    continue
                for i in sorted(nodes - reach):
                    if self.carrier[i] == -2:
                        new.append(i)
                        reach.add(i)
                        grow = True
        if not new:
            return
        file = model.scene_file or model.file
        names = ", ".join(model.node_names[i] for i in new)
        if model.effects.damping != "none":
            raise ModelError(f"the massless node(s) {names} with damping: a dashpot on a "
                             "massless block makes its velocity a differential, not an "
                             "algebraic, unknown; not solved yet: give the block a mass "
                             "(masses) or set damping: none", file, "effects.damping")
        if not model.effects.rope_elasticity:
            raise ModelError(f"the massless node(s) {names} with inextensible ropes: not "
                             "solved yet; give the block a mass (masses) or use elastic "
                             "ropes", file, "effects.rope_elasticity")
        self.free = np.concatenate([self.free, np.array(new, dtype=int)])
        self.free_mass = np.concatenate([self.free_mass, np.zeros(len(new))])

    def _above(self, model, i):
        """The node a point mass hangs from: the other end of its highest rope span or
        axial spring (most nearly against gravity)."""
        best, score = -1, -np.inf
        ends = list(zip(self.span_a, self.span_b)) + list(zip(self.sp_a, self.sp_b))
        for a, b in ends:
            if i not in (a, b):
                continue
            o = b if a == i else a
            d = model.coords[o] - model.coords[i]
            s = d @ self.up / (np.linalg.norm(d) + 1e-300)
            if s > score:
                best, score = o, s
        if best < 0:
            raise ModelError(f"the point mass at node '{model.node_names[i]}' hangs on no "
                             "rope or axial spring; an operation scene moves masses on "
                             "ropes", model.file,
                             f"masses.{model.node_names[i]}")
        return best

    def _root(self, model, k):
        seen = set()
        i = self.free[k]
        while self.carrier[i] == -2:
            if i in seen:
                return -1
            seen.add(i)
            i = self.hang[list(self.free).index(i)]
        return i

    def _drums(self, model):
        nd = len(model.drums)
        self.nd = nd
        self.drum_drive = [None] * nd
        for d in self.spec.drives:
            if d.target == "drum":
                self.drum_drive[d.index] = d
        self.qdrums = [k for k in range(nd) if self.drum_drive[k] is not None
                       and self.drum_drive[k].kind != "profile"]
        self.n = self.nx + len(self.qdrums)
        # rope end -> drum: (active rope, drum, radius)
        ends = []
        for j, k in enumerate(self.ropes):
            for dd in model.ropes[k].end_drums:
                ends.append((j, dd, model.drums[dd].radius))
        self.rope_drum = np.array([e[0] for e in ends], dtype=int)
        self.drum_of_end = np.array([e[1] for e in ends], dtype=int)
        self.end_radius = np.array([e[2] for e in ends], dtype=float)
        # rope paid out per drum radian, all ends of all ropes on the drum (m/rad)
        self.drum_rate = np.zeros(nd)
        for r in model.ropes:
            for dd in r.end_drums:
                self.drum_rate[dd] += model.drums[dd].radius
        self.J = np.array([model.drums[k].reduced_inertia for k in self.qdrums])
        self.gear = np.array([model.drums[k].gear_ratio for k in range(nd)])
        self.M = np.concatenate([(self.E.T ** 2) @ np.repeat(self.free_mass, 3),
                                 np.zeros(self.nJ), self._Mu(), self.J])

    # ----------------------------------------------------------------- state at t
    def kinematics(self, t):
        """Positions, velocities, accelerations of kinematic nodes at t, and the
        prescribed drums' (theta, omega, alpha). The arrays are shared with the last
        call when every drive is in the same state (a crane at rest between moves):
        read them, never write."""
        states = tuple(self._rest if d.coordinate else d.motion(t)
                       for d in self._chain_drives)
        drums = tuple(d.motion(t) for _, d in self._profile_drums)
        if self.linear is not None:
            drums = drums + (self.linear.drive.motion(t),)
        key = (states, drums)
        if key == self._kin_key:
            return self._kin_last
        mot = self.body_motions(t, states)
        X = np.zeros((self.nn, 3))
        V = np.zeros((self.nn, 3))
        A = np.zeros((self.nn, 3))
        for b, idx, Xr in self._groups:
            R, dR, ddR, p, dp, ddp = mot[b]
            X[idx] = Xr @ R.T + p
            V[idx] = Xr @ dR.T + dp
            A[idx] = Xr @ ddR.T + ddp
        th = np.zeros((self.nd, 3))
        for (k, _), m in zip(self._profile_drums, drums):
            th[k] = m
        self._kin_key, self._kin_last = key, (X, V, A, th)
        return X, V, A, th

    def joint_motions(self, t, q, v, tangent=True):
        """The joint coordinates' terms at (t, q, q') (joints.JointState): their mass
        matrix M_J (with the motors' rotors), Kane's inertia and gravity forces with
        their tangents, energies, and the positions and derivatives of the nodes they
        carry. At t == `left_at` (a step ending at a breakpoint of a prescribed drive)
        the prescribed accelerations are their limits from the left."""
        jb = self.jb
        st = self.chain.state(t, q[jb], v[jb], left=(t == self.left_at),
                              tangent=tangent)
        st.M = st.M + np.diag(self.MJ_rotor)
        return st

    def _joint_spans(self, js):
        """Span-difference Jacobians over all metre coordinates D (ns, 3, nx), the second
        derivatives by the joint coordinates DJJ (ns, 3, nJ, nJ), and the nodes'
        first derivatives XJ (nn, 3, nJ) (zero off the bodies the coordinates carry)."""
        nJ = self.nJ
        XJ = np.zeros((self.nn, 3, nJ))
        XJJ = np.zeros((self.nn, 3, nJ, nJ))
        for idx, _, _, xj, xjj, _ in js.groups:
            XJ[idx] = xj
            XJJ[idx] = xjj
        DJ = XJ[self.span_b] - XJ[self.span_a]
        DJJ = XJJ[self.span_b] - XJJ[self.span_a]
        return np.concatenate([self.D, DJ], axis=2), DJJ, XJ

    def _joint_forces(self, t, q, v, js, F, K, C):
        """Add gravity, Kane's inertia terms (Coriolis, centrifugal, carried
        accelerations) and the drive of every joint coordinate to F (and their
        derivatives to K, C); return the drives' torques (N m) or forces (N)."""
        nc, jd = self.nc, self.jb
        F[jd] += js.F
        K[jd, jd] += js.K
        C[jd, jd] += js.C
        jt = np.zeros(self.nJ)
        for c, jc in enumerate(self.jc):
            i, r = nc + c, jc["rho"]
            d = jc["drive"]
            if d.kind == "torque":
                tq, dtq = d.torque(t)[0], 0.0
            elif d.kind == "motor":
                gr = d.gear_ratio
                Mm, dM = d.motor.torque(gr * v[i] / r)
                tq, dtq = gr * Mm, gr * gr * dM
            else:
                tq = dtq = 0.0
            jt[c] = tq
            F[i] += tq / r
            C[i, i] -= dtq / r ** 2
        return jt

    def mass_matrix(self, ev):
        """The dense mass matrix (n, n) at the state of `ev`: the loads' and drums'
        constant diagonal and the joint coordinates' block M_J(u, t) (ev.MJ)."""
        M = np.diag(self.M)
        if self.nJ:
            M[self.jb, self.jb] = ev.MJ
        return M

    def joint_accel(self, ev):
        """The joint coordinates' accelerations M_J^-1 F_J of an evaluated state (the
        loads are decoupled from them in the mass matrix)."""
        return np.linalg.solve(ev.MJ, ev.F[self.jb])

    def _joint_power(self, ev, js, q, v):
        """Power of the joint drives (torque x speed) and of the prescribed parents on
        the sets the coordinates carry: int (x'' - g) . x_t dm, x_t the velocity field
        with the coordinates held, x'' with u'' = M_J^-1 F_J (the accepted state's)."""
        nc = self.nc
        P = 0.0
        for c, jc in enumerate(self.jc):
            P += ev.joint_torque[c] * v[nc + c] / jc["rho"]
        if js.pw:
            P += self.chain.power(js, self.joint_accel(ev))
        return P

    def _joint_energy(self, ev):
        """Kinetic energy 1/2 int |x'|^2 dm and gravity potential -g . int x dm of the
        bodies the joint coordinates carry (with the motors' rotors)."""
        js, _, _, v = ev._ctx[4]
        T = js.T
        for c, jc in enumerate(self.jc):
            d = jc["drive"]
            if d.rotor_inertia:              # the motor's rotor at i times joint speed
                w = v[self.nc + c] / jc["rho"]
                T += 0.5 * d.rotor_inertia * (d.gear_ratio * w) ** 2
        return T, float(js.Vg)

    def check_range(self, ev, t):
        """A joint coordinate past its range (the engine has no end stops), or a drum
        driven by a torque or motor that has paid out all its rope: AnalysisError naming
        the time (the integrator keeps the results up to it)."""
        for k in self.qdrums:
            # rope paid out: every rope end on the drum, R theta each (unstretched())
            payout = -float(ev.theta[k]) * self.drum_rate[k]
            drum = self.model.drums[k]
            if payout > drum.rope_reserve:
                d = self.drum_drive[k]
                raise AnalysisError(
                    f"at t = {t:.6g} s drum '{drum.name}' (drive '{d.name}', {d.kind}) has "
                    f"paid out {payout:.6g} m of rope, all it holds (rope_reserve "
                    f"{drum.rope_reserve:g} m of drums.{drum.name}); likely cause: a "
                    f"drive {'torque' if d.kind == 'torque' else 'motor'} too weak to hold "
                    f"the load; the results up to t = {t:.6g} s are kept")
        if not self.nJ:
            return
        q = ev._ctx[4][2]
        for c, jc in enumerate(self.jc):
            j = self.model.joints[jc["joint"]]
            if j.range is None:
                continue
            s = q[self.nc + c] / jc["rho"]
            if s < j.range[0] - 1e-9 or s > j.range[1] + 1e-9:
                f, u = (1.0, "m") if not jc["hinge"] else (180 / np.pi, "deg")
                d = jc["drive"]
                load = "force" if not jc["hinge"] else "torque"
                drums = [f"'{x.name}'" for x in self.drum_drive
                         if x is not None and x.kind == "profile"]
                by = f" (drives of drums by profiles: {', '.join(drums)}: hauling in or " \
                    "paying out the rope that holds it)" if drums else ""
                cause = {"free": "the joint is free (free: true): the ropes and weights on "
                                 f"it moved it there{by}",
                         "motor": "a motor that does not stop it",
                         }.get(d.kind, f"a drive {load} that does not stop it")
                name = j.label
                raise AnalysisError(
                    f"at t = {t:.6g} s {name} (drive '{d.name}') "
                    f"reached {s * f:.6g} {u}, past the end of its range "
                    f"[{j.range[0] * f:g}, {j.range[1] * f:g}] {u}: the engine has no end "
                    f"stops; likely cause: {cause}; "
                    f"the results up to t = {t:.6g} s are kept")

    def joint_drive_torque(self, d, t, speed):
        """Torque (N m) or force (N) of a joint drive at t and joint speed; nan for a
        prescribed joint, 0 for a free one."""
        if d.kind == "torque":
            return float(d.torque(t)[0])
        if d.kind == "motor":
            return d.gear_ratio * d.motor.torque(d.gear_ratio * speed)[0]
        return 0.0 if d.kind == "free" else np.nan

    def joint_state(self, d, t, q, v):
        """(position, speed) of a joint drive: rad, rad/s or m, m/s."""
        if not d.coordinate:
            return d.motion(t)[:2]
        c = next(k for k, jc in enumerate(self.jc) if jc["drive"] is d)
        r = self.jc[c]["rho"]
        return q[self.nc + c] / r, v[self.nc + c] / r

    def place(self, t, q, v, kin=None, jm=None):
        """Node positions and velocities (nn, 3) and all drum angles/speeds."""
        X, V, _, th = self.kinematics(t) if kin is None else kin
        X, V = X.copy(), V.copy()
        if self.nJ:
            if jm is None:
                # positions and velocities only: the bodies' motions with u'' = 0
                states, c = [], 0
                for d in self._chain_drives:
                    if d.coordinate:
                        r = self.jc[c]["rho"]
                        states.append((q[self.nc + c] / r, v[self.nc + c] / r, 0.0))
                        c += 1
                    else:
                        states.append(d.motion(t))
                mot = self.body_motions(t, states)
                for b, idx, Xr, proj in self.chain.groups_spec:
                    if proj is None:
                        R, dR, _, p, dp, _ = mot[b]
                        X[idx] = Xr @ R.T + p
                        V[idx] = Xr @ dR.T + dp
            else:
                for idx, Xg, Vg, _, _, own in jm.groups:
                    if own:
                        X[idx] = Xg
                        V[idx] = Vg
        if self.flex is not None:
            self.flex.place(self, t, q, v, X, V)
        nf = len(self.free)
        if nf:
            P = (self.E @ q[:self.nc]).reshape(nf, 3)
            W = (self.E @ v[:self.nc]).reshape(nf, 3)
            if not self.sway:
                H = self._H
                P = P + (self._X0_free + X[self.root] - self._X0_root) @ H.T
                W = W + V[self.root] @ H.T
            X[self.free] = P
            V[self.free] = W
        theta, omega = th[:, 0].copy(), th[:, 1].copy()
        if len(self.qdrums):
            theta[self._qd] = q[self.nx:]
            omega[self._qd] = v[self.nx:]
        return X, V, theta, omega

    def unstretched(self, theta):
        """(nr,) L0 and dL0/dtheta per rope end: L0_ref - sum R theta / lambda_ref."""
        L0 = self.L0_ref.copy()
        if len(self.rope_drum):
            fac = self.end_radius / self.lam_ref[self.rope_drum]
            L0 -= np.bincount(self.rope_drum, weights=fac * theta[self.drum_of_end],
                              minlength=len(L0))
        return L0

    def _projections(self):
        """Constant maps of the hot path: span-end difference to coordinates D (ns, 3,
        nx), span -> rope incidence A (nr, ns), drum radii Rd (nr, nd), gravity."""
        nf = len(self.free)
        where = {int(i): k for k, i in enumerate(self.free)}
        ns = len(self.span_a)
        D = np.zeros((ns, 3, self.nc))
        for s_, (a, b) in enumerate(zip(self.span_a, self.span_b)):
            if b in where:
                D[s_] += self.E[3 * where[b]:3 * where[b] + 3]
            if a in where:
                D[s_] -= self.E[3 * where[a]:3 * where[a] + 3]
        self.D = D
        self.DtD = np.einsum("sia,sib->sab", D, D).reshape(ns, self.nc ** 2)  # D_s^T D_s
        nr = len(self.ropes)
        self.A = np.zeros((nr, ns))
        self.A[self.span_rope, np.arange(ns)] = 1.0
        self.kin_a = ~np.isin(self.span_a, self.free)
        self.kin_b = ~np.isin(self.span_b, self.free)
        self.Rd = np.zeros((nr, self.nd))
        if len(self.rope_drum):
            np.add.at(self.Rd, (self.rope_drum, self.drum_of_end), self.end_radius)
        self.Fg = np.concatenate([self.E.T @ (np.repeat(self.free_mass, 3) *
                                              np.tile(self.g, nf)), np.zeros(self.nJ),
                                  np.zeros(self.nu)])
        self.free3 = (3 * self.free[:, None] + np.arange(3)).ravel()

    def evaluate(self, t, q, v, taut, kin=None, damping=True, powers=True):
        """Forces and tangents at (t, q, v); with powers=False the power terms of the
        energy balance are left to `powers(ev)` (the integrator needs them only for the
        iterate it accepts).

        Length: the engine's hot path (residual and tangent of one Newton iteration)
        kept in one frame to avoid call overhead per step.
        """
        kin = self.kinematics(t) if kin is None else kin
        jm = self.joint_motions(t, q, v) if self.nJ else None
        X, V, theta, omega = self.place(t, q, v, kin, jm)
        n, nx, nc = self.n, self.nx, self.nc
        L0 = self.unstretched(theta)
        l, e, L, S = kernels.rope_spans(X, self.span_a, self.span_b, self.falls,
                                        self.span_rope, self.EA, L0, self.extra, taut)
        nr = len(L)
        lam = L / L0
        fe = self.falls[:, None] * e                         # span rows f e
        if self.nJ:
            D, DJJ, XJ = self._joint_spans(jm)
        else:
            D, XJ = self.D, None
        if self.flex is not None:                # the elastic nodes' columns R
            D = self.flex.spans(self, t, D)
        eD = np.einsum("si,sij->sj", e, D)                   # (ns, nx) e_s . D_s
        G = self.A @ (self.falls[:, None] * eD)              # (nr, nx) dL/dq_x
        Rd = self.Rd
        dV = V[self.span_b] - V[self.span_a]
        edot = self.A @ np.einsum("si,si->s", fe, dV) + Rd @ omega   # elongation rate
        F = np.zeros(n)
        K = np.zeros((n, n))
        C = np.zeros((n, n))
        cL = np.where(taut, self.EA / L, 0.0)
        F[:nx] = self.Fg - G.T @ S
        # tangent: EA/L G^T G + sum f S / l (I - e e^T) on the span ends
        # (kernels.projected_tangent, w = f S / l, with the constant D_s^T D_s made once)
        w = self.falls * S[self.span_rope] / l
        jt = None
        if self.nJ or self.flex is not None:
            # the span vectors depend on the joint coordinates too: D_s^T D_s changes,
            # and d^2L/du_i du_k gains f e . (d^2 Delta / du_i du_k); elastic nodes: D_s
            # has R(t)
            K[:nx, :nx] = (G.T * cL) @ G + np.einsum("s,sia,sib->ab", w, D, D) \
                - (eD.T * w) @ eD
            if self.nJ:
                jb = self.jb
                K[jb, jb] += np.einsum("s,si,sijk->jk", w * l, e, DJJ)
                jt = self._joint_forces(t, q, v, jm, F, K, C)
        else:
            K[:nx, :nx] = (G.T * cL) @ G + (w @ self.DtD).reshape(nx, nx) \
                - (eD.T * w) @ eD
        # damping: b = psi c / (2 pi w) with w = w0 sqrt(c / c0): w0 the frequency of
        # the mode that most strains the rope at the static state (_dashpot_frequencies),
        # carried along with its stiffness c = EA/L; b = beta sqrt(c)
        Sd = np.zeros(nr)
        b = np.zeros(nr)
        if damping and self.damped and nr:
            b = self.beta * np.sqrt(cL)
            Sd = b * edot
            F[:nx] -= G.T @ Sd
            C[:nx, :nx] += (G.T * b) @ G
        # drums with a coordinate: the ropes' torque -(S + Sd) R
        if self.qdrums:
            dS = np.where(taut, self.EA / (self.lam_ref * L0), 0.0)  # dS/d(R theta)
        drive_torque = np.zeros(self.nd)
        for cc, k in enumerate(self.qdrums):
            i = nx + cc
            Rk = Rd[:, k]
            F[i] -= Rk @ (S + Sd)
            K[i, :nx] += (Rk * cL) @ G
            K[:nx, i] += G.T @ (Rk * dS)
            K[i, i] += (Rk ** 2 * dS).sum()
            C[i, :nx] += (Rk * b) @ G
            C[:nx, i] += G.T @ (Rk * b)
            C[i, i] += (Rk ** 2 * b).sum()
            d = self.drum_drive[k]
            if d.kind == "torque":
                tq, dtq = d.torque(t)[0], 0.0
            else:
                gr = self.gear[k]
                Mm, dM = d.motor.torque(gr * omega[k])
                tq, dtq = gr * Mm, gr * gr * dM
            drive_torque[k] = tq
            F[i] += tq
            C[i, i] -= dtq
        # springs
        nsp = len(self.sp_k)
        N = np.zeros(nsp)
        spring = Gs = None
        if nsp:
            _, N, rs, Ks = kernels.spring_state(X, self.sp_a, self.sp_b, self.sp_k,
                                                 self.sp_dref, self.N_ref)
            Gs = rs.reshape(nsp, -1)[:, self.free3] @ self.E
            F[:nc] -= Gs.T @ N
            K[:nc, :nc] += self.E.T @ Ks[np.ix_(self.free3, self.free3)] @ self.E
            Ndot = 0.0
            if damping and self.damped:
                bs = self.sp_bd                  # psi k / (2 pi w0), k constant
                ddot = np.einsum("rij,ij->r", rs, V)
                Nd = bs * ddot
                F[:nc] -= Gs.T @ Nd
                C[:nc, :nc] += (Gs.T * bs) @ Gs
                N = N + Nd
                Ndot = float(Nd @ ddot)
            spring = (rs, Ndot)
        if self.flex is not None:                # elastic, gravity, frame inertia
            self.flex.forces(self, t, q, v, F, K, C)
        ev = Eval(t, F, K, C, X, V, L, L0, S, Sd, edot, N, theta, omega, drive_torque,
                  None, None, None, joint_torque=jt)
        if self.nJ:
            ev.MJ, ev.dMJ = jm.M, jm.dM
        ev._rows = (G, Gs)                      # dL/dq_x, the springs' rows (setup)
        if self.flex is not None:                # the ropes' force on u (power)
            o = nc + self.nJ
            ev._flex_rope = -(G[:, o:o + self.nu].T @ (S + Sd))
            ev._flex_G = G                       # dL/dq_x (the step's force error)
        ev._ctx = (fe, lam, taut, spring, (jm, XJ, q, v))
        if powers:
            self.powers(ev)
        return ev

    def powers(self, ev):
        """Fill the power terms of `ev` (W) and the guided loads' kinetic energy (J)."""
        if ev.P_drive is not None:
            return ev
        fe, lam, taut, spring, (jm, _, q, v) = ev._ctx
        S, Sd, V, omega, Rd = ev.S, ev.Sd, ev.V, ev.omega, self.Rd
        # energy carried onto (off) the drums with the wound rope: the drum's work
        # (S R omega) less the change of the free rope's energy (R omega / lambda_ref)
        # (S lambda - w), w = EA (lambda ln lambda - lambda + 1)
        if len(self.rope_drum):
            wden = np.where(taut, self.EA * (lam * np.log(lam) - lam + 1), 0.0)
            P_wound = float(((S - (S * lam - wden) / self.lam_ref) * (Rd @ omega)).sum())
        else:
            P_wound = 0.0
        # power fed through kinematic nodes (moving sheaves, dead ends on bodies)
        if self.nJ:
            # the nodes a joint coordinate carries: only the prescribed part of their
            # velocity is fed in from outside (the rest is the coordinate's own motion)
            V = V.copy()
            vJ = v[self.jb]
            for idx, _, _, xj, _, own in jm.groups:
                if own:
                    V[idx] -= xj @ vJ
        Vk = np.where(self.kin_b[:, None], V[self.span_b], 0.0) - \
            np.where(self.kin_a[:, None], V[self.span_a], 0.0)
        rVk = self.A @ np.einsum("si,si->s", fe, Vk)
        # springs: the power fed through kinematic nodes and the dashpots' dissipation
        if spring is not None:
            rs, P_sp_diss = spring
            Pk = np.einsum("rij,ij->r", rs[:, self.kin], V[self.kin])
            P_sp_kin = float(ev.N @ Pk)
        else:
            P_sp_kin = P_sp_diss = 0.0
        # power of the drives: kinematic nodes pulled by the ropes and springs, prescribed
        # drums, torque drives
        P = float((S + Sd) @ rVk) + P_sp_kin
        for k in range(self.nd):
            d = self.drum_drive[k]
            if d is not None and d.kind == "profile":
                P += float(Rd[:, k] @ (S + Sd)) * omega[k]
        P += float(ev.drive_torque @ omega)
        if self.nJ:
            P += self._joint_power(ev, jm, q, v)
        if self.flex is not None:
            P += self.flex.power(self, ev, q, v)
        # loads without sway are guided horizontally with their carrier: the guidance
        # does the work of their horizontal kinetic energy (the ropes hang vertically)
        T_guided = 0.0
        if not self.sway and len(self.free):
            # (loads guided by bodies a joint coordinate carries: their horizontal
            # inertia is in the coordinates' equations, the guidance internal)
            Vh = V[self.free] - np.outer(V[self.free] @ self.up, self.up)
            mg = self.free_mass if not self.nJ else \
                np.where(self.guided_joint, 0.0, self.free_mass)
            T_guided = 0.5 * float(mg @ np.einsum("ij,ij->i", Vh, Vh))
        ev.P_drive, ev.P_diss = P, float(Sd @ ev.edot) + P_sp_diss
        ev.P_wound, ev.T_guided = P_wound, T_guided
        return ev

    def energy(self, ev, taut):
        """Kinetic, gravity potential and elastic energy (J)."""
        T = 0.5 * float(self.free_mass @ np.einsum("ij,ij->i", ev.V[self.free],
                                                   ev.V[self.free]))
        for cc, k in enumerate(self.qdrums):
            T += 0.5 * self.J[cc] * ev.omega[k] ** 2
        Vg = -float(self.free_mass @ (ev.X[self.free] @ self.g))
        if self.nJ:
            dT, dV = self._joint_energy(ev)
            T, Vg = T + dT, Vg + dV
        if self.flex is not None:
            dT, dV, dU = self.flex.energy(self, ev.t, ev._ctx[4][2], ev._ctx[4][3])
            T, Vg = T + dT, Vg + dV
        with np.errstate(invalid="ignore", divide="ignore"):
            U = float(np.where(taut, kernels.hencky_energy(self.EA, ev.L, ev.L0), 0.0).sum())
        if len(self.sp_k):
            d = np.linalg.norm(ev.X[self.sp_b] - ev.X[self.sp_a], axis=1) - self.sp_dref
            U += float((self.N_ref * d + 0.5 * self.sp_k * d * d).sum())
        if self.flex is not None:
            U += dU
        return T, Vg, U

    # ----------------------------------------------------------------- static state
    def _static(self, model):
        """Static tensions of the reference geometry (drums held, elastic stiffness
        only, as model-format.md "Static state"): S0 = c r u with K_e u = F_gravity; the
        geometry must then be in equilibrium (checked). L0_ref = L_ref exp(-S0/EA).

        Length: one least-squares statics over the loads and free joints, with the check
        and message of each way it can fail.
        """
        file = model.scene_file or model.file
        self.damped = model.effects.damping != "none"
        nr, ns = len(self.ropes), len(self.sp_k)
        self.L0_ref = np.ones(nr)
        self.lam_ref = np.ones(nr)
        self.N_ref = np.zeros(ns)
        q0 = np.zeros(self.n)
        q0[:self.nc] = self.qx_ref
        X = self.place(0.0, q0, np.zeros(self.n))[0]
        L, _, r, _ = kernels.rope_state(X, self.span_a, self.span_b, self.falls,
                                        self.span_rope, self.EA, np.ones(nr), self.extra,
                                        np.ones(nr, bool))
        free3 = (3 * self.free[:, None] + np.arange(3)).ravel()
        G = r.reshape(nr, 3 * self.nn)[:, free3] @ self.E
        Fg = self.E.T @ (np.repeat(self.free_mass, 3) * np.tile(self.g, len(self.free)))
        # joint coordinates: free joints are unknowns of the static state, torque and
        # motor joints are held (their drive's holding torque balances them at t = 0)
        QgJ = np.zeros(self.nJ)
        GJ = np.zeros((nr, self.nJ))
        if self.nJ:
            jm = self.joint_motions(0.0, q0, np.zeros(self.n), tangent=False)
            D, _, _ = self._joint_spans(jm)
            l = np.linalg.norm(X[self.span_b] - X[self.span_a], axis=1)
            e = (X[self.span_b] - X[self.span_a]) / l[:, None]
            GJ = self.A @ (self.falls[:, None] *
                           np.einsum("si,sij->sj", e, D[:, :, self.jb]))
            QgJ = jm.Fg.copy()
        free_j = [c for c, jc in enumerate(self.jc) if jc["drive"].kind == "free"]
        G = np.hstack([G, GJ[:, free_j]])
        Fg = np.concatenate([Fg, QgJ[free_j]])
        nu = len(Fg)
        c = self.EA / L
        rows, stiff = [G], [c]
        if ns:
            _, _, rs, _ = kernels.spring_state(X, self.sp_a, self.sp_b, self.sp_k,
                                               self.sp_dref, np.zeros(ns))
            Gs = rs.reshape(ns, -1)[:, free3] @ self.E
            rows.append(np.hstack([Gs, np.zeros((ns, len(free_j)))]))
            stiff.append(self.sp_k)
        Rall = np.vstack(rows) if rows else np.zeros((0, nu))
        call = np.concatenate(stiff)
        Ke = (Rall.T * call) @ Rall
        u = np.linalg.lstsq(Ke, Fg, rcond=1e-12)[0]
        force = call * (Rall @ u)
        resid = Fg - Rall.T @ force
        weight = np.abs(Fg).max(initial=0.0)
        worst = int(np.argmax(np.abs(resid))) if len(resid) else 0
        if weight > 0 and np.abs(resid).max() > 1e-8 * weight and worst >= self.nc:
            jc = self.jc[free_j[worst - self.nc]]
            raise ModelError(f"the model's geometry is not a static equilibrium: the ropes "
                             f"cannot hold {model.joints[jc['joint']].label} (free in "
                             f"drive '{jc['drive'].name}') there (unbalanced "
                             f"{abs(resid[worst]) * jc['rho']:.4g} N m or N); reeve a rope "
                             "that holds it, or drive it by a torque", file,
                             jc["drive"].entry)
        if weight > 0 and np.abs(resid).max() > 1e-8 * weight:
            k = int(np.argmax(np.abs(self.E[:, worst]))) // 3
            node = self.model.node_names[self.free[k]]
            raise ModelError(f"the model's geometry is not a static equilibrium: the ropes "
                             f"and springs cannot hold the weight at node '{node}' there "
                             f"(unbalanced {np.abs(resid).max():.4g} N); hang the loads "
                             "below their sheaves (an operation starts at rest)",
                             model.file, f"nodes.{node}")
        S0 = force[:nr]
        self.N_ref = force[nr:]
        for j in np.flatnonzero(S0 < 0):
            raise ModelError(f"rope '{model.ropes[self.ropes[j]].name}' would be in "
                             f"compression at rest ({S0[j]:.4g} N)", model.file,
                             f"ropes.{model.ropes[self.ropes[j]].name}")
        self.S0 = S0
        # what holds each joint coordinate at rest (N m or N): -(gravity + ropes)
        self.joint_hold = np.array([-(QgJ[c] - GJ[:, c] @ S0) * jc["rho"]
                                    for c, jc in enumerate(self.jc)])
        self._warn_held_joints(model, GJ)
        self.L_ref = L
        self.lam_ref = np.exp(S0 / self.EA)
        self.L0_ref = L / self.lam_ref
        self.q0 = q0
        self.taut0 = S0 > 0
        # what holds each drum at rest: the ropes' torque S0 R
        self.hold_torque = np.zeros(self.nd)
        for j, dd, R in zip(self.rope_drum, self.drum_of_end, self.end_radius):
            self.hold_torque[dd] += R * S0[j]

    def _dashpot_frequencies(self):
        """The dashpots' frequencies (damping: exact): each rope's and axial spring's w0,
        the frequency of the mode that stores the largest share of its strain energy,
        (r phi_j)^2 / w_j^2, at the static state, as the linear core's transient damping
        picks it (analysis/damping/element.py, element_frequencies): the modes of the
        tangent K and the mass matrix at rest (every rope taut, rigid modes left out;
        massless blocks are refused with damping); an element no mode strains gets the
        lowest frequency. A rope's dashpot is then b = psi c / (2 pi w0 sqrt(c / c0)) =
        beta sqrt(c) at its current stiffness c = EA/L (c0 at rest): a load on one rope
        keeps zeta = psi / (4 pi) at every rope length (w = sqrt(n^2 c / m)); a spring's
        is psi k / (2 pi w0)."""
        nr, nsp = len(self.ropes), len(self.sp_k)
        self.beta, self.sp_bd = np.zeros(nr), np.zeros(nsp)
        self.dashpot_w0 = np.full(nr + nsp, np.inf)          # no dashpots
        if not self.damped or not nr + nsp:
            return
        n, nx = self.n, self.nx
        ev = self.evaluate(0.0, self.q0, np.zeros(n), np.ones(nr, bool), damping=False,
                           powers=False)
        G, Gs = ev._rows
        R = np.zeros((nr + nsp, n))
        R[:nr, :nx] = G
        for cc, k in enumerate(self.qdrums):
            R[:nr, nx + cc] = self.Rd[:, k]
        if nsp:
            R[nr:, :self.nc] = Gs
        K = 0.5 * (ev.K + ev.K.T)
        M = np.diag(np.asarray(self.M, float))
        if self.nJ:
            M[self.jb, self.jb] = ev.MJ
        if (np.diag(M) <= 0).any():      # massless blocks with damping are refused earlier
            raise AnalysisError("damping: a coordinate without mass has no modes to pick "
                                "the dashpots' frequencies from")
        lam, phi = eigh(K, M)
        ok = lam > 1e-10 * max(lam.max(initial=0.0), 1e-300)
        if not ok.any():
            return
        lam = lam[ok]
        E = R @ phi[:, ok]
        w0 = np.sqrt(lam[np.argmax(E * E / lam, axis=1)])   # all zero: the lowest
        c0 = self.EA / ev.L
        self.beta = self.psi * np.sqrt(c0) / (2 * np.pi * w0[:nr])
        self.sp_bd = self.sp_psi * self.sp_k / (2 * np.pi * w0[nr:])
        self.dashpot_w0 = w0

    def _inextensible(self, model):
        """Ropes as inextensible constraints L(q, t) = L0(t) (rope_elasticity: false;
        constraints.py, docs/operations.md "Inextensible ropes"): the rope is not
        stretched, so L0_ref = L_ref and a drum winds R theta of it (lambda_ref = 1).
        What the constraint formulation does not cover yet is refused (exit 2)."""
        file = model.scene_file or model.file
        if self.nJ:
            d = self.jc[0]["drive"]
            raise ModelError(f"drive '{d.name}' makes {model.joints[self.jc[0]['joint']].label}"
                             " a coordinate: joint coordinates with inextensible ropes "
                             "(rope_elasticity: false) are not solved yet; use elastic "
                             "ropes or prescribe the joint's motion with a profile", file,
                             "effects.rope_elasticity")
        if self.flex is not None:
            raise ModelError("an elastic structure (effects.structure: flexible) with "
                             "inextensible ropes (rope_elasticity: false) is not solved "
                             "yet; use elastic ropes or a rigid structure", file,
                             "effects.rope_elasticity")
        self.lam_ref = np.ones(len(self.ropes))
        self.L0_ref = self.L_ref.copy()

    def _warn_held_joints(self, model, GJ):
        """A torque- or motor-driven joint is held at rest like a drum: its holding
        torque carries the whole static moment, and a rope on the bodies it turns that
        nothing else loads (a luffing rope) is at 0 N. Warn, with the holding torque and
        the drive's torque at t = 0 (if they differ the bodies start out of equilibrium:
        torque: 0 drops a boom onto its unloaded luffing rope)."""
        big = max(1.0, np.abs(GJ).max(initial=0.0))
        S0 = self.S0
        for c, jc in enumerate(self.jc):
            d = jc["drive"]
            hold = float(self.joint_hold[c])
            if d.kind not in ("torque", "motor") or hold == 0.0:
                continue
            ropes = [model.ropes[self.ropes[j]].name for j in range(len(S0))
                     if abs(GJ[j, c]) > 1e-12 * big
                     and S0[j] <= 1e-9 * max(1.0, np.abs(S0).max())]
            if not ropes:
                continue
            given = float(d.torque(0.0)[0]) if d.kind == "torque" else \
                float(d.gear_ratio * d.motor.torque(0.0)[0])
            u = "N m" if jc["hinge"] else "N"
            j = model.joints[jc["joint"]]
            off = "" if abs(given - hold) <= 1e-6 * abs(hold) else \
                f"; the drive gives {given:.6g} {u} at t = 0, so the bodies start out of " \
                "equilibrium and fall onto the unloaded rope"
            self.warnings.append(
                f"drive '{d.name}' ({d.kind}) on {j.label}: at rest the joint is "
                f"held like a drum: its holding {'torque' if jc['hinge'] else 'force'} "
                f"{hold:.6g} {u} carries the whole static load and rope(s) "
                f"{', '.join(ropes)}, which also hold the bodies it moves, carry 0 N{off} "
                "(a boom held by its luffing rope: use free: true; docs/operations.md, "
                "'Torque, force, motor and free joints')")
