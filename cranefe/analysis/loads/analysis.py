"""`loads(model)`: the dynamic factors of EN 13001-2 computed from simulations of the crane
itself, each beside the standard's simplified value (docs/loads.md).

- phi2: lift-off of the grounded load at a prescribed drum speed (rigid drive) for a
  range of steady hoisting speeds from creep to full, and per hoist drive class HD1-HD5
  (Table 3's v_h; HD5 lifts off at v = 0 and accelerates: simulated as the drive's ramp
  from the grounded state); phi2 = peak force of the rope that carries the load over its
  force with the load hanging at rest; the hoisting class it behaves like;
- phi1: the same lift-off at full speed: vertical acceleration of every mass of the crane
  (bodies at their centre of mass, carried point masses), phi1 = 1 + a_up / g;
- phi3: release of dm from the load (linear superposition, `runs.release`);
- phi5: hoist start from the hanging state (drum speed ramp) and a trapezoidal move of
  every named slider and hinge on the operation engine; peak elastic force over the
  rigid-body inertia force of the hoist load;
- phi6 from phi2; phi4 and phi7 what the model lacks.
"""

import time

import numpy as np

from ...errors import ModelError
from . import standard
from .result import LoadsResult
from .runs import (hook_per_drum, hoist_start, joint_move, lift_model, lift_off,
                   placed, release)
from .scene import complete, parse


ALL = ("phi1", "phi2", "phi3", "phi5", "phi6")


def loads(model, only=None, shapers=()):
    """Compute the factors of `model` (a model, a transient scene or a loads scene)
    -> `LoadsResult`. only : factor names (phi1-phi7) or drive names (phi5 of that
    drive) to compute with the fewest runs (a sweep's outputs), reporting only those:
    phi2 then comes from the declared drive class's speed alone (HD5: the hoist start),
    phi6 from that run. shapers : input shapers (ZV, ZVD, ZVDD, EI) run on every
    slider and hinge move -> `shapers: {JOINT: {NAME: {residual_sway_deg, move_time_s,
    ...}}}` beside the unshaped move (docs/shaping.md).

    Length: the factors' runs in the order docs/loads.md lists them, each guarded by
    whether it is wanted.
    """
    t0 = time.perf_counter()
    asked = set(ALL if only is None else only)   # what is reported
    want = set(asked)                            # what is computed
    if "phi6" in want:
        want.add("phi2")
    spec0 = parse(model)
    file = model.scene_file or model.file
    _check_only(asked, spec0, file)
    work = placed(model, spec0)
    lift = lift_model(work)
    ratio = hook_per_drum(lift, spec0.drum)
    spec = complete(spec0, ratio, file)
    traces, warnings, results = [], [], []
    g = float(np.linalg.norm(model.gravity))

    def drum(v):                      # hook speed (m/s) -> drum speed (rad/s)
        return v / ratio

    # phi2 curve: rigid drive at each steady speed, the fastest first (its lift-off
    # time, scaled by the speeds, is the next runs' first guess)
    vh = standard.characteristic_speed(spec.drive_class, spec.speed, spec.creep, "A1")
    if only is None:
        speeds = spec.speeds
    else:
        speeds = (spec.speed,) if "phi1" in want else ()
        if "phi2" in want and spec.drive_class != "HD5":
            speeds = tuple(sorted({*speeds, vh}))
    curve, runs, t_full = [], {}, None
    for v in sorted(speeds, reverse=True):
        guess = None if t_full is None else 1.05 * t_full * max(speeds) / v
        res, tr = lift_off(lift, spec, f"lift-off {v:.4g} m/s", drum(v), guess=guess)
        t_full = t_full or res.lift_off_time
        traces.append(tr)
        runs[v] = res
        results.append(res)
        curve.insert(0, _phi2_point(res, spec, v, tr.name))
    # HD5: pre-tensioned to the lift-off (the hanging state at rest), then the drive's
    # own start: the hoist-start run, which is also phi5's
    start = None
    if only is None or spec.drum in want or "phi5" in want or \
            ("phi2" in want and spec.drive_class == "HD5"):
        start, trs, acc = hoist_start(lift, spec, drum(spec.speed))
        traces.append(trs)
        results.append(start)
    factors = {}
    if "phi2" in want:
        hd5 = _phi2_point(start, spec, 0.0, trs.name) if start is not None else None
        factors["phi2"] = _phi2(spec, curve, hd5)
    if "phi1" in want:
        factors["phi1"] = _phi1(lift, runs[spec.speed], g, traces[0].name)
    if "phi3" in want:
        rel, reduced, trr = release(lift, spec)
        traces.append(trr)
        results.append(rel)
        factors["phi3"] = _phi3(lift, reduced, rel, spec, trr.name)
    if only is None or "phi4" in want:
        factors["phi4"] = _phi4(model)
    phi5 = {}
    # the start also runs for HD5's phi2: phi5 of the hoist only when asked
    if start is not None and (only is None or "phi5" in want or spec.drum in want):
        phi5[spec.drum] = _phi5_hoist(start, spec, trs.name, g, acc * ratio)
    for move in spec.moves:
        if only is None or "phi5" in want or move.joint in want:
            res, tr, a_max = joint_move(work, spec, move)
            traces.append(tr)
            results.append(res)
            phi5[move.joint] = _phi5_joint(work, res, spec, move, tr.name, a_max)
    if phi5:
        factors["phi5"] = phi5
    shaped = {move.joint: joint_move(work, spec, move, shapers=shapers)
              for move in spec.moves} if shapers else {}
    if "phi6" in want:
        factors["phi6"] = _phi6(factors["phi2"])
    if only is None or "phi7" in want:
        factors["phi7"] = _phi7(model)
    if only is not None:              # phi6 needs phi2's run, reported only when asked
        factors = {k: v for k, v in factors.items() if k in asked or k == "phi5"}
    for r in results:
        warnings += [w for w in r.warnings if not w.startswith("modes:")]
    return LoadsResult(model.name, model.scene, file, spec, ratio, factors,
                       tuple(traces), tuple(spec.assumed), tuple(dict.fromkeys(warnings)),
                       {"total": time.perf_counter() - t0}, shapers=shaped)


