"""Every validation case (closed form, paper, peer program) with its measured error:
results/validation.csv and docs/validation.md (`cranefe study validation`).

A peer program that is not installed (OpenSeesPy, Exudyn: optional, ``pip install
'cranefe[peers]'``) keeps its row, marked ``missing (... not installed)``: the table
always shows every comparison it is meant to hold."""

import os
import subprocess
import sys
import textwrap
from dataclasses import replace

import numpy as np

from .. import cases
from ..model import load
from ..analysis.modal import drive_reduction, modes
from ._common import write_csv

DESCRIPTION = "the table of validation cases and their measured errors"
G = cases.G


def _solve(text, **effects):
    model = load("case.yaml", textwrap.dedent(text))
    return modes(model, replace(model.effects, **effects) if effects else None)


def _elastic(r):
    return np.sort(r.omega[~r.rigid])


def hoist_cases():
    for falls in (1, 2, 3, 4):
        text, ex = cases.two_mass_hoist(falls=falls)
        yield (f"two-mass hoist, free drum, {falls} fall(s)", "closed form",
               "w^2 = k (n^2/m + R^2/J)", _elastic(_solve(text)), ex["omega"])
        r = _solve(text, drive="held")
        yield (f"two-mass hoist, braked drum, {falls} fall(s)", "closed form",
               "w^2 = n^2 k / m", _elastic(r), ex["omega_reduced"])
    text, ex = cases.two_mass_hoist(falls=2)
    model = load("case.yaml", text)
    red = modes(model, replace(model.effects, drive="reduced"))
    err = drive_reduction(model, red)["modes"][0]["relative_error"]
    yield ("drive reduction error (Heletiy eq. 10, corrected)", "closed form",
           "dw^2/w^2 = m r^2 / (m r^2 + J)", np.array([1 - (1 + err) ** 2]),
           np.array([ex["error_w2"]]))


def pendulum_cases():
    l = 12.0
    for falls in (1, 4):
        r = _solve(f"""
            cranefe: 1
            plane: xz
            nodes: {{S: [0, 0, 30], B: [0, 0, {30 - l}]}}
            ground: [S]
            masses: {{B: 2000}}
            ropes:
              r: {{EA: 1.0e7, path: [S, {{node: B, falls: {falls}}}]}}
            """)
        yield ("single pendulum" if falls == 1 else f"pendulum on a {falls}-fall tackle",
               "closed form", "sqrt(g/l)",
               r.omega[:1], np.array([np.sqrt(G / l)]))
    text, ex = cases.double_pendulum()
    yield ("double pendulum", "closed form", "quartic m1 l1 l2 w^4 - ... = 0",
           _solve(text).omega[:2], ex["omega"])


def chain_cases():
    text = """
        cranefe: 1
        plane: xz
        gravity: [0, 0, 0]
        nodes: {A: [0, 0, 0], B: [1, 0, 0]}
        masses: {A: 1000, B: 2000}
        springs:
          - {name: k, type: axial, nodes: [A, B], stiffness: 1.0e6}
        effects: {sway: false}
        """
    r = _solve(text)
    yield ("free-free two-mass chain (1 zero frequency)", "closed form",
           "w^2 = k (1/m1 + 1/m2) = 1500", np.r_[r.rigid.sum(), r.omega[1] ** 2],
           np.array([1.0, 1500.0]))
    text, ex = cases.spring_chain(200)
    r = modes(load("c.yaml", text), count=10)
    yield ("fixed-free chain of 200 masses", "closed form",
           "w_j = 2 sqrt(k/m) sin((2j-1) pi / (2(2N+1)))", r.omega, ex["omega"][:10])


ROPE_REFERENCES = {
    "heavy_rope_end_mass": ("heavy vertical rope with an end mass, longitudinal",
                            "beta tan beta = mu L / M"),
    "hanging_chain": ("hanging chain, lateral", "w_n = (j0_n / 2) sqrt(g / L)"),
    "tensioned_span": ("span tensioned by a counterweight over a sheave",
                       "w_n = (n pi / l) sqrt(S / mu)"),
}


