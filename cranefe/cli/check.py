"""Check a model or scene: coordinates, effects, ropes (length, stiffness, static tension),
quasi-cyclic coordinates and warnings, without solving for modes."""

import numpy as np

HELP = "check a model: DOFs, ropes, static tensions, quasi-cyclic coordinates"


def add_arguments(p):
    p.add_argument("file", help="model or scene file (YAML)")
    p.add_argument("--json", action="store_true", help="print one JSON document")
    p.add_argument("--member-forces", action="store_true", help="list the trusses' axial "
                   "forces too (beams' end forces are always listed)")


def run(args):

    from ..system import assemble
    from ..condense import DENSE_MAX, condense
    from ..model import load, plausibility
    from ..model.load import _Reader, read_raw
    from ..model.ropes_data import designations
    from ..outputs.report import dumps
    from ..statics import solve_static
    model = load(args.file)
    system = assemble(model)
    static = system.static or solve_static(model)
    sp = system.springs
    warnings = []
    elements = []
    tension = static.rope_tension()
    for k, r in enumerate(model.ropes):
        rows = np.flatnonzero(sp.rope == k)
        e = {"name": f"rope {r.name}", "psi": r.psi, "path": list(r.points),
             "falls": int(r.falls.sum()),
             "length_m": float(sp.length[rows].sum() + (r.extra_length if len(rows) > 1
                                                        else 0.0)),
             "static_force": float(tension[k, 1]), "static_force_min": float(tension[k, 0])}
        if len(rows) == 1:
            e["stiffness"] = float(sp.c[rows[0]])
        else:
            e["elements"] = int(len(rows))
            e["stiffness"] = float(r.EA / e["length_m"])
        if tension[k, 0] <= 0:
            warnings.append(f"rope {r.name} is slack in the static state "
                            f"({tension[k, 0]:.4g} N)")
        elements.append(e)
    derived = designations(read_raw(model.file)[0], _Reader(model.file))
    for e, r in zip(elements, model.ropes):
        if r.name in derived:
            e["designation"] = derived[r.name]
    warnings += plausibility.warnings(model, tension)
    for k, s in enumerate(model.springs):
        row = int(np.flatnonzero(sp.spring == k)[0])
        elements.append({"name": f"spring {s.name}", "stiffness": float(sp.c[row]),
                         "psi": float(sp.psi[row]),
                         "static_force": float(static.element_force[row])})
    qc, massless = [], []
    if system.K.shape[0] <= DENSE_MAX:
        c = condense(system)
        qc, massless = list(c.quasi_cyclic), list(c.massless)
    for i, m in zip(model.masses.nodes, model.masses.inertia):
        if system.dofs.carrier[i] == -2 and np.any(m) and not _rotates(system.dofs, i):
            warnings.append(f"rotary inertia of the point mass at free node "
                            f"'{model.node_names[i]}' is ignored (no rotation there)")
    doc = {"model": model.name, "file": model.file, "scene": model.scene,
           "planar": model.planar, "effects": system.effects.as_dict(),
           "dofs": system.K.shape[0], "coordinates": list(system.dofs.labels),
           "quasi_cyclic": qc, "massless_condensed": massless,
           "constraints": [c.name for c in system.dofs.constraints],
           "elements": elements, "warnings": warnings,
           **_member_forces(model, system, static, args)}
    if args.json:
        print(dumps(doc))
        return 0
    _print(model, doc)
    return 0


def _print(model, doc):
    """The human-readable report of `run`'s document."""
    qc, massless = doc["quasi_cyclic"], doc["massless_condensed"]
    eff = ", ".join(f"{k}={v}" for k, v in doc["effects"].items())
    print(f"{model.name} ({'planar x-z' if model.planar else '3D'}): {doc['dofs']} "
          f"coordinates; effects: {eff}")
    coords = doc["coordinates"]
    shown = ", ".join(coords if len(coords) <= 24 else coords[:12] + ["..."] + coords[-4:])
    print(f"  coordinates: {shown}")
    if qc:
        print(f"  quasi-cyclic: {', '.join(qc)}")
    if massless:
        print(f"  massless, condensed statically: {', '.join(massless)}")
    if doc["constraints"]:
        print(f"  constraints: {', '.join(doc['constraints'])}")
    print(f"  {'element':<28} {'length [m]':>11} {'stiffness':>12} {'static force':>13}")
    for e in doc["elements"]:
        length = f"{e['length_m']:.4g}" if "length_m" in e else "-"
        unit = "N m/rad" if e["name"].startswith("spring") and "length_m" not in e else "N/m"
        force = f"{e['static_force']:>13.5g}"
        if e.get("elements"):
            force = f"{e['static_force_min']:.5g}..{e['static_force']:.5g}"
            unit += f", {e['elements']} elements"
        print(f"  {e['name']:<28} {length:>11} {e['stiffness']:>12.4g} {force:>13}"
              f"  ({unit})")
        if "path" in e:
            print(f"    path: {' - '.join(e['path'])} ({e['falls']} rope parts)")
        if "designation" in e:
            print(f"    {_designation(e['designation'])}")
    for w in doc["warnings"]:
        print(f"  warning: {w}")


def _designation(d):
    """One line: what a rope's diameter and construction gave (cranefe.model.ropes_data)."""
    own = [k for k, f in (("EA", "EA_from"), ("mass_per_length", "mass_from"))
           if d[f] == "given"]
    return (f"designation: {d['diameter_m'] * 1e3:g} mm {d['class']} {d['core']} "
            f"(EN 12385-4): metallic area {d['metallic_area_m2'] * 1e6:.4g} mm^2 "
            f"(fill factor {d['fill_factor']:.3f}), EA {d['EA_N']:.4g} N (modulus "
            f"{d['modulus_pa'] / 1e9:.4g} GPa, {d['modulus_from']}), "
            f"{d['mass_per_length_kg_m']:.4g} kg/m, minimum breaking force "
            f"{d['min_breaking_force_N'] / 1e3:.4g} kN (grade 1770)"
            + (f"; your own {' and '.join(own)} used" if own else ""))


def _rotates(dofs, i):
    """Whether node i has rotations (beams meet there): a point mass's rotary inertia
    counts there."""
    return dofs.T[dofs.layout.rot(i)].nnz > 0


def _member_forces(model, system, static, args=None):
    """{"member_forces": [...]}: section forces at the ends of beam members (with
    --member-forces also of trusses) in the static state, when the structure is flexible
    and has them ({} otherwise)."""
    from ..outputs.member_forces import member_end_forces
    mm = system.dofs.members
    forces = member_end_forces(model, system.dofs.layout, mm, static.u,
                               trusses=getattr(args, "member_forces", False)) if mm else []
    return {"member_forces": forces} if forces else {}