def _check_only(asked, spec, file):
    """Every name of `only=` is a factor (phi1-phi7) or a drive of the scene (the hoist
    drum, a slider or hinge with a move)."""
    drives = [spec.drum, *(m.joint for m in spec.moves)]
    bad = sorted(asked - {*ALL, "phi4", "phi7", *drives})
    if bad:
        raise ModelError(f"unknown factor or drive {', '.join(map(repr, bad))} in "
                         f"only=; use phi1-phi7 or a drive: {', '.join(drives)}",
                         file, "only")


# ----------------------------------------------------------------------- phi2

def load_ropes(res, spec, model=None):
    """Indices of the ropes whose force carries the hoist load (their names contain no
    other clue: every rope with a static force; the largest dynamic factor counts)."""
    return [k for k, s in enumerate(res.rope_force_static) if s > 0]


def _phi2_point(res, spec, v, name):
    ks = load_ropes(res, spec)
    k = max(ks, key=lambda i: res.dynamic_factor[i])
    return {"v_h_m_s": float(v), "value": float(res.dynamic_factor[k]),
            "rope": res.rope_names[k],
            "peak_time_s": float(res.rope_force_max_time[k]),
            "lift_off_s": float(res.lift_off_time), "simulation": name}


def _phi2(spec, curve, hd5):
    pts = curve or [dict(hd5, v_h_m_s=0.0)]
    v = np.array([p["v_h_m_s"] for p in pts])
    p = np.array([p["value"] for p in pts])
    cls = standard.behaves_like(v, p)
    declared = spec.hoisting_class or cls["within"] or "HC4"
    by_drive = {}
    for hd in standard.DRIVE_CLASSES:
        vh = standard.characteristic_speed(hd, spec.speed, spec.creep, "A1")
        if hd == "HD5":
            point = dict(hd5, v_h_m_s=0.0) if hd5 is not None else None
        else:
            point = next((c for c in curve
                          if abs(c["v_h_m_s"] - vh) <= 1e-12 * spec.speed), None)
        if point is not None:
            by_drive[hd] = dict(point, text=standard.DRIVE_CLASS_TEXT[hd],
                                standard={hc: float(standard.phi2(hc, vh))
                                          for hc in standard.HOISTING_CLASSES})
    chosen = by_drive[spec.drive_class]
    return {
        "value": chosen["value"], "drive_class": spec.drive_class,
        "v_h_m_s": chosen["v_h_m_s"],
        "standard": chosen["standard"][declared], "hoisting_class": declared,
        "hoisting_class_source": "declared" if spec.hoisting_class else
        ("behaves like (lowest class covering every computed point)" if cls["within"]
         else "HC4: the crane exceeds every class somewhere"),
        "behaves_like": {"within": cls["within"], "closest": cls["closest"],
                         "excess": cls["excess"]},
        "rope": chosen["rope"], "peak_time_s": chosen["peak_time_s"],
        "lift_off_s": chosen["lift_off_s"], "simulation": chosen["simulation"],
        "drive_classes": by_drive, "curve": curve,
        "clause": standard.CLAUSES["phi2"],
        "assumes": "the class formula phi2,min + beta2 v_h stands for a crane of the "
                   "stiffness class HC1-HC4 lifting at the steady speed v_h of Table 3; "
                   "here the crane's own stiffness and masses give phi2 = peak rope force "
                   "/ force with the load hanging, the drum held at its speed (a rigid "
                   "drive: the severest case); HD5: pre-tensioned until the load just "
                   "hangs (lift-off at v = 0), then the drive's jerk-limited start",
    }


