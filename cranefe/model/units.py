"""Quantities with units in model and scene files: ``EA: 110 MN``, ``mass: 8 t``.

A number in a file is SI. Text such as ``250 mm`` is read with pint (imported only
here, and only when a file holds such text, so that small runs stay light) and
converted to the SI unit of its entry. That unit comes from one table, `UNITS`, keyed
by the entry's last key (``ropes.hoist.EA`` -> ``EA`` -> N), with a few rules for
entries whose last key is a name (``nodes.A[0]``, ``masses.B``) and for the columns of
time tables (``analysis.drums.hoist.speed[2][0]`` is a time). A quantity of another
dimension is a `ModelError` naming both dimensions (docs/model-format.md, section 1).
"""

import math
import re

from ..errors import ModelError

# The SI unit of each entry, by its last key ("" = a plain number). Where one key means
# different things (a spring's stiffness) the caller passes the unit itself.
UNITS = {
    # model file
    "gravity": "m/s^2", "com": "m", "mass": "kg", "inertia": "kg*m^2",
    "stiffness": "N/m", "psi": "", "radius": "m", "rotor_inertia": "kg*m^2",
    "gear_ratio": "", "EA": "N", "mass_per_length": "kg/m", "extra_length": "m",
    "diameter": "m", "modulus": "Pa", "E": "Pa", "G": "Pa", "A": "m^2", "Iy": "m^4",
    "Iz": "m^4", "J": "m^4", "rho": "kg/m^3", "pinion_radius": "m",
    # scenes: transient (docs/transient.md) and luffing (docs/luffing.md)
    "duration": "s", "time_step": "s", "output_step": "s", "ramp": "s", "speed": "rad/s",
    "torque": "N*m", "force": "N", "synchronous_speed": "rad/s", "stall_torque": "N*m",
    "breakdown_torque": "N*m", "breakdown_slip": "", "t_k": "s", "rope_length": "m",
    "reach0": "m", "reachk": "m", "alpha0": "rad", "alphak": "rad", "alpha0_deg": "deg",
    "alphak_deg": "deg", "rest_to_rest_tau": "",
}
# time tables [[t, value...], ...]: the unit of the first column and of the others
TABLES = {"speed": ("s", "rad/s"), "torque": ("s", "N*m"), "force": ("s", "N"),
          "characteristic": ("rad/s", "N*m")}

# What a dimension is called in messages, in the order they are tried
_NAMES = (("m", "a length"), ("kg", "a mass"), ("s", "a time"), ("N", "a force"),
          ("Pa", "a pressure or stress"), ("m^2", "an area"), ("m^3", "a volume"),
          ("m^4", "a second moment of area"), ("kg/m^3", "a density"),
          ("kg/m", "a mass per length"), ("m/s", "a speed"),
          ("rad/s", "an angular speed or a frequency"), ("m/s^2", "an acceleration"),
          ("N*m", "a torque (or an energy, or a rotational stiffness)"),
          ("N/m", "a stiffness (force per length)"), ("kg*m^2", "a moment of inertia"),
          ("W", "a power"), ("", "a plain number"))
_TARGET_NAMES = {"N*m": "a torque", "N*m/rad": "a rotational stiffness",
                 "rad/s": "an angular speed", "rad": "an angle", "deg": "an angle",
                 "": "a plain number", "kg*m^2": "a moment of inertia"}
_SHOWN = {"kg*m^2": "kg m^2", "N*m": "N m", "N*m/rad": "N m/rad", "": "no unit"}

_NUMBER = re.compile(r"\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(.*?)\s*$")
# a unit, once its spacing is normalised (`_normal`): names joined by one space, * or /,
# with powers of one digit (no numbers elsewhere: pint would evaluate them, and
# 10**10**10 must not reach it). Every repetition starts with one separator, so the
# match is linear in the length of the text.
_NAME = r"\(?[A-Za-z_%°µμΩ][A-Za-z0-9_%°µμΩ]*(?:\^[+-]?\d)?\)?"
_UNIT = re.compile(rf"(?:1/)?{_NAME}(?:[*/ ]{_NAME})*")
_SUPERSCRIPTS = {"²": "^2", "³": "^3", "⁴": "^4", "·": "*", "⋅": "*", "−": "-"}
MAX_TEXT = 64
_registry = None


def registry():
    """pint's unit registry, made on first use."""
    global _registry
    if _registry is None:
        import pint
        _registry = pint.UnitRegistry()
    return _registry


def expected_unit(entry):
    """The SI unit (pint notation) of the value at `entry`, or None where no unit is
    known (the entry then takes plain numbers only)."""
    keys, index = _split(entry)
    if not keys:
        return None
    if keys[0] == "nodes":
        return "m"
    if keys[0] == "masses" and len(keys) == 2:
        return "kg"
    last = keys[-1]
    if last in TABLES and len(index) == 2:
        first, rest = TABLES[last]
        return first if index[1] == 0 else rest
    return UNITS.get(last)


def has_unit(text):
    """True if `text` looks like a number followed by a unit (not a bare number)."""
    m = _NUMBER.match(text[:4 * MAX_TEXT])       # longer text: refused by `convert`
    return bool(m and m.group(2))


