"""Member forces in the archive, in `cranefe show`, in the pictures' colours, and
members given in mesh files with supports, releases and profile sections (issue 19)."""

import json
import math
import textwrap

import numpy as np
import pytest

from cranefe.cli import main
from cranefe.outputs import archive

E, G = 2.1e11, 8.1e10
B, H = 0.1, 0.2                      # rectangle: Iy = B H^3 / 12 (strong), Wy = B H^2 / 6


def _write(tmp_path, text, name="m.yaml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return str(path)


def _cantilever(L=4.0, m=1000.0, rho=0.0, elements=4):
    """A 3D cantilever along x (rectangle B x H, depth along z), a point mass at T."""
    return f"""
    cranefe: 1
    nodes: {{O: [0, 0, 0], T: [{L}, 0, 0]}}
    ground: [O]
    members:
      b: {{type: beam, nodes: [O, T], E: {E}, G: {G}, rho: {rho}, orientation: [0, 0, 1],
          elements: {elements}, section: {{shape: rectangle, b: {B}, h: {H}}}}}
    masses: {{T: {m}}}
    effects: {{structure: flexible}}
    """


def test_modes_archive_keeps_the_member_forces_of_json(tmp_path, capsys):
    """`modes --member-forces --archive`: the group read back holds the same numbers as
    --json (the JSON's piece ends are elements 0 and 3 of the four), and `show` prints
    each member's largest |sigma| over the modes."""
    model = _write(tmp_path, _cantilever(rho=7850.0))
    out = tmp_path / "m.h5"
    assert main(["modes", model, "--count", "4", "--json", "--member-forces",
                 "--member-forces-scale", "0.01", "--archive", str(out)]) == 0
    doc = json.loads(capsys.readouterr().out)["member_forces"]
    mf = archive.read(out).results["member_forces"]
    assert mf.kind == "modes" and mf.scale == doc["scale"] == {
        "normalisation": "largest node translation", "amplitude_m": 0.01}
    assert mf.forces.shape == (4, 4, 2, 6) and mf.element_member == ("b",) * 4
    assert mf.pieces == [("b", "beam", "O", "T", 0, 3)]
    names = ("N", "Vy", "Vz", "T", "My", "Mz")
    for k, mode in enumerate(doc["modes"]):
        (p,) = mode["pieces"]
        # the JSON is written from these very arrays: equal to the last bit
        assert [p["start"][n] for n in names] == mf.forces[k, 0, 0].tolist()
        assert [p["end"][n] for n in names] == mf.forces[k, 3, 1].tolist()
        assert p["start"]["sigma_max"] == mf.stress[k, 0, 0, 0]
    peak = np.nanmax(np.abs(mf.stress))
    assert main(["show", str(out)]) == 0
    text = capsys.readouterr().out
    assert "results/member_forces (MemberForces):" in text
    assert f"{peak / 1e6:.6g}" in text
    assert main(["show", str(out), "--json"]) == 0
    shown = json.loads(capsys.readouterr().out)["documents"]["member_forces"]
    (row,) = shown["peak_stress"]
    assert row["member"] == "b" and row["sigma_abs_max_Pa"] == peak
    # at 0.01 m tip amplitude the first bending mode's root stress is of the order of
    # 3 E I y / L^3 * L * c / I = 3 E c y / L^2 (a static tip load's shape): the peak over
    # four modes is larger than that (higher modes bend more for the same amplitude)
    assert peak > 3 * E * (H / 2) * 0.01 / 4.0**2


def test_simulate_archive_keeps_the_envelope(tmp_path, capsys):
    """A step force F at the tip mass of a massless cantilever (as in
    tests/test_member_forces.py): the archived envelope's clamp moment runs from m g L
    to (m g + 2 F) L, within the output-time sampling's 1e-4."""
    L, m, g, F = 4.0, 1000.0, 9.81, 5000.0
    I = B * H**3 / 12
    T = 2 * math.pi * math.sqrt(m / (3 * E * I / L**3))
    _write(tmp_path, _cantilever(L, m), "cant.yaml")
    scene = _write(tmp_path, f"""
    cranefe: 1
    scene: step load at the tip
    model: cant.yaml
    analysis:
      type: transient
      duration: {1.5 * T}
      time_step: {T / 360}
      forces:
        T: {{force: [0, 0, {-F}]}}
    """, "scene.yaml")
    out = tmp_path / "t.h5"
    assert main(["simulate", scene, "--json", "--member-forces", "--archive",
                 str(out)]) == 0
    doc = json.loads(capsys.readouterr().out)["member_forces"]
    arc = archive.read(out)
    assert set(arc.results) == {"transient", "member_forces"}
    mf = arc.results["member_forces"]
    assert mf.kind == "envelope" and mf.forces.shape == (2, 4, 2, 6)
    lo, hi = mf.forces[0, 0, 0, 4], mf.forces[1, 0, 0, 4]
    assert lo == doc["pieces"][0]["start"]["min"]["My"]
    assert lo == pytest.approx(m * g * L, rel=1e-6)
    assert hi == pytest.approx((m * g + 2 * F) * L, rel=1e-4)
    assert mf.stress[1, 0, 0, 0] == pytest.approx((m * g + 2 * F) * L * (H / 2) / I,
                                                  rel=1e-4)
    import h5py
    with h5py.File(out, "r") as h:
        d = h["results/member_forces"]
        assert d["bending_moment"].attrs["units"] == "N m"
        assert d["bending_moment"][1, 0, 0, 0] == hi
        assert d["extreme_fibre_stress"].attrs["units"] == "Pa"
        assert list(d["section_forces"].attrs["components"]) == \
            ["N", "Vy", "Vz", "T", "My", "Mz"]


# ------------------------------------------------------------------ pictures' colours

def _viridis_fraction(rgb):
    """The position 0..1 in viridis of the colour nearest to rgb (and its distance)."""
    from matplotlib import colormaps
    table = colormaps["viridis"](np.linspace(0, 1, 256))[:, :3] * 255
    d = np.linalg.norm(table - np.asarray(rgb, dtype=float), axis=1)
    return np.argmin(d) / 255, d.min()


def test_members_are_coloured_by_their_stress(tmp_path):
    """A cantilever of 8 elements (a small tip mass) in its first bending mode in the
    x-z plane (view xz): the pixel at the middle of the root element has the viridis
    colour of that element's mean end stress over the mode's peak (high end), the one
    at the middle of the tip element that of its own (low end); the bar is in MPa and runs
    from 0 to the mode's peak. Colours are drawn unlit, so only anti-aliasing at a
    line's edge separates a pixel from its map colour (measured: 0.002 and 0.004 of
    the map): 0.05."""
    from cranefe.analysis.modal import modes
    from cranefe.model import load
    from cranefe.outputs import render
    from cranefe.outputs.member_forces import modal_member_forces
    from cranefe.system import assemble
    model = load(_write(tmp_path, _cantilever(rho=7850.0, m=50.0, elements=8)))
    system = assemble(model)
    result = modes(model, count=2, system=system)
    tip = model.node_names.index("T")
    k = int(np.argmax(np.abs(result.node_shapes[:, tip, 2])))     # bending in x-z
    mf = modal_member_forces(model, system.dofs, result.shapes, result.node_shapes, 0.01)
    scene = render.ModeScene(model, system.dofs, result, size=(600, 400), view="xz",
                             member_forces=mf)
    try:
        scene.show(k)
        img = scene.image()[:, :, :3]
        sigma = np.fmax(*np.abs(np.moveaxis(mf.stress[k], -1, 0))) / 1e6      # (8, 2)
        peak = sigma.max()
        assert scene.stress_actor.mapper.scalar_range == pytest.approx((0.0, peak))
        assert render.STRESS_TITLE in scene.p.scalar_bars and "MPa" in render.STRESS_TITLE
        pts = np.asarray(scene.mesh.points, dtype=float) + scene.disp[k]
        ends = pts[scene.member_points].reshape(-1, 2, 3)
        seen = []
        for e in (0, 7):
            expected = sigma[e].mean() / peak
            f, dist = _viridis_fraction(img[tuple(scene.pixels([ends[e].mean(0)])[0])])
            assert dist < 30 and f == pytest.approx(expected, abs=0.05), (e, f, expected)
            seen.append(f)
        assert seen[0] > 0.8 and seen[1] < 0.2
    finally:
        scene.close()


def test_color_stress_needs_images_and_members(tmp_path, capsys):
    model = _write(tmp_path, _cantilever())
    assert main(["modes", model, "--color", "stress"]) == 2
    assert "--images" in capsys.readouterr().err
    import os
    hoist = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                         "models", "two_mass_hoist.yaml")
    assert main(["modes", hoist, "--color", "stress", "--images",
                 str(tmp_path / "img")]) == 2
    assert "has none" in capsys.readouterr().err


