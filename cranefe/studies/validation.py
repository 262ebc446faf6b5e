"""Every validation case (closed form, paper, peer program) with its measured error:
results/validation.csv and docs/validation.md (`cranefe study validation`)."""

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


def peer_cases(quick):
    from ..model.generate import panels_for, to_yaml, tower_crane
    import json
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        path = to_yaml(tower_crane(panels=panels_for(3000)), os.path.join(tmp, "c.yaml"))
        r = modes(load(path), count=10)
        for module, label, kind in (("_floor", "independent numpy assembly", "peer program"),
                                    ("_opensees", "OpenSeesPy 3.7", "peer program")):
            p = subprocess.run([sys.executable, "-m", f"cranefe.studies.{module}", path,
                                "10"], capture_output=True, text=True)
            if p.returncode:
                continue             # OpenSeesPy is optional
            out = p.stdout
            ref = np.array(json.loads(out[out.index("{"):])["frequency_hz"])
            yield (f"lattice tower crane, 3000 DOFs, vs {label}", kind, "10 frequencies",
                   r.frequency_hz, ref)


def run(outdir, quick=False):
    groups = [hoist_cases(), pendulum_cases(), chain_cases(), rope_cases(),
              structure_cases(), peer_cases(quick)]
    rows = []
    for g in groups:
        for name, kind, reference, computed, exact in g:
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
                     "test_stability.py).\n\n"
                     "| case | kind | reference | max. relative error |\n|---|---|---|---|\n")
            for r in rows:
                fh.write(f"| {r['case']} | {r['kind']} | {r['reference']} | "
                         f"{r['max_relative_error']} |\n")
        written.append(md)
    return written
