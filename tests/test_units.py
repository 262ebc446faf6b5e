"""Inputs in engineers' units (issue 18): quantities with units, ropes from their
designation, plausibility warnings.

Conversions are checked against the factors written out by hand (1 t = 1000 kg,
1 m/min = 1/60 m/s, 1 rpm = 2 pi/60 rad/s, 1 deg = pi/180 rad): pint must give them to
rounding (rtol 1e-12: one or two float operations). The rope factors are EN 12385-4's,
and the test reproduces a printed table (API 9A / ISO 10425 Table C.1, class 6x7 FC)
from them to the table's own rounding.
"""

import json
import math
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from cranefe.cli import main
from cranefe.errors import ModelError
from cranefe.model import load, plausibility, ropes_data
from cranefe.model.load import _Reader
from cranefe.model.units import expected_unit

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(ROOT, "models")
HOIST = os.path.join(MODELS, "two_mass_hoist.yaml")
RTOL = 1e-12        # a unit conversion is one or two float operations


def write(tmp_path, text, name="m.yaml"):
    p = tmp_path / name
    p.write_text(textwrap.dedent(text).lstrip("\n"))
    return p


# ----------------------------------------------------------------------- units

@pytest.mark.parametrize("text, entry, unit, expected", [
    ("110 MN", "ropes.hoist.EA", None, 110e6),
    ("8 t", "masses.B", None, 8000.0),
    ("8 t", "masses.E", None, 8000.0),                 # a node named like a key
    ("5.2 t", "bodies.jib.mass", None, 5200.0),
    ("250 mm", "drums.hoist.radius", None, 0.25),
    ("120 kg m^2", "drums.hoist.inertia", None, 120.0),
    ("120 kg·m²", "bodies.jib.inertia[1]", None, 120.0),
    ("0.6 kg*m**2", "drums.hoist.motor.rotor_inertia", None, 0.6),
    ("1000 mm", "nodes.W[2]", None, 1.0),
    ("-9.81 m/s^2", "gravity[2]", None, -9.81),
    ("5 kN/mm", "springs[0].stiffness", None, 5e6),
    ("4 GN m/rad", "springs.bend.stiffness", "N*m/rad", 4e9),
    ("1 MN m/deg", "springs.bend.stiffness", "N*m/rad", 1e6 * 180 / math.pi),
    ("210 GPa", "members.mast.E", None, 210e9),
    ("120 cm^2", "members.mast.A", None, 120e-4),
    ("2000 cm^4", "members.mast.Iy", None, 2000e-8),
    ("7.85 t/m^3", "members.mast.rho", None, 7850.0),
    ("1.5 kg/m", "ropes.hoist.mass_per_length", None, 1.5),
    ("20 %", "ropes.hoist.psi", None, 0.2),
    ("20 ms", "analysis.time_step", None, 0.02),
    ("1450 rpm", "analysis.drums.hoist.motor.synchronous_speed", None, 1450 * math.pi / 30),
    ("12 kN m", "analysis.drums.hoist.torque", None, 12e3),
    ("500 ms", "analysis.drums.hoist.torque[1][0]", None, 0.5),      # a table's time
    ("12 kN m", "analysis.drums.hoist.torque[1][1]", None, 12e3),
    ("80 deg", "analysis.alpha0_deg", None, 80.0),
    ("15 m", "analysis.load.rope_length", None, 15.0),
])
def test_quantities_convert_to_si(text, entry, unit, expected):
    assert _Reader("m.yaml").number(text, entry, unit=unit) == \
        pytest.approx(expected, rel=RTOL)


def test_rope_speed_of_a_drum_turns_by_its_radius():
    # 40 m/min of rope on a 0.25 m drum: omega = (40/60) / 0.25 rad/s
    r = _Reader("s.yaml", drums={"hoist": 0.25})
    w = 40 / 60 / 0.25
    assert r.number("40 m/min", "analysis.drums.hoist.speed") == pytest.approx(w, rel=RTOL)
    assert r.number("40 m/min", "analysis.drums.hoist.speed[2][1]") == \
        pytest.approx(w, rel=RTOL)
    assert r.number("30 rpm", "analysis.drums.hoist.speed") == pytest.approx(math.pi,
                                                                              rel=RTOL)
    with pytest.raises(ModelError, match=r"is a speed, but speed is an angular speed"):
        _Reader("s.yaml").number("40 m/min", "analysis.drums.hoist.speed")


