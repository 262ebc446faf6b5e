"""Generator of lattice tower-crane models of a chosen size (pin-jointed trusses).

The mast is a square lattice (4 chords, horizontal frames with a plan diagonal so each
frame is rigid in its plane, one diagonal per face and panel: a braced box per panel,
statically determinate and stable). Masts taller than one free-standing height are tied
to the building every `tie_every` panels (three tie bars to anchors), as real climbing
cranes are. A triangular jib and counter-jib lattice, a tower head with pendants to both,
trolley and counterweight masses, and a hook load on a 2-fall hoist rope complete it.
Sizes: about 12 coordinates per mast panel; the jib adds a fixed amount.
"""

import numpy as np

PANEL = 2.5          # m, mast panel height and jib panel length
WIDTH = 2.0          # m, mast square
STEEL = {"E": 2.1e11, "rho": 7850.0}
CHORD_A, BRACE_A, TIE_A = 7.6e-3, 1.9e-3, 4.0e-3      # m^2 (L200x20, L100x10, ...)


class _Builder:
    def __init__(self):
        self.names, self.coords = [], []
        self.index = {}
        self.groups = {}

    def node(self, name, xyz):
        self.index[name] = len(self.names)
        self.names.append(name)
        self.coords.append(np.asarray(xyz, dtype=float))
        return name

    def bar(self, group, a, b):
        self.groups.setdefault(group, []).append((a, b))


MAX_PANELS = 40_000       # mast panels: about 5e5 coordinates, beyond any real crane


def tower_crane(panels=16, jib_panels=20, counter_panels=6, tie_every=12, load=8000.0):
    """A model dict (model-format.md, with member `pairs`) of a lattice tower crane.

    Length: the generated crane written out part by part (mast, jib, counter-jib,
    ropes), as the module docstring sketches it.
    """
    if not 1 <= panels <= MAX_PANELS or tie_every < 1:
        raise ValueError(f"panels must be 1..{MAX_PANELS} and tie_every >= 1")
    B = _Builder()
    half = WIDTH / 2
    corners = [(-half, -half), (half, -half), (half, half), (-half, half)]
    for lv in range(panels + 1):
        for c, (x, y) in enumerate(corners):
            B.node(f"M{lv}_{c}", (x, y, lv * PANEL))
    for lv in range(panels + 1):
        for c in range(4):
            if lv:
                B.bar("mast_chords", f"M{lv - 1}_{c}", f"M{lv}_{c}")
                # face diagonal, alternating direction from panel to panel
                a, b = (c, (c + 1) % 4) if lv % 2 else ((c + 1) % 4, c)
                B.bar("mast_braces", f"M{lv - 1}_{a}", f"M{lv}_{b}")
            B.bar("mast_braces", f"M{lv}_{c}", f"M{lv}_{(c + 1) % 4}")
        B.bar("mast_braces", f"M{lv}_0", f"M{lv}_2")              # plan diagonal
    ground = [f"M0_{c}" for c in range(4)]
    for lv in range(tie_every, panels, tie_every):                # ties to the building
        z = lv * PANEL
        for k, (c, anchor) in enumerate(((0, (-half - 4, -half, z)),
                                         (3, (-half - 4, half, z)),
                                         (0, (-half, -half - 4, z)))):
            ground.append(B.node(f"A{lv}_{k}", anchor))
            B.bar("ties", f"M{lv}_{c}", f"A{lv}_{k}")
    top = panels * PANEL

    def lattice(prefix, n, sign, z0):
        """Triangular boom along sign*x from the mast top: 2 bottom chords, 1 top."""
        for k in range(1, n + 1):
            x = sign * (half + k * PANEL)
            B.node(f"{prefix}{k}_0", (x, -half, z0))
            B.node(f"{prefix}{k}_1", (x, half, z0))
            B.node(f"{prefix}{k}_t", (x, 0.0, z0 + 1.5))
        root = ({"0": f"M{panels}_1", "1": f"M{panels}_2"} if sign > 0 else
                {"0": f"M{panels}_0", "1": f"M{panels}_3"})
        B.node(f"{prefix}0_t", (sign * half, 0.0, z0 + 1.5))
        B.bar(f"{prefix}_braces", root["0"], f"{prefix}0_t")
        B.bar(f"{prefix}_braces", root["1"], f"{prefix}0_t")
        B.bar(f"{prefix}_braces", root["0"], root["1"])
        prev = {"0": root["0"], "1": root["1"], "t": f"{prefix}0_t"}
        for k in range(1, n + 1):
            cur = {s: f"{prefix}{k}_{s}" for s in ("0", "1", "t")}
            for s in ("0", "1", "t"):
                B.bar(f"{prefix}_chords", prev[s], cur[s])
            B.bar(f"{prefix}_braces", cur["0"], cur["1"])           # cross frame
            B.bar(f"{prefix}_braces", cur["0"], cur["t"])
            B.bar(f"{prefix}_braces", cur["1"], cur["t"])
            B.bar(f"{prefix}_braces", prev["0"], cur["1"])           # face diagonals
            B.bar(f"{prefix}_braces", prev["0"], cur["t"])
            B.bar(f"{prefix}_braces", prev["1"], cur["t"])
            prev = cur
        return prev

    lattice("J", jib_panels, 1.0, top)
    lattice("C", counter_panels, -1.0, top)
    # tower head (apex above the mast) with pendants to the jib and the counter-jib
    B.node("HEAD", (0.0, 0.0, top + 7.0))
    for c in range(4):
        B.bar("head", f"M{panels}_{c}", "HEAD")
    jt = f"J{(2 * jib_panels) // 3}_t"
    ct = f"C{counter_panels}_t"
    B.bar("ties", "HEAD", jt)
    B.bar("ties", "HEAD", ct)
    # trolley at mid-jib, counterweight at the counter-jib end, hook load on the rope
    k = jib_panels // 2
    trolley = f"J{k}_0"
    tx = B.coords[B.index[trolley]]
    B.node("HOOK", (tx[0], tx[1], max(tx[2] - 20.0, 2.0)))
    masses = {trolley: 600.0, f"C{counter_panels}_0": 6000.0,
              f"C{counter_panels}_1": 6000.0, "HOOK": load + 250.0}
    members = {}
    for group, bars in B.groups.items():
        area = CHORD_A if "chord" in group else TIE_A if group in ("ties", "head") \
            else BRACE_A
        members[group] = {"type": "truss", "pairs": [list(p) for p in bars],
                          "A": area, "mass": "lumped", **STEEL}
    return {
        "cranefe": 1,
        "name": (f"Lattice tower crane: {panels * PANEL:g} m mast, "
                 f"{jib_panels * PANEL:g} m jib (generated)"),
        "nodes": {n: [round(float(v), 6) for v in xyz] for n, xyz in zip(B.names, B.coords)},
        "ground": ground,
        "masses": masses,
        "members": members,
        "ropes": {"hoist": {"EA": 2.8e7, "mass_per_length": 1.35, "psi": 0.2,
                            "path": [trolley, {"node": "HOOK", "falls": 2}]}},
        "effects": {"structure": "flexible", "sway": False},
    }