# ----------------------------------------------------------------------- phi1

def crane_masses(model, dofs):
    """(names, masses, rows): each crane mass (bodies at their centre of mass, point
    masses carried by bodies) with the (3, n) rows of T giving its translation."""
    layout = dofs.layout
    T = dofs.T.tocsr()
    names, mass, rows = [], [], []
    for b, body in enumerate(model.bodies):
        if body.mass > 0:
            names.append(body.name)
            mass.append(body.mass)
            rows.append(T[layout.body(b)[:3]].toarray())
    for node, m in zip(model.masses.nodes, model.masses.mass):
        if dofs.carrier[int(node)] >= 0 and m > 0:
            names.append(model.node_names[int(node)])
            mass.append(float(m))
            rows.append(T[layout.node([int(node)])[0]].toarray())
    return names, np.array(mass), rows


def _phi1(model, res, g, name):
    from ...system import assemble
    dofs = assemble(model).dofs
    names, mass, rows = crane_masses(model, dofs)
    up = -model.gravity / g
    text = standard.CLAUSES["phi1"]
    std = {"upper": 1.1, "lower": 0.9,
           "assumes": "1 +/- a with 0 <= a <= 0.1: the vibration of the crane's own mass "
                      "when a load lifts off or is set down, as a share of g"}
    moving = [k for k in range(len(names)) if np.abs(rows[k]).max(initial=0.0) > 0]
    if not moving:
        return {"value": 1.0, "lower": 1.0, "standard": std["upper"],
                "standard_range": [std["lower"], std["upper"]], "by_mass": {},
                "clause": text, "simulation": name,
                "assumes": "the crane's masses have no coordinates in this model (fixed to "
                           "the ground or to rigid parts with no elastic support), so "
                           "lifting off cannot accelerate them: phi1 = 1 follows from the "
                           "rigid structure, not from a computation of its vibration"}
    t = res.times
    a = np.gradient(res.v, t, axis=0)          # (nt, n)
    by, acc = {}, []
    for k in moving:
        az = a @ (rows[k].T @ up)              # (nt,) upward acceleration
        acc.append(az)
        i, j = int(np.argmax(az)), int(np.argmin(az))
        by[names[k]] = {"upper": float(1 + az[i] / g), "lower": float(1 + az[j] / g),
                        "time_upper_s": float(t[i]), "mass_kg": float(mass[k])}
    acc = np.array(acc)
    whole = (mass[moving] @ acc) / mass[moving].sum()
    worst = max(by, key=lambda n: max(by[n]["upper"] - 1, 1 - by[n]["lower"]))
    return {"value": by[worst]["upper"], "lower": by[worst]["lower"], "mass": worst,
            "peak_time_s": by[worst]["time_upper_s"],
            "whole_crane": {"upper": float(1 + whole.max() / g),
                            "lower": float(1 + whole.min() / g)},
            "standard": std["upper"], "standard_range": [std["lower"], std["upper"]],
            "by_mass": by, "clause": text, "simulation": name,
            "assumes": std["assumes"] + "; computed: 1 + (vertical acceleration of each "
                       "crane mass)/g during the lift-off at full speed (bodies at their "
                       "centre of mass; whole_crane: the mass-weighted mean). Set-down is "
                       "not simulated (the transient core has no ground under a hanging "
                       "load); for a linear crane it mirrors the lift-off"}


# ----------------------------------------------------------------------- phi3