@pytest.mark.parametrize("text, entry, unit, message", [
    ("250 mm", "ropes.hoist.EA", None,
     "m.yaml: ropes.hoist.EA: 250 mm is a length, but EA is a force (N)"),
    ("8 kN", "masses.B", None, "masses.B: 8 kN is a force, but this entry is a mass (kg)"),
    ("3 m/s", "springs.bend.stiffness", "N*m/rad",
     "3 m/s is a speed, but stiffness is a rotational stiffness (N m/rad)"),
    ("1 N", "drums.hoist.gear_ratio", None, "but gear_ratio is a plain number (no unit)"),
    ("8 foo", "masses.B", None, "masses.B: must be a number, or a number with a unit: "
     "unknown unit in '8 foo'"),
    ("8 ton", "masses.B", None, "'ton' is ambiguous"),
    ("3 Hz", "analysis.drums.hoist.speed", None, "Hz is ambiguous"),
    ("10**10**10 N", "ropes.hoist.EA", None, "cannot read '10**10**10 N'"),
    ("1 m^99 N", "ropes.hoist.EA", None, "cannot read"),
    ("1e400 N", "ropes.hoist.EA", None, "is not a finite number"),
    ("1 N", "joints[0].axis[0]", None, "this entry takes a plain number"),
    ("2 " + "m" * 80, "ropes.hoist.extra_length", None, "too long"),
])
def test_bad_quantities_name_the_entry(text, entry, unit, message):
    with pytest.raises(ModelError) as exc:
        _Reader("m.yaml").number(text, entry, unit=unit)
    assert message in str(exc.value)
    assert entry in str(exc.value)


def test_every_unit_of_the_table_is_a_unit():
    from cranefe.model.units import TABLES, UNITS, registry
    ureg = registry()
    for u in list(UNITS.values()) + [u for pair in TABLES.values() for u in pair]:
        if u:
            ureg.parse_units(u)
    assert expected_unit("nodes.A[0]") == "m"
    assert expected_unit("analysis.drums.d.speed[0][0]") == "s"
    assert expected_unit("analysis.drums.d.motor.characteristic[3][1]") == "N*m"
    assert expected_unit("joints[0].axis[1]") is None


def test_a_model_in_units_is_the_si_model(tmp_path):
    si = load(HOIST)
    text = open(HOIST).read()
    for old, new in (("H: 5200 ", "H: 5.2 t "), ("EA: 1.7e7 ", "EA: 17 MN "),
                     ("radius: 0.25 ", "radius: 250 mm "), ("inertia: 95.0 ", "inertia: 95 kg m^2 "),
                     ("W: [-12.0, 0.0, 1.0]", "W: [-12 m, 0, 1000 mm]"),
                     ("mass_per_length: 1.5 ", "mass_per_length: 1.5 kg/m ")):
        assert old in text
        text = text.replace(old, new)
    m = load(write(tmp_path, text))
    assert np.array_equal(m.coords, si.coords)
    assert (m.masses.mass[0], m.ropes[0].EA, m.drums[0].radius, m.drums[0].inertia) == \
        pytest.approx((5200.0, 1.7e7, 0.25, 95.0), rel=RTOL)


def test_a_file_with_units_loads_pint_and_one_without_does_not(tmp_path):
    text = open(HOIST).read().replace("H: 5200 ", "H: 5.2 t ")
    p = write(tmp_path, text)
    code = ("import sys\nfrom cranefe.model import load\nload(sys.argv[1])\n"
            "print('pint' in sys.modules)")
    env = dict(os.environ, PYTHONPATH=ROOT)
    out = [subprocess.run([sys.executable, "-c", code, f], capture_output=True,
                          text=True, check=True, env=env).stdout.strip()
           for f in (str(p), HOIST)]
    assert out == ["True", "False"]