def dofs_estimate(panels, jib_panels=20, counter_panels=6):
    return 12 * panels + 9 * (jib_panels + counter_panels) + 10


def panels_for(dofs, jib_panels=20, counter_panels=6):
    """Mast panels giving about `dofs` coordinates."""
    return max(4, int(round((dofs - 9 * (jib_panels + counter_panels) - 10) / 12)))


def to_yaml(model, path, header=""):
    """Write a generated model as YAML (flow style for the long lists)."""
    import yaml
    Dumper = getattr(yaml, "CSafeDumper", yaml.SafeDumper)
    text = yaml.dump(model, Dumper=Dumper, default_flow_style=None, sort_keys=False,
                     width=100)
    from ..outpaths import write_text
    return write_text(path, header + text)


def with_meshes(model, yaml_path):
    """Move the members into VTU files beside yaml_path (one per member group); the YAML
    keeps only the nodes something else refers to. Returns the new model dict."""
    import os

    import meshio

    from ..outpaths import atomic
    folder = os.path.dirname(os.path.abspath(yaml_path))
    base = os.path.splitext(os.path.basename(yaml_path))[0]
    names = list(model["nodes"])
    index = {n: i for i, n in enumerate(names)}
    X = np.array([model["nodes"][n] for n in names], dtype=float)
    members = {}
    for group, m in model["members"].items():
        pairs = np.array([[index[a], index[b]] for a, b in m["pairs"]])
        used, inverse = np.unique(pairs, return_inverse=True)
        fname = f"{base}_{group}.vtu"
        with atomic(os.path.join(folder, fname), ".vtu") as tmp:
            meshio.write(tmp, meshio.Mesh(X[used], [("line", inverse.reshape(-1, 2))]),
                         file_format="vtu")
        members[group] = {k: v for k, v in m.items() if k != "pairs"}
        members[group]["mesh"] = fname
    keep = set(model["ground"]) | set(model["masses"])
    for r in model["ropes"].values():
        keep |= {p["node"] if isinstance(p, dict) else p for p in r["path"]}
    out = dict(model, members=members)
    out["nodes"] = {n: v for n, v in model["nodes"].items() if n in keep}
    return out