def _phi3(model, reduced, res, spec, name):
    from ...statics import solve_static
    full = solve_static(model)
    ks = [k for k, s in enumerate(res.rope_force_static) if s > 0]
    # static force of each rope with the whole load (the run's ropes are the model's)
    S_m = _rope_static(model, full, res.rope_names)
    best = None
    for k in ks:
        lowest = S_m[k] - (res.rope_force_max[k] - res.rope_force_static[k])
        ratio = lowest / S_m[k]
        if best is None or ratio < best[0]:
            best = (ratio, k)
    ratio, k = best
    r = spec.fraction
    beta3 = (1 - ratio) / r - 1
    out = {"value": float(ratio), "dm_over_m": r, "release_time_s": spec.release_time,
           "rope": res.rope_names[k], "peak_time_s": float(res.rope_force_max_time[k]),
           "standard": float(standard.phi3(r, "fast")),
           "standard_slow": float(standard.phi3(r, "slow")),
           "beta3_equivalent": float(beta3), "simulation": name,
           "clause": standard.CLAUSES["phi3"],
           "assumes": "1 - (dm/m)(1 + beta3): beta3 = 1 for magnets or similar rapid "
                      "release, 0.5 for grabs or similar slow release; computed: lowest "
                      "force of the rope over its force with the whole load hanging"}
    if ratio < 0:
        out["slack"] = ("the rope would go slack (a negative factor): the linear value "
                        "says how far the load on the crane reverses; the rope's own force "
                        "stays at zero")
    return out


def _rope_static(model, static, rope_names):
    """Largest static force along each rope (as the transient results report them)."""
    from ...system import assemble
    springs = assemble(model).springs
    out = []
    for k in range(len(rope_names)):
        rows = np.flatnonzero(springs.rope == k)
        out.append(float(static.element_force[rows].max()))
    return np.array(out)


# ----------------------------------------------------------------------- phi5

def _phi5_hoist(res, spec, name, g, a):
    ks = load_ropes(res, spec)
    best = None
    for k in ks:
        S0 = res.rope_force_static[k]
        rigid = S0 * a / g
        val = (res.rope_force_max[k] - S0) / rigid
        if best is None or val > best[0]:
            best = (val, k, rigid)
    val, k, rigid = best
    lo, hi, text = standard.phi5_guidance(sudden=spec.jerk == 0)
    return {"value": float(val), "standard": [lo, hi], "standard_text": text,
            "rope": res.rope_names[k], "acceleration_m_s2": a, "ramp_s": spec.ramp,
            "jerk_time_s": spec.jerk,
            "rigid_body_force_N": float(rigid),
            "peak_force_N": float(res.rope_force_max[k]),
            # braking from steady full speed over the same profile: the mirror image of
            # the start (a linear system at constant speed is its static state)
            "braking": {"value": float(val), "lowest_force_N": float(
                res.rope_force_static[k] - val * rigid),
                "slack": bool(res.rope_force_static[k] - val * rigid < 0)},
            "peak_time_s": float(res.rope_force_max_time[k]), "simulation": name,
            "clause": standard.CLAUSES["phi5"],
            "assumes": "phi5 multiplies the change of drive force of a rigid-body model; "
                       "computed: (peak rope force - force hanging at rest) / (that force "
                       "x a/g), a the hook's rigid-body acceleration (v_h,max / (ramp - "
                       "jerk time), reached linearly over the jerk time); "
                       "braking over the same ramp mirrors it while the rope stays taut"}


def suspension_node(model, hanging):
    """The node the hanging masses hang from: the node, neither hanging nor on the
    ground, that the most falls of spans join to a hanging mass (a tag line's anchor on
    the ground cannot carry the load through a drive's motion); None if there is none.
    Two different nodes with the most falls are refused: the suspension point (the
    lever of phi5 of a hinge) would be ambiguous."""
    idx = model.node_index
    hang = {idx[n] for n in hanging}
    ground = {int(i) for i in model.ground}
    falls, ropes = {}, {}
    for rope in model.ropes:
        for a, b, f in zip(rope.span_a, rope.span_b, rope.falls):
            for x, y in ((a, b), (b, a)):
                if x in hang and y not in hang and y not in ground:
                    falls[int(y)] = falls.get(int(y), 0) + int(f)
                    ropes.setdefault(int(y), []).append(rope.name)
    if not falls:
        return None
    most = max(falls.values())
    top = [y for y, f in falls.items() if f == most]
    if len(top) > 1:
        names = [model.node_names[y] for y in top]
        raise ModelError(
            f"the hanging masses hang from {' and '.join(names)} by {most} falls each "
            f"(ropes {', '.join(sorted({r for y in top for r in ropes[y]}))}), so phi5 of a "
            "hinge has no single suspension point; reeve the load to one node (e.g. a "
            "path ending [.., TIP, {node: LOAD, falls: 2}]) or give one node more falls",
            model.file, "ropes")
    return top[0]