def test_transient_scene_in_units(tmp_path):
    from cranefe.analysis.transient.scene import parse
    write(tmp_path, open(HOIST).read(), "hoist.yaml")
    scene = write(tmp_path, """
        cranefe: 1
        scene: start
        model: hoist.yaml
        effects: {sway: false}
        analysis:
          type: transient
          duration: 1500 ms
          drums:
            hoist: {speed: [[0 s, 0 m/min], [2 s, 30 m/min]]}
        """, "s.yaml")
    t = parse(load(scene))
    assert t.duration == pytest.approx(1.5, rel=RTOL)
    prof = t.drums[0].profile
    assert prof.times.tolist() == [0.0, 2.0]
    assert prof.values[1, 0] == pytest.approx(0.5 / 0.25, rel=RTOL)   # 0.5 m/s / 0.25 m


# ------------------------------------------------------------ rope designation

# API 9A / ISO 10425 Table C.1, class 6x7 fibre core: d (mm), nominal length mass
# (kg/100 m) and minimum breaking force at grade 1770 (kN), printed to 3 figures
TABLE_6X7_FC = [(6, 12.4, 21.2), (10, 34.5, 58.8), (12, 49.7, 84.6), (20, 138, 235),
                (28, 270, 461), (40, 552, 940)]


@pytest.mark.parametrize("d, mass, force", TABLE_6X7_FC)
def test_designation_reproduces_a_printed_rope_table(d, mass, force):
    r = ropes_data.derive(d / 1e3, "6x7 FC")
    # the table rounds to 3 significant figures: half a unit of the last digit
    assert r["mass_per_length_kg_m"] * 100 == pytest.approx(mass, abs=0.5 * 10 **
                                                            (math.floor(math.log10(mass)) - 2))
    assert r["min_breaking_force_N"] / 1e3 == pytest.approx(
        force, abs=0.5 * 10 ** (math.floor(math.log10(force)) - 2))


@pytest.mark.parametrize("cls", sorted(ropes_data.FACTORS))
@pytest.mark.parametrize("core", ["FC", "steel"])
def test_designation_uses_the_en_12385_factors(cls, core):
    W, C, K = ropes_data.FACTORS[cls][core]
    d = 0.022
    construction = f"{cls.rstrip('MN')}{'M' if cls.endswith('M') else ''}" \
        f"{'N' if cls.endswith('N') else ''} {'FC' if core == 'FC' else 'IWRC'}"
    r = ropes_data.derive(d, construction)
    assert r["class"] == cls
    # Feyrer eq. 1.5, 1.5a, 1.5b with d in mm
    assert r["metallic_area_m2"] == pytest.approx(C * 22.0**2 * 1e-6, rel=RTOL)
    assert r["fill_factor"] == pytest.approx(4 * C / math.pi, rel=RTOL)
    assert r["mass_per_length_kg_m"] == pytest.approx(W * 22.0**2 / 100, rel=RTOL)
    assert r["EA_N"] == pytest.approx(r["modulus_pa"] * r["metallic_area_m2"], rel=RTOL)
    assert r["min_breaking_force_N"] == pytest.approx(K * 22.0**2 * 1770, rel=RTOL)
    # a rope is lighter than solid steel of its metallic area plus the lay and core
    # allowance is small: mass / (7850 A) lies between 1.0 and 1.25 for every class
    assert 1.0 < r["mass_per_length_kg_m"] / (7850 * r["metallic_area_m2"]) < 1.25


@pytest.mark.parametrize("text, cls, core", [
    ("6x36WS-IWRC", "6x36", "steel"), ("6x19 FC", "6x19", "FC"),
    ("6x25F IWRC", "6x19", "steel"), ("8x19S-IWRC", "8x19", "steel"),
    ("8-strand", "8x19", "steel"), ("8-strand FC", "8x19", "FC"),
    ("35(W)x7", "34x7", "steel"), ("18x7 FC", "18x7", "FC"),
    ("rotation-resistant", "34x7", "steel"), ("6x36", "6x36", None),
    ("6 × 41WS IWRC", "6x36", "steel"), ("6x37M IWRC", "6x37M", "steel"),
])
def test_construction_classes(text, cls, core):
    assert ropes_data.classify(text) == (cls, core)