def rope_cases():
    for name, make in cases.ROPE_CASES.items():
        text, ex = make()
        model = load("c.yaml", text)
        r = modes(model, replace(model.effects, rope_mass=32), count=12)
        label, reference = ROPE_REFERENCES[name]
        yield (f"{label}, 32 elements per fall (3 modes)", "closed form", reference,
               cases.matched(r.omega, ex["omega"][:3]), ex["omega"][:3])


def structure_cases():
    E, A, I, rho = 2.1e11, 1.0e-2, 2.0e-4, 7850.0
    r = _solve(f"""
        cranefe: 1
        plane: xz
        gravity: [0, 0, 0]
        nodes: {{O: [0, 0, 0], T: [10, 0, 0]}}
        ground: [O]
        members:
          b: {{type: beam, nodes: [O, T], E: {E}, A: {A}, Iy: {I}, rho: {rho},
              elements: 16}}
        effects: {{structure: flexible}}
        """)
    bl = np.array([1.875104068711961, 4.694091132974175, 7.854757438237613])
    yield ("cantilever beam, 16 elements", "closed form", "beta_n L = 1.8751, 4.6941, 7.8548",
           r.omega[:3], bl**2 * np.sqrt(E * I / (rho * A)) / 100)
    text, ex = cases.loaded_column()
    yield ("P-delta of a loaded column, 16 elements", "closed form",
           "k(P) = P / (L (tan kL / kL - 1))", _solve(text).omega[:1], ex["omega"])


def _version(dist):
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version(dist)
    except PackageNotFoundError:
        return None


def peer_cases(quick):
    from ..model.generate import panels_for, to_yaml, tower_crane
    import json
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        path = to_yaml(tower_crane(panels=panels_for(3000)), os.path.join(tmp, "c.yaml"))
        r = modes(load(path), count=10)
        for module, label, dist in (("_floor", "independent numpy assembly", None),
                                    ("_opensees", "OpenSeesPy", "openseespy")):
            case = f"lattice tower crane, 3000 DOFs, vs {label}"
            if dist is not None and _version(dist) is None:
                yield (case, "peer program", "10 frequencies", None, f"{label} not installed")
                continue
            p = subprocess.run([sys.executable, "-m", f"cranefe.studies.{module}", path,
                                "10"], capture_output=True, text=True)
            if dist is not None:
                case += f" {_version(dist)}"
            if p.returncode:
                last = (p.stderr.strip().splitlines() or ["no output"])[-1]
                yield (case, "peer program", "10 frequencies", None, f"failed: {last}")
                continue
            out = p.stdout
            ref = np.array(json.loads(out[out.index("{"):])["frequency_hz"])
            yield (case, "peer program", "10 frequencies", r.frequency_hz, ref)
    yield from spatial_peer_cases()


# A spreader beam (rigid body, full inertia tensor) hung on six inclined ropes from six
# anchors (statically determinate: the tensions follow from its six equilibrium
# equations), with a hook load on a rope below an off-centre point; spatial, sway on:
# every frequency depends on the ropes' tension stiffness and the body's load stiffness.
SPREADER_COM = (0.0, 0.0, 20.0)
SPREADER_POINTS = ((1.38, -0.36, 0.72), (1.58, 0.1, 0.57), (-0.42, 0.83, 0.69),
                   (-1.29, 0.66, 0.61), (-1.16, -0.67, 0.7), (-0.23, -1.05, 0.66))
SPREADER_ANCHORS = ((3.09, -2.89, 28.5), (3.37, 2.48, 28.81), (1.93, 3.37, 28.97),
                    (-4.16, 0.14, 29.21), (-4.56, -1.02, 29.16), (1.97, -3.58, 29.13))