def _phi5_joint(model, res, spec, move, name, a_max):
    """Peak inertia force of the hanging masses along the motion of their suspension
    point (slider: its axis; hinge: the horizontal tangent of the suspension point's
    circle at the drive's current angle) over their rigid-body force m a (a: the
    suspension point's acceleration along that line at a_max of the drive)."""
    t = res.times
    X = res.mass_position                              # (nt, nm, 3)
    hang = [k for k, n in enumerate(res.mass_names) if n in res.sway_names]
    masses = dict(zip((model.node_names[int(i)] for i in model.masses.nodes),
                      model.masses.mass))
    m = np.array([masses[res.mass_names[k]] for k in hang])
    acc = np.gradient(np.gradient(X[:, hang], t, axis=0), t, axis=0)   # (nt, nh, 3)
    joint = next(j for j in model.joints if j.name == move.joint)
    up = -model.gravity / np.linalg.norm(model.gravity)
    if move.kind == "slider":
        e = np.broadcast_to(joint.axis, (len(t), 3))
        a_rigid = a_max
    else:
        n = joint.axis
        c = model.coords[joint.at]
        top = suspension_node(model, [res.mass_names[k] for k in hang])
        s0 = (model.coords[top] if top is not None else X[0, hang[0]]) - c
        phi = res.drive_position[:, list(res.drive_names).index(move.joint)]
        cs, sn = np.cos(phi)[:, None], np.sin(phi)[:, None]
        s = s0 * cs + np.cross(n, s0) * sn + np.outer(1 - cs[:, 0], n * (n @ s0))
        e = np.cross(n, s)                             # tangent of the circle (x r)
        e -= (e @ up)[:, None] * up                    # its horizontal part
        lever = np.linalg.norm(e[0])
        e = e / np.linalg.norm(e, axis=1, keepdims=True)
        a_rigid = lever * a_max
    F = np.einsum("k,tkj,tj->t", m, acc, e)
    rigid = m.sum() * a_rigid
    i = int(np.argmax(np.abs(F)))
    lo, hi, text = standard.phi5_guidance(sudden=move.jerk == 0)
    return {"value": float(abs(F[i]) / rigid), "standard": [lo, hi], "standard_text": text,
            "kind": move.kind, "acceleration": float(a_rigid),
            "ramp_s": move.ramp, "jerk_time_s": move.jerk,
            "rigid_body_force_N": float(rigid),
            "peak_force_N": float(abs(F[i])), "peak_time_s": float(t[i]),
            "simulation": name, "clause": standard.CLAUSES["phi5"],
            "assumes": "computed on the operation engine (large motions, sway on, "
                       "undamped): the hanging masses' inertia force along the motion of "
                       "their suspension point (the slider's axis; for a hinge the "
                       "horizontal tangent of its circle) over their rigid-body force m a; "
                       "the carrier's own mass moves rigidly (phi5 = 1 for it)"}


# ----------------------------------------------------------------- phi4, 6, 7

def _phi4(model):
    return {"value": None, "standard": None, "clause": standard.CLAUSES["phi4"],
            "missing": "the model has no travel on a rail with a step or gap (no "
                       "travelling drive, no track irregularity): " + standard.PHI4_NEEDS}


def _phi6(phi2):
    return {"value": float(standard.phi6(phi2["value"])),
            "standard": float(standard.phi6(phi2["standard"])),
            "static_test": 1.0, "from": "phi2 (computed) and phi2 (standard, "
            f"{phi2['hoisting_class']}) of drive class {phi2['drive_class']}",
            "clause": standard.CLAUSES["phi6"],
            "assumes": "dynamic test: phi6 = 0.5 (1 + phi2) on a test load of at least "
                       "110 % of the rated load; static test: 1"}


def _phi7(model):
    return {"value": None, "standard": [1.25, 1.6], "clause": standard.CLAUSES["phi7"],
            "missing": "the model has no buffer (a travel drive running into an end stop "
                       "with a buffer's force-stroke curve): phi7 = 1.25 for a linear "
                       "buffer (xi <= 0.5) up to 1.6 (xi = 1, constant force) from "
                       "standard.phi7(buffer_characteristic(stroke, force))"}