# ------------------------------------------------------------------ mesh files

FRAME_NODES = {"A": [0, 0, 0], "B": [0, 0, 3], "C": [4, 0, 3], "D": [4, 0, 0]}
GIRDER_POINTS = [[0, 0, 3], [4 / 3, 0, 3.2], [8 / 3, 0, 3.2], [4, 0, 3]]
COLUMN_POINTS = [[0, 0, 0], [0, 0, 3], [4, 0, 0], [4, 0, 3]]


def _frame(girder, columns, extra_nodes="", support="girder.1"):
    """A 3D portal frame A-B-C-D with a bent girder B-G1-G2-C (IPE 200, released about
    its strong axis at C) on box columns (Timoshenko from the shape), pinned at D,
    clamped at A, the girder's first interior point held sideways (uy)."""
    return f"""
    cranefe: 1
    nodes: {{A: [0, 0, 0], B: [0, 0, 3], C: [4, 0, 3], D: [4, 0, 0]{extra_nodes}}}
    ground: [A]
    supports: {{D: pinned, {support}: [uy]}}
    members:
      girder: {{type: beam, {girder}, E: {E}, G: {G}, rho: 7850,
               orientation: [0, 1, 0], elements: 2, section: {{profile: IPE 200}},
               releases: {{C: [ry]}}}}
      columns: {{type: beam, {columns}, E: {E}, G: {G}, rho: 7850,
                orientation: [0, 1, 0], elements: 3,
                section: {{shape: box, b: 0.2, h: 0.2, t: 0.01, timoshenko: true}}}}
    masses: {{C: 200}}
    effects: {{structure: flexible}}
    """


