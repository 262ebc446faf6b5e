"""Shapers run through the operation engine (issue 17; docs/shaping.md): the scene of a
model run once per shaper on one drive, and the JSON ``shapers: {NAME:
{residual_sway_deg, move_time_s}}`` from the engine's own results (nonlinear kinematics,
elastic ropes, the hook-and-load double pendulum as modelled).
"""

import copy
import dataclasses

import numpy as np

from ...errors import ModelError


def _moves(profile):
    return profile if isinstance(profile, list) else [profile]


def with_profiles(model, drive, edit, extend=0.0):
    """A copy of the scene `model` whose drive `drive` has each profile move passed
    through ``edit(move dict, index) -> move dict`` (on a deep copy), its duration longer
    by `extend` s."""
    a = copy.deepcopy(model.analysis)
    drives = a.get("drives") or {}
    if drive not in drives or "profile" not in (drives[drive] or {}):
        names = ", ".join(str(k) for k in drives) or "none"
        raise ModelError(f"no drive '{drive}' with a profile in the scene (drives: "
                         f"{names})", model.scene_file or model.file, "analysis.drives")
    prof = drives[drive]["profile"]
    new = [edit(dict(p), k) for k, p in enumerate(_moves(prof))]
    drives[drive]["profile"] = new if isinstance(prof, list) else new[0]
    if extend:
        a["duration"] = float(a["duration"]) + float(extend)
    return dataclasses.replace(model, analysis=a)


def _strip(p, k):
    p.pop("shaper", None)
    return p


def shaped_model(model, drive, shaper, extend=True):
    """The scene with every move of `drive` shaped by `shaper` (a dict as in a scene's
    ``shaper:``, or None: unshaped), its duration lengthened by the time the shaper adds
    (so the swing after the last move is watched as long as in the scene)."""
    from ..operation.scene import parse

    def edit(p, k):
        p = _strip(p, k)
        if shaper is not None:
            p["shaper"] = dict(shaper)
        return p
    m = with_profiles(model, drive, edit)
    if not extend or shaper is None:
        return m
    end0 = parse(with_profiles(model, drive, _strip)).motion_end
    end1 = parse(m).motion_end
    return with_profiles(model, drive, edit, extend=max(end1 - end0, 0.0))


def summary(res, motion):
    """{residual_sway_deg (largest over the hanging masses), ..._by_node, max_sway_deg,
    move_time_s (the drive's first start to its last stop, exact from its `motion`),
    motion_end_s (the last drive of the scene stops)} of an engine result."""
    mv = motion.moves()
    resid = res.sway_residual_deg
    return {"residual_sway_deg": float(np.nanmax(resid)) if np.isfinite(resid).any()
            else None,
            "residual_sway_deg_by_node": {n: float(v) for n, v in
                                          zip(res.sway_names, resid)},
            "max_sway_deg": float(np.nanmax(res.sway_max_deg)) if len(res.sway_max_deg)
            else None,
            "move_time_s": float(mv[-1][1] - mv[0][0]) if mv else 0.0,
            "motion_end_s": float(res.motion_end)}


def compare(model, drive, kinds=("unshaped", "ZV", "ZVD", "ZVDD", "EI"), frequency="auto",
            modes=None, damping=0.0):
    """Run the scene once per shaper kind on drive `drive` -> the JSON document
    ``{"drive", "shapers": {NAME: {residual_sway_deg, move_time_s, extra_time_s, ...}}}``
    (residual: the engine's, the largest angle of each rope span above a hanging mass
    after the last drive stops; the scene's duration is lengthened by what each shaper
    adds, so every run watches the swing equally long)."""
    from ..operation.integrate import simulate
    from ..operation.scene import parse
    out = {}
    plain = parse(with_profiles(model, drive, _strip))
    base_end = float(next(x for x in plain.drives if x.name == drive).motion.t[-1])
    for kind in kinds:
        spec = None
        if kind != "unshaped":
            spec = {"type": kind, "frequency": frequency, "damping": damping}
            if modes is not None:
                spec["modes"] = list(modes)
        m = shaped_model(model, drive, spec)
        d = next(x for x in parse(m).drives if x.name == drive)
        res = simulate(m)
        row = summary(res, d.motion)
        row["extra_time_s"] = float(d.motion.t[-1]) - base_end
        row["frequencies_hz"] = sorted({float(w) / (2 * np.pi) for _, _, ws in
                                        getattr(d.motion, "shapers", ()) for w in ws})
        row["status"] = res.status
        out[kind] = row
    return {"drive": drive, "shapers": out}