def convert(text, entry, file, unit=None, drums=None):
    """The SI value of `text` (a number and a unit) at `entry`.

    `unit` overrides the table (e.g. ``N*m/rad`` for a rotational spring). `drums`
    (name -> radius): a drum's speed in a scene (``analysis.drums.NAME.speed``) may
    also be a rope speed (m/s, m/min): the speed of the rope on the drum, turned into
    the drum's angular speed ``omega = v / radius``."""
    where = text.strip()
    unit = expected_unit(entry) if unit is None else unit
    radius = _drum_radius(entry, unit, drums or {})
    if len(text) > MAX_TEXT:
        raise ModelError(f"'{where[:MAX_TEXT]}...' is too long for a number with a unit",
                         file, entry)
    m = _NUMBER.match(text)
    if unit is None:
        raise ModelError(f"must be a number, not text '{where}'; this entry takes a plain "
                         "number without quotes or units", file, entry)
    clean = _normal(m.group(2)) if m else ""
    if not m or not _UNIT.fullmatch(clean):
        raise ModelError(f"must be a number, or a number with a unit: cannot read "
                         f"'{where}'; write e.g. "
                         f"'{_example(unit)}'", file, entry)
    bare = clean.split("/")[0].split("*")[0].split()[0] if clean else ""
    if bare in ("ton", "tons"):
        raise ModelError(f"{where}: 'ton' is ambiguous (pint reads it as the short ton, "
                         "907 kg); write t or tonne (1000 kg), or short_ton / long_ton",
                         file, entry)
    ureg = registry()
    try:
        q = ureg.Quantity(float(m.group(1)), ureg.parse_units(clean))
    except Exception as exc:      # pint raises several kinds for unknown or bad units
        msg = str(exc).split("\n")[0]
        raise ModelError(f"must be a number, or a number with a unit: unknown unit in "
                         f"'{where}' ({msg}); write e.g. "
                         f"'{_example(unit)}'", file, entry) from None
    target = ureg.parse_units(unit) if unit else ureg.dimensionless
    if q.dimensionality != target.dimensionality:
        speed = ureg.parse_units("m/s")
        if radius is not None and q.dimensionality == speed.dimensionality:
            return _finite(q.to(speed).magnitude / radius, text, entry, file)
        keys = _split(entry)[0]
        key = "this entry" if keys[0] in ("nodes", "masses") and len(keys) == 2 \
            else keys[-1]
        also = " or a rope speed (m/s, m/min), turned into the drum's by its radius" \
            if radius is not None else ""
        raise ModelError(f"{where} is {_name(q, ureg)}, but {key} is "
                         f"{_TARGET_NAMES.get(unit) or _name(ureg.Quantity(1, target), ureg)}"
                         f" ({_SHOWN.get(unit, unit)}){also}", file, entry)
    if "rad" in unit and re.search(r"\b(Hz|hertz)\b", clean):
        raise ModelError(f"{where}: Hz is ambiguous for an angular quantity (a cycle per "
                         "second is 2 pi rad/s); write rpm or rad/s", file, entry)
    return _finite(q.to(target).magnitude, text, entry, file)


def _normal(unit):
    """``'kg · m²'`` -> ``'kg*m^2'``: superscripts and dots written out, no spaces around
    operators, single spaces between names."""
    for k, v in _SUPERSCRIPTS.items():
        unit = unit.replace(k, v)
    unit = re.sub(r"\s*([*/^()])\s*", r"\1", unit.replace("**", "^"))
    return re.sub(r"\s+", " ", unit).strip()


def _drum_radius(entry, unit, drums):
    """The radius of the drum whose speed `entry` is (None for any other entry)."""
    keys, _ = _split(entry)
    if unit == "rad/s" and len(keys) == 4 and keys[:2] == ["analysis", "drums"] \
            and keys[3] == "speed":
        return drums.get(keys[2])
    return None


def what(text, entry, file):
    """What the quantity `text` is, in the words of messages ('a length', 'a force',
    ...), or None if it cannot be read."""
    for u, name in _NAMES:
        try:
            convert(text, entry, file, unit=u)
        except ModelError:
            continue
        return name
    return None


def _finite(v, text, entry, file):
    v = float(v)
    if not math.isfinite(v):
        raise ModelError(f"{text.strip()} is not a finite number in SI units", file, entry)
    return v


def _name(q, ureg):
    for u, name in _NAMES:
        ref = ureg.parse_units(u) if u else ureg.dimensionless
        if q.dimensionality == ref.dimensionality:
            return name
    return f"of dimension {q.dimensionality}"


def _example(unit):
    return {"N": "110 kN", "kg": "8 t", "m": "250 mm", "kg*m^2": "120 kg m^2",
            "Pa": "210 GPa", "m^2": "12 cm^2", "m^4": "2000 cm^4", "kg/m": "1.2 kg/m",
            "kg/m^3": "7850 kg/m^3", "m/s^2": "9.81 m/s^2", "N/m": "5 kN/mm",
            "N*m/rad": "4 GN m/rad", "s": "20 ms", "rad/s": "30 rpm", "N*m": "12 kN m",
            "rad": "5 deg", "deg": "80 deg", "": "20 %"}.get(unit, f"1 {unit}")


def _split(entry):
    """``analysis.drums.hoist.speed[2][0]`` -> (['analysis', 'drums', 'hoist',
    'speed'], [2, 0]): the keys, and the indices after the last key."""
    keys, index = [], []
    for name, i in re.findall(r"([^.\[\]]+)|\[(\d+)\]", entry or ""):
        if name:
            keys.append(name)
            index = []
        else:
            index.append(int(i))
    return keys, index
