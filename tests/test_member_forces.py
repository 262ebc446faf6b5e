"""Member forces and extreme-fibre stresses: static state, per mode, and envelopes of
transient runs (cranefe/outputs/member_forces.py) against closed forms."""

import json
import math
import textwrap

import numpy as np
import pytest

from cranefe.cli import main

E, G = 2.1e11, 8.1e10
B, H = 0.1, 0.2                      # rectangle: Iy = B H^3 / 12 (strong), Wy = B H^2 / 6


def _write(tmp_path, text, name="m.yaml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return str(path)


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def _cantilever(L=4.0, m=1000.0, elements=4, extra=""):
    """A massless 3D cantilever along x with a point mass m at its tip T (rectangle
    B x H, depth along z): tip load P = m g downwards."""
    return f"""
    cranefe: 1
    nodes: {{O: [0, 0, 0], T: [{L}, 0, 0]}}
    ground: [O]
    members:
      b: {{type: beam, nodes: [O, T], E: {E}, G: {G}, rho: 0, orientation: [0, 0, 1],
          elements: {elements}, section: {{shape: rectangle, b: {B}, h: {H}}}}}
    masses: {{T: {m}}}
    effects: {{structure: flexible}}
    {extra}"""


def test_cantilever_tip_load_root_moment_and_stress(tmp_path, capsys):
    # P = m g at the tip of a massless cantilever: at the clamp M = P L, V = P; at the tip
    # no moment; the extreme fibres sigma = +- M c / I = +- M / (B H^2 / 6). Cubic elements
    # are exact for a tip load: round-off (1e-9 of P L)
    L, m, g = 4.0, 1000.0, 9.81
    P = m * g
    doc = _json(capsys, ["check", _write(tmp_path, _cantilever(L, m)), "--json"])
    (f,) = doc["member_forces"]
    s, e = f["start"], f["end"]
    assert (f["member"], f["type"], f["from"], f["to"]) == ("b", "beam", "O", "T")
    # the shear is P all along (the tip node carries the mass), the moment P L at the
    # clamp (hogging is My > 0 in these axes, as under self-weight) and 0 at the tip
    assert [s["Vz"], s["My"], e["Vz"], e["My"], s["N"], s["Mz"]] == pytest.approx(
        [-P, P * L, -P, 0, 0, 0], abs=1e-9 * P * L)
    I, c = B * H**3 / 12, H / 2
    assert s["sigma_max"] == pytest.approx(P * L * c / I, rel=1e-9)
    assert s["sigma_min"] == pytest.approx(-P * L * c / I, rel=1e-9)
    assert [e["sigma_max"], e["sigma_min"]] == pytest.approx([0, 0], abs=1e-6)


def test_column_under_axial_load_and_a_truss(tmp_path, capsys):
    # a vertical column carrying m at its top: N = -m g, no bending, sigma = N / A at both
    # fibres; a truss bar hanging m: N = +m g, sigma = N / A (its section's area only)
    m, g = 2000.0, 9.81
    text = f"""
    cranefe: 1
    nodes: {{O: [0, 0, 0], T: [0, 0, 5], S: [3, 0, 0], W: [3, 0, -2]}}
    ground: [O, S]
    members:
      c: {{type: beam, nodes: [O, T], E: {E}, G: {G}, rho: 0, orientation: [1, 0, 0],
          elements: 2, section: {{profile: HEB 200}}}}
      t: {{type: truss, nodes: [S, W], E: {E}, rho: 0, section: {{profile: L 100x10}}}}
    masses: {{T: {m}, W: {m}}}
    effects: {{structure: flexible}}
    """
    from cranefe.model.sections import profile_shape, section_properties
    Ac = section_properties(*profile_shape("HEB 200"), 0.3)[0]
    At = section_properties(*profile_shape("L 100x10"), 0.3)[0]
    path = _write(tmp_path, text)
    (beam_only,) = _json(capsys, ["check", path, "--json"])["member_forces"]
    doc = _json(capsys, ["check", path, "--json", "--member-forces"])
    c, t = doc["member_forces"]
    assert beam_only == c
    for end in ("start", "end"):
        assert c[end]["N"] == pytest.approx(-m * g, rel=1e-9)
        assert [c[end][k] for k in ("Vy", "Vz", "T", "My", "Mz")] == pytest.approx(
            [0] * 5, abs=1e-9 * m * g)
        assert [c[end]["sigma_max"], c[end]["sigma_min"]] == pytest.approx(
            [-m * g / Ac] * 2, rel=1e-9)
        assert t[end]["N"] == pytest.approx(m * g, rel=1e-9)
        assert t[end]["sigma_max"] == pytest.approx(m * g / At, rel=1e-9)
    assert t["type"] == "truss"


def test_a_tripod_of_trusses_shares_its_load(tmp_path, capsys):
    # three bars from the ground at 120 degrees down to a hanging mass m: each carries
    # N = m g / (3 cos theta), theta the bars' angle from the vertical (here 45 degrees)
    m, g = 3000.0, 9.81
    r3 = math.sqrt(3)
    text = f"""
    cranefe: 1
    nodes: {{S1: [2, 0, 0], S2: [-1, {r3}, 0], S3: [-1, {-r3}, 0], W: [0, 0, -2]}}
    ground: [S1, S2, S3]
    members:
      bars: {{type: truss, pairs: [[S1, W], [S2, W], [S3, W]], E: {E}, rho: 0,
             section: {{profile: L 60x6}}}}
    masses: {{W: {m}}}
    effects: {{structure: flexible}}
    """
    doc = _json(capsys, ["check", _write(tmp_path, text), "--json", "--member-forces"])
    pieces = doc["member_forces"]
    assert [p["from"] for p in pieces] == ["S1", "S2", "S3"]
    N = m * g / (3 * math.cos(math.pi / 4))
    for p in pieces:
        assert [p["start"]["N"], p["end"]["N"]] == pytest.approx([N, N], rel=1e-9)


def _simply_supported(n, L=10.0):
    """A simply supported beam A-C-B (C at midspan), n elements per half, planar."""
    return f"""
    cranefe: 1
    plane: xz
    gravity: [0, 0, 0]
    nodes: {{A: [0, 0, 0], C: [{L / 2}, 0, 0], B: [{L}, 0, 0]}}
    supports: {{A: pinned, B: pinned}}
    members:
      b: {{type: beam, nodes: [A, C, B], E: {E}, rho: 7850, elements: {n},
          section: {{shape: rectangle, b: {B}, h: {H}}}}}
    effects: {{structure: flexible}}
    """


def test_first_mode_forces_of_a_simply_supported_beam(tmp_path, capsys):
    # mode 1: w = a sin(pi x / L), so M = EI w'' = -EI (pi/L)^2 a sin(pi x / L): at
    # midspan |M| = EI (pi/L)^2 a with the mode scaled to a = 1 cm at its largest node
    # translation (midspan); at the supports M = 0 and |V| = EI (pi/L)^3 a. The element
    # end forces K_e u_e of the discrete mode converge at O(h^2) (the distributed inertia
    # load of the mode is not in K_e u_e, and at a support the node's rotary consistent
    # mass takes omega^2 (M u) of the moment): errors at 4, 8, 16 elements per half
    L, a = 10.0, 0.01
    I = B * H**3 / 12
    M_ref = E * I * (math.pi / L) ** 2 * a
    V_ref = E * I * (math.pi / L) ** 3 * a
    errs = []
    for n in (4, 8, 16):
        doc = _json(capsys, ["modes", _write(tmp_path, _simply_supported(n), f"s{n}.yaml"),
                             "--json", "--count", "1", "--member-forces",
                             "--member-forces-scale", str(a)])
        mf = doc["member_forces"]
        assert mf["scale"] == {"normalisation": "largest node translation",
                               "amplitude_m": a}
        first, second = mf["modes"][0]["pieces"]
        assert (first["from"], first["to"], second["from"]) == ("A", "C", "C")
        # the beam diagram is continuous at C
        assert first["end"]["My"] == pytest.approx(second["start"]["My"], rel=1e-9)
        errs.append([abs(abs(first["end"]["My"]) / M_ref - 1),
                     abs(abs(first["start"]["Vz"]) / V_ref - 1),
                     abs(first["start"]["My"]) / M_ref])    # the support's (zero) moment
        # the stress at midspan: M / Wy
        assert first["end"]["sigma_max"] == pytest.approx(
            abs(first["end"]["My"]) / (B * H**2 / 6), rel=1e-12)
    errs = np.array(errs)
    assert np.all(errs[-1] < 2e-3), errs
    orders = np.log2(errs[:-1] / errs[1:])
    assert np.all(orders > 1.8), orders


def test_modes_without_scale_are_mass_normalised(tmp_path, capsys):
    # without --member-forces-scale the forces are those of the mass-normalised shape:
    # scaling by the midspan translation w_C of that shape gives the scaled ones
    path = _write(tmp_path, _simply_supported(8))
    doc = _json(capsys, ["modes", path, "--json", "--count", "1", "--member-forces"])
    assert doc["member_forces"]["scale"]["normalisation"].startswith("mass")
    M1 = doc["member_forces"]["modes"][0]["pieces"][0]["end"]["My"]
    doc2 = _json(capsys, ["modes", path, "--json", "--count", "1", "--member-forces",
                          "--member-forces-scale", "1"])
    M2 = doc2["member_forces"]["modes"][0]["pieces"][0]["end"]["My"]
    assert "member_forces" not in _json(capsys, ["modes", path, "--json", "--count", "1"])
    # the mass-normalised amplitude of a uniform beam's first mode: sqrt(2 / (rho A L))
    wC = math.sqrt(2 / (7850 * B * H * 10.0))
    assert abs(M1 / M2) == pytest.approx(wC, rel=2e-3)


def test_transient_envelope_of_a_step_load(tmp_path, capsys):
    # a step force F (down) at the tip mass of a massless cantilever, from rest in the
    # static state: the tip swings between the static deflection and that plus 2 F / k,
    # so the clamp's moment between m g L and (m g + 2 F) L (an undamped one-degree
    # system). Newmark's trapezoidal rule keeps the amplitude; the output times sample the
    # peak within (w h)^2 / 8 = 3e-5 at 360 steps per period: 1e-4
    L, m, g, F = 4.0, 1000.0, 9.81, 5000.0
    I = B * H**3 / 12
    k = 3 * E * I / L**3
    T = 2 * math.pi * math.sqrt(m / k)
    model = _write(tmp_path, _cantilever(L, m), "cant.yaml")
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
    assert model
    doc = _json(capsys, ["simulate", scene, "--json", "--member-forces"])
    env = doc["member_forces"]
    assert env["over"] == "output times"
    (p,) = env["pieces"]
    lo, hi = p["start"]["min"], p["start"]["max"]
    assert lo["My"] == pytest.approx(m * g * L, rel=1e-6)
    assert hi["My"] == pytest.approx((m * g + 2 * F) * L, rel=1e-4)
    c = H / 2
    assert hi["sigma_max"] == pytest.approx((m * g + 2 * F) * L * c / I, rel=1e-4)
    assert lo["sigma_min"] == pytest.approx(-(m * g + 2 * F) * L * c / I, rel=1e-4)


def test_vtu_carries_the_modes_member_forces_as_cell_data(tmp_path, capsys):
    # the VTU's member cells hold each element's end value of larger magnitude: the
    # element at midspan of mode 1 carries the midspan moment of --json
    meshio = pytest.importorskip("meshio")
    path = _write(tmp_path, _simply_supported(4))
    out = tmp_path / "m.vtu"
    xdmf = tmp_path / "m.xdmf"
    doc = _json(capsys, ["modes", path, "--json", "--count", "2", "--member-forces",
                         "--member-forces-scale", "0.01", "--vtu", str(out), "--xdmf",
                         str(xdmf)])
    m = meshio.read(out)
    My = m.cell_data["mode_1_My"][0]
    kind = m.cell_data["kind"][0]
    members = My[kind == 3]
    assert len(members) == 8 and np.isnan(My[kind != 3]).all()
    mid = doc["member_forces"]["modes"][0]["pieces"][0]["end"]["My"]
    assert np.nanmax(np.abs(members)) == pytest.approx(abs(mid), rel=1e-12)
    assert "mode_2_sigma_max" in m.cell_data
    # the XDMF series of the modes: step k carries mode k's arrays
    with meshio.xdmf.TimeSeriesReader(str(xdmf)) as r:
        r.read_points_cells()
        _, _, cells = r.read_data(0)
    assert np.nanmax(np.abs(cells["My"][0])) == pytest.approx(abs(mid), rel=1e-12)


def test_xdmf_series_of_a_run_carries_member_forces(tmp_path, capsys):
    # simulate --xdmf --member-forces: every step holds the members' cell arrays; their
    # extremes over the steps are the envelope of --json
    meshio = pytest.importorskip("meshio")
    model = _write(tmp_path, _cantilever(), "cant.yaml")
    assert model
    scene = _write(tmp_path, """
    cranefe: 1
    scene: step
    model: cant.yaml
    analysis: {type: transient, duration: 0.2, time_step: 0.002,
               forces: {T: {force: [0, 0, -5000]}}}
    """, "scene.yaml")
    out = tmp_path / "run.xdmf"
    doc = _json(capsys, ["simulate", scene, "--json", "--member-forces", "--xdmf", str(out)])
    hi = doc["member_forces"]["pieces"][0]["start"]["max"]["My"]
    peaks = []
    with meshio.xdmf.TimeSeriesReader(str(out)) as r:
        r.read_points_cells()
        for k in range(r.num_steps):
            _, _, cells = r.read_data(k)
            My = np.asarray(cells["My"][0])
            peaks.append(np.nanmax(My))
    assert max(peaks) == pytest.approx(hi, rel=1e-12)