@pytest.mark.parametrize("text, message", [
    ("compacted 6xK36", "compacted-strand ropes are not in the EN 12385-4 tables"),
    ("7x7", "no EN 12385-4 class"), ("spiral strand", "is not a rope class"),
])
def test_unknown_constructions(text, message):
    with pytest.raises(ValueError, match=message):
        ropes_data.classify(text)


DESIGNATED = """
    cranefe: 1
    plane: xz
    nodes: {W: [-5, 0, 0], S: [0, 0, 10], H: [0, 0, 0]}
    ground: [W, S]
    masses: {H: 1000}
    drums:
      hoist: {node: W, radius: 0.2, inertia: 10}
    ropes:
      r: {diameter: 16 mm, construction: 6x36WS-IWRC, path: [hoist, S, {node: H, falls: 2}]}
"""


def test_rope_from_designation_and_own_values_win(tmp_path, capsys):
    m = load(write(tmp_path, DESIGNATED))
    W, C, _ = ropes_data.FACTORS["6x36"]["steel"]
    E = ropes_data.MODULUS["6", "steel"]
    assert m.ropes[0].EA == pytest.approx(E * C * 16.0**2 * 1e-6, rel=RTOL)
    assert m.ropes[0].mass_per_length == pytest.approx(W * 16.0**2 / 100, rel=RTOL)
    own = DESIGNATED.replace("construction: 6x36WS-IWRC,",
                             "construction: 6x36WS-IWRC, EA: 2.5e7, modulus: 95 GPa,")
    p = write(tmp_path, own, "own.yaml")
    m = load(p)
    assert m.ropes[0].EA == 2.5e7
    assert m.ropes[0].mass_per_length == pytest.approx(W * 16.0**2 / 100, rel=RTOL)
    assert main(["check", str(p), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    d = doc["elements"][0]["designation"]
    assert (d["class"], d["EA_from"], d["mass_from"], d["modulus_from"]) == \
        ("6x36", "given", "designation", "given")
    assert d["EA_N"] == pytest.approx(95e9 * C * 16.0**2 * 1e-6, rel=RTOL)
    assert main(["check", str(p)]) == 0
    out = capsys.readouterr().out
    assert "designation: 16 mm 6x36 IWRC (EN 12385-4)" in out
    assert "your own EA used" in out


@pytest.mark.parametrize("edit, entry, message", [
    (("construction: 6x36WS-IWRC, ", ""), "ropes.r",
     "needs both 'diameter' and 'construction'"),
    (("6x36WS-IWRC", "6x36"), "ropes.r.construction", "does not say the core"),
    (("6x36WS-IWRC", "compacted"), "ropes.r.construction", "give EA and mass_per_length"),
    (("diameter: 16 mm, construction: 6x36WS-IWRC, ", ""), "ropes.r",
     "missing required key 'EA'"),
    (("16 mm", "16 kg"), "ropes.r.diameter", "16 kg is a mass, but diameter is a length"),
])
def test_bad_designations(tmp_path, capsys, edit, entry, message):
    assert edit[0] in DESIGNATED
    p = write(tmp_path, DESIGNATED.replace(*edit))
    assert main(["check", str(p)]) == 2
    err = capsys.readouterr().err
    assert f"{entry}:" in err and message in err, err


# ------------------------------------------------------------ plausibility

def _examples():
    out = []
    for folder in (MODELS, os.path.join(MODELS, "scenes")):
        out += sorted(os.path.join(folder, f) for f in os.listdir(folder)
                      if f.endswith(".yaml"))
    return out


@pytest.mark.parametrize("path", _examples(), ids=os.path.basename)
def test_no_plausibility_warning_on_the_examples(path, capsys):
    assert main(["check", path, "--json"]) == 0
    check = json.loads(capsys.readouterr().out)["warnings"]
    assert main(["modes", path, "--json"]) == 0
    modes = json.loads(capsys.readouterr().out)["warnings"]
    for w in check + modes:
        assert not w.startswith(("ropes.", "masses.", "bodies.", "springs.",
                                 "the slowest mode")), w


def test_kN_for_N_stretches_the_rope_and_makes_a_slow_mode(tmp_path, capsys):
    # The case: EA 11000 meant in kN. Static tension 5200 g / 2 = 25.5 kN
    # stretches the rope by 232 %; the bounce mode then is slower than a 60 m pendulum.
    p = write(tmp_path, open(HOIST).read().replace("EA: 1.7e7 ", "EA: 11000 "))
    assert main(["modes", str(p), "--json"]) == 0
    w = json.loads(capsys.readouterr().out)["warnings"]
    assert any(x.startswith("ropes.hoist_rope: the static tension 2.551e+04 N stretches "
                            "the rope by 232 %") and "'EA: 11000 kN'" in x for x in w), w
    assert any(x.startswith("the slowest mode (0.0623 Hz) is slower than a pendulum")
               for x in w), w
    assert main(["damping", str(p), "--json"]) == 0
    assert any("stretches the rope" in x
               for x in json.loads(capsys.readouterr().out)["warnings"])


MASSES = """
    cranefe: 1
    plane: xz
    nodes: {O: [0, 0, 0], T: [0, 0, 10], K: [5, 0, 10], H: [5, 0, 2]}
    ground: [O]
    masses: {H: 2000}
    bodies:
      mast: {mass: 10000, com: [0, 0, 5], inertia: 1.0e5, nodes: [O, T]}
      jib: {mass: 3000, com: K, inertia: 2.0e4, nodes: [T, K]}
    joints:
      - {type: hinge, bodies: [ground, mast], at: O}
      - {type: fixed, bodies: [mast, jib], at: T}
    springs:
      - {name: bend, type: rotational, bodies: [ground, mast], at: O, stiffness: 1e10}
      - {name: sling, type: axial, nodes: [K, H], stiffness: 1e7}
"""


def test_a_mass_in_t_written_as_kg(tmp_path):
    good = load(write(tmp_path, MASSES))
    assert plausibility.warnings(good) == []
    m = load(write(tmp_path, MASSES.replace("H: 2000", "H: 2"), "bad.yaml"))
    w = plausibility.warnings(m)
    assert w == ["masses.H: the mass 2 kg is 1,500 times lighter than the model's median "
                 "mass (3000 kg): a mass in t written as kg? (write '2 t')"]


def test_an_axial_stiffness_far_from_the_others(tmp_path):
    extra = MASSES + textwrap.indent(textwrap.dedent("""
        - {name: guy1, type: axial, nodes: [O, K], stiffness: 2e7}
        - {name: guy2, type: axial, nodes: [O, H], stiffness: 5e6}
    """).strip("\n"), "      ") + "\n"
    assert plausibility.warnings(load(write(tmp_path, extra))) == []
    bad = extra.replace("stiffness: 5e6", "stiffness: 5e10")
    w = plausibility.warnings(load(write(tmp_path, bad, "bad.yaml")))
    assert len(w) == 1 and w[0].startswith("springs.guy2.stiffness: the axial stiffness "
                                           "5e+10 N/m is 2,500 times stiffer"), w
    assert "N/mm written as N/m" in w[0]


def test_pendulum_longer_than_the_model(tmp_path):
    # 1000 kg on one 10 m fall: a pendulum of 10 m (0.158 Hz); with EA = 1 kN the
    # vertical bounce has w^2 = EA / (L m) = 1e-4 (1/s^2): a 98 km "pendulum"
    text = """
        cranefe: 1
        plane: xz
        nodes: {S: [0, 0, 10], H: [0, 0, 0]}
        ground: [S]
        masses: {H: 1000}
        ropes:
          r: {EA: 1000, path: [S, H]}
    """
    m = load(write(tmp_path, text))
    w = plausibility.warnings(m, omega=np.array([0.01, math.sqrt(9.81 / 10)]))
    assert len(w) == 1 and "pendulum 9.81e+04 m long" in w[0], w
    assert plausibility.warnings(m, omega=np.array([math.sqrt(9.81 / 10)])) == []


@pytest.mark.parametrize("text", ["1 " + " " * 10**6 + "N", "1 " + "m * " * 10**5 + "#",
                                  "1 " + "m * " * 12 + "#"])
def test_long_or_tangled_text_is_refused_at_once(text):
    # the unit is matched by one separator per name (linear); text is bounded in length
    with pytest.raises(ModelError, match="ropes.r.EA"):
        _Reader("m.yaml").number(text, "ropes.r.EA")