def spreader_text():
    """The spatial peer case as a model file (9 coordinates: 6 of the body, 3 of the hook)."""
    fmt = lambda v: "[" + ", ".join(f"{x:.10g}" for x in v) + "]"       # noqa: E731
    c = SPREADER_COM
    lines = ["cranefe: 1", "name: spreader on six ropes with a hook load", "nodes:"]
    lines += [f"  A{i}: {fmt(a)}" for i, a in enumerate(SPREADER_ANCHORS, 1)]
    lines += [f"  P{i}: {fmt(np.add(p, c))}" for i, p in enumerate(SPREADER_POINTS, 1)]
    lines += ["  T: [0.3, -0.2, 19.2]", "  H: [0.3, -0.2, 14.2]",
              "ground: [A1, A2, A3, A4, A5, A6]", "masses: {H: 1500}", "bodies:",
              "  spreader:", "    mass: 4000", f"    com: {fmt(c)}",
              "    inertia: [[3000, 120, -80], [120, 5200, 60], [-80, 60, 6500]]",
              "    nodes: [P1, P2, P3, P4, P5, P6, T]", "ropes:"]
    lines += [f"  r{i}: {{EA: 2.0e7, path: [A{i}, P{i}]}}" for i in range(1, 7)]
    lines += ["  hook: {EA: 5.0e6, path: [T, H]}", "effects: {sway: true}", ""]
    return "\n".join(lines)


def exudyn_omega(text):
    """Natural frequencies (rad/s, ascending) and rope tensions of a model of rigid bodies,
    point masses and single-span ropes, computed by Exudyn (an independent multibody
    program; `pip install exudyn`). The model file is read with PyYAML, not cranefe.

    The rope tensions S come from the equilibrium of every body (forces and moments about
    its centre of mass) and free point mass in the reference geometry (least squares;
    exact for a determinate system, checked). Each rope is an Exudyn SpringDamper of
    stiffness k = EA / L with reference length L - S / k, so the reference geometry is
    Exudyn's static equilibrium with these tensions; bodies use Tait-Bryan rotations (no
    constraints). Exudyn linearises its nonlinear equations there, so its stiffness holds
    the ropes' tension stiffness and the bodies' load stiffness by construction.
    Raises ImportError without Exudyn.

    Length: an independent peer program (equilibrium, Exudyn model, linearisation) kept
    in one piece so that it reads as the peer's script, sharing nothing with cranefe.
    """
    import exudyn as exu
    import yaml
    from exudyn.utilities import RigidBodyInertia
    d = yaml.safe_load(text)
    vec = lambda v: np.array([float(x) for x in v])                    # noqa: E731
    X = {k: vec(v) for k, v in d["nodes"].items()}
    g = vec(d.get("gravity", [0, 0, -9.81]))
    ground = set(d.get("ground", []))
    bodies = d.get("bodies", {})
    owner = {n: b for b, spec in bodies.items() for n in spec["nodes"]}
    masses = {k: float(v) for k, v in d.get("masses", {}).items()}
    parts = [("body", b) for b in bodies] + [("mass", n) for n in masses if n not in owner]
    row = {p: i for i, p in enumerate(parts)}
    com = {b: vec(spec["com"]) for b, spec in bodies.items()}

    def part(n):
        return None if n in ground else ("body", owner[n]) if n in owner else ("mass", n)

    ropes = d["ropes"]
    A = np.zeros((6 * len(parts), len(ropes)))
    rhs = np.zeros(6 * len(parts))
    spans = []
    for j, r in enumerate(ropes.values()):
        a, b = r["path"]
        e = X[b] - X[a]
        L = float(np.linalg.norm(e))
        e = e / L
        spans.append((a, b, L, float(r["EA"]) / L))
        for n, sign in ((a, 1.0), (b, -1.0)):          # S pulls a towards b, b towards a
            p = part(n)
            if p is not None:
                A[6 * row[p]:6 * row[p] + 3, j] += sign * e
                if p[0] == "body":
                    A[6 * row[p] + 3:6 * row[p] + 6, j] += np.cross(X[n] - com[p[1]],
                                                                    sign * e)
    for p in parts:
        m = float(bodies[p[1]]["mass"]) if p[0] == "body" else masses[p[1]]
        rhs[6 * row[p]:6 * row[p] + 3] -= m * g
    S = np.linalg.lstsq(A, rhs, rcond=None)[0]
    if np.abs(A @ S - rhs).max() > 1e-9 * np.abs(rhs).max():
        raise ValueError("the peer model is not in equilibrium with rope tensions alone")
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    item = {None: mbs.CreateGround()}
    for b, spec in bodies.items():
        inertia = spec["inertia"]
        inertia = (np.array([vec(r) for r in inertia]) if isinstance(inertia[0], list)
                   else np.diag(vec(inertia)))
        item[("body", b)] = mbs.CreateRigidBody(
            referencePosition=list(com[b]), gravity=list(g),
            inertia=RigidBodyInertia(float(spec["mass"]), inertia),
            nodeType=exu.NodeType.RotationRxyz)
    for n, m in masses.items():
        if n not in owner:
            item[("mass", n)] = mbs.CreateMassPoint(referencePosition=list(X[n]),
                                                    mass=m, gravity=list(g))

    def local(n):
        p = part(n)
        return X[n] if p is None else X[n] - com[p[1]] if p[0] == "body" else np.zeros(3)

    for (a, b, L, k), s in zip(spans, S):
        mbs.CreateSpringDamper(itemNumbers=[item[part(a)], item[part(b)]],
                               localPosition0=list(local(a)), localPosition1=list(local(b)),
                               referenceLength=L - s / k, stiffness=k)
    mbs.Assemble()
    w2 = np.sort(np.asarray(mbs.ComputeODE2Eigenvalues()[0]))
    return np.sqrt(np.abs(w2)), dict(zip(ropes, S))