def test_mesh_file_members_carry_supports_releases_and_sections(tmp_path):
    """The frame with its girder and columns read from VTU files (points merged with
    the named nodes, new points named girder.1, girder.2) has the frequencies of its
    YAML twin (the same members as chains and pairs of named nodes) to 1e-12: the
    support on a mesh point, the release at C, the profile and the shape section all
    reach the members. Without them the frequencies differ (the test can fail)."""
    import meshio
    from cranefe.api import load, modes
    meshio.write_points_cells(str(tmp_path / "girder.vtu"), np.array(GIRDER_POINTS, float),
                              [("line", np.array([[0, 1], [1, 2], [2, 3]]))])
    meshio.write_points_cells(str(tmp_path / "columns.vtu"), np.array(COLUMN_POINTS, float),
                              [("line", np.array([[0, 1], [2, 3]]))])
    meshed = load(_write(tmp_path, _frame("mesh: girder.vtu", "mesh: columns.vtu"),
                         "meshed.yaml"))
    assert {"girder.1", "girder.2"} <= set(meshed.node_names)
    twin = load(_write(tmp_path, _frame(
        "nodes: [B, G1, G2, C]", "pairs: [[A, B], [D, C]]",
        ", G1: [1.3333333333333333, 0, 3.2], G2: [2.6666666666666665, 0, 3.2]",
        support="G1"), "twin.yaml"))
    f_mesh, f_twin = (modes(m, count=8).frequency_hz for m in (meshed, twin))
    assert np.abs(f_mesh / f_twin - 1).max() < 1e-12
    # the same frame without the release, or the support, differs
    for change in (lambda t: t.replace("releases: {C: [ry]}", ""),
                   lambda t: t.replace(", girder.1: [uy]", "")):
        other = load(_write(tmp_path, change(_frame("mesh: girder.vtu",
                                                    "mesh: columns.vtu")), "other.yaml"))
        f = modes(other, count=8).frequency_hz
        assert np.abs(f / f_twin - 1).max() > 1e-3