def spatial_peer_cases():
    case = "spreader on six ropes with a hook load, spatial, sway on (9 DOFs), vs Exudyn"
    reference = "9 frequencies: tension and load stiffness"
    if _version("exudyn") is None:
        yield (case, "peer program", reference, None, "Exudyn not installed")
        return
    text = spreader_text()
    r = modes(load("spreader.yaml", text))
    yield (f"{case} {_version('exudyn')}", "peer program", reference, r.omega,
           exudyn_omega(text)[0])


def run(outdir, quick=False):
    groups = [hoist_cases(), pendulum_cases(), chain_cases(), rope_cases(),
              structure_cases(), peer_cases(quick)]
    rows = []
    for g in groups:
        for name, kind, reference, computed, exact in g:
            if computed is None:                 # a peer that is missing or failed
                rows.append({"case": name, "kind": kind, "reference": reference,
                             "max_relative_error": f"missing ({exact})"})
                continue
            err = float(np.max(np.abs(np.asarray(computed) / np.asarray(exact) - 1)))
            # below 1e-11 the digits are round-off that varies with the peer's solver
            rows.append({"case": name, "kind": kind, "reference": reference,
                         "max_relative_error": f"{err:.1e}" if err >= 1e-11 else "< 1e-11"})
    written = [write_csv(outdir, "validation.csv", rows)]
    docs = os.path.join(os.path.dirname(os.path.abspath(outdir)), "docs")
    if os.path.isdir(docs):
        md = os.path.join(docs, "validation.md")
        with open(md, "w") as fh:
            fh.write("# Validation cases\n\nRegenerated by `cranefe study validation` (also "
                     "part of `cranefe study accuracy`), which writes this page and "
                     "`results/validation.csv`. Each row is computed by cranefe from a "
                     "model file and compared with the reference; the error is the largest "
                     "relative error over the frequencies compared. The tests check the "
                     "same cases with tolerances (tests/test_closed_forms.py, "
                     "test_rope_elements.py, test_members.py, test_large_models.py, "
                     "test_stability.py, test_validation_study.py; the values of this "
                     "table: test_studies.py).\n\n"
                     "Peer programs are optional: `pip install 'cranefe[peers]'` (Exudyn); "
                     "OpenSeesPy needs `apt-get install libblas3` then `pip install "
                     "openseespy`. A peer that is not installed keeps its row, marked "
                     "missing. The spatial case (a spreader on six inclined ropes with a "
                     "hook load, sway on) compares the tension stiffness of the ropes and "
                     "the load stiffness of the rigid body with Exudyn, which linearises "
                     "its own nonlinear multibody equations about the same static state "
                     "(`validation.exudyn_omega`).\n\n"
                     "| case | kind | reference | max. relative error |\n|---|---|---|---|\n")
            for r in rows:
                fh.write(f"| {r['case']} | {r['kind']} | {r['reference']} | "
                         f"{r['max_relative_error']} |\n")
        written.append(md)
    return written
