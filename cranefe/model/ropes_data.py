"""Wire ropes from their designation: metallic area, EA and mass per metre.

A rope given as ``diameter: 20 mm, construction: 6x36 IWRC`` gets (docs/model-format.md,
"Ropes from their designation"):

- metallic area      ``A = C d^2``            (Feyrer, Wire Ropes, eq. 1.5; C = f pi / 4,
                                               f the fill factor, eq. 1.5a)
- mass per metre     ``m = W d^2 / 100``      (kg/m with d in mm; Feyrer eq. 1.5b)
- axial rigidity     ``EA = E_rope A``        (E_rope: the rope modulus on the metallic
                                               area, Feyrer ch. 3)
- min. breaking force ``F_min = K d^2 R_r / 1000`` (kN, d in mm, R_r in N/mm^2)

with the factors W, C, K of EN 12385-4:2002 (the same classes as ISO 2408), as printed in
Feyrer, *Wire Ropes*, 2nd ed., Springer 2015, Table 1.9. The user's own ``EA`` and
``mass_per_length`` win over the derived ones.
"""

import math
import re

# class -> core -> (W, C, K): W in kg/(100 m mm^2), C in mm^2/mm^2, K dimensionless.
# EN 12385-4:2002 / Feyrer Table 1.9; "steel" is the steel rope core (IWRC) of the
# single-layer classes and the steel core of the multi-strand (rotation-resistant) ones.
FACTORS = {
    "6x7": {"FC": (0.345, 0.369, 0.332), "steel": (0.384, 0.432, 0.359)},
    "8x7": {"FC": (0.327, 0.335, 0.291), "steel": (0.391, 0.439, 0.359)},
    "6x19": {"FC": (0.359, 0.384, 0.330), "steel": (0.400, 0.449, 0.356)},
    "8x19": {"FC": (0.340, 0.349, 0.293), "steel": (0.407, 0.457, 0.356)},
    "6x36": {"FC": (0.367, 0.393, 0.330), "steel": (0.409, 0.460, 0.356)},
    "8x36": {"FC": (0.348, 0.357, 0.293), "steel": (0.417, 0.468, 0.356)},
    "6x35N": {"FC": (0.352, 0.377, 0.317), "steel": (0.392, 0.441, 0.345)},
    "6x19M": {"FC": (0.344, 0.357, 0.307), "steel": (0.372, 0.418, 0.332)},
    "6x37M": {"FC": (0.334, 0.357, 0.295), "steel": (0.372, 0.418, 0.319)},
    "18x7": {"FC": (0.382, 0.408, 0.328), "steel": (0.401, 0.433, 0.328)},
    "34x7": {"FC": (0.390, 0.416, 0.318), "steel": (0.401, 0.428, 0.318)},
}
# Typical rope modulus on the metallic area at working loads (10-30 % of the minimum
# breaking force), Pa. Ropes stiffen with load and use; these are middle values of the
# ranges in Feyrer ch. 3 and makers' data (about +-15 %): give `modulus` or `EA` from the
# rope maker's data sheet where the stiffness matters.
MODULUS = {("6", "FC"): 90e9, ("6", "steel"): 105e9, ("8", "FC"): 80e9,
           ("8", "steel"): 100e9, ("multi", "FC"): 90e9, ("multi", "steel"): 100e9}
# words for whole families, with the class they stand for and its default core
ALIASES = {"8-strand": ("8x19", "steel"), "rotation-resistant": ("34x7", "steel"),
           "35wx7": ("34x7", "steel"), "35x7": ("34x7", "steel")}
KEYS = ("diameter", "construction", "modulus")
GRADE = 1770.0        # N/mm^2: the rope grade the reported minimum breaking force is for

_CORES = (("FC", r"\b(FC|NFC|SFC|fib(re|er)(\s+core)?)\b"),
          ("steel", r"\b(IWRC|IWR|WSC|WC|steel(\s+core)?)\b"))


def classify(text):
    """``'6x36WS-IWRC'`` -> ('6x36', 'steel'), the EN 12385-4 class and its core (core
    None when the text gives none). Raises ValueError with what is wrong."""
    t = text.strip()
    core = None
    for name, pattern in _CORES:
        if re.search(pattern, t, flags=re.IGNORECASE):
            core = name
    low = t.lower().replace("×", "x")
    if "compact" in low:
        raise ValueError("compacted-strand ropes are not in the EN 12385-4 tables cranefe "
                         "holds (their factors are the maker's); give EA and "
                         "mass_per_length from the rope's data sheet")
    for word, (cls, default) in ALIASES.items():
        if low.replace(" ", "").replace("(", "").replace(")", "").startswith(word):
            return cls, core or default
    m = re.match(r"(\d+)\s*x\s*(\d+)\s*([a-z]*)", low)
    if not m:
        raise ValueError(f"'{text}' is not a rope class such as 6x36 IWRC, 6x19 FC, "
                         "8x19 IWRC, 18x7, 35x7, 8-strand or rotation-resistant")
    strands, wires, kind = int(m.group(1)), int(m.group(2)), m.group(3)
    cls = _class(strands, wires, kind)
    if cls is None:
        raise ValueError(f"no EN 12385-4 class holds {strands}x{wires}{kind.upper()}; "
                         f"known classes: {', '.join(FACTORS)}")
    if core is None and strands > 8:
        core = "steel"
    return cls, core


def _class(strands, wires, kind):
    """The EN 12385-4 class of `strands` strands of `wires` wires (kind: the strand
    suffix: WS, S, F, W for parallel lay, M cross lay, N compound lay)."""
    if strands in (17, 18, 19) and wires == 7:
        return "18x7"
    if strands in (34, 35, 36) and wires == 7:
        return "34x7"
    if strands not in (6, 8):
        return None
    if kind.startswith("m"):
        return {19: "6x19M", 37: "6x37M"}.get(wires) if strands == 6 else None
    if kind.startswith("n"):
        return "6x35N" if strands == 6 and 27 <= wires <= 49 else None
    if 5 <= wires <= 9:
        return f"{strands}x7"
    if 15 <= wires <= 26:           # 9-12 outer wires: Seale, Filler, Warrington
        return f"{strands}x19"
    if 27 <= wires <= 49:           # 12-18 outer wires: Warrington-Seale
        return f"{strands}x36"
    return None


def derive(diameter, construction, modulus=None):
    """What a rope of `diameter` (m) and `construction` gives, as a dict of SI values
    (raises ValueError for an unknown construction or a missing core)."""
    cls, core = classify(construction)
    if core is None:
        raise ValueError(f"'{construction}' does not say the core; write e.g. "
                         f"'{cls} IWRC' (steel core) or '{cls} FC' (fibre core)")
    W, C, K = FACTORS[cls][core]
    family = cls.split("x")[0] if cls.split("x")[0] in ("6", "8") else "multi"
    E = MODULUS[family, core] if modulus is None else modulus
    d_mm = diameter * 1e3
    A = C * d_mm**2 * 1e-6                                      # m^2, eq. 1.5
    return {"class": cls, "core": "IWRC" if core == "steel" and family != "multi"
            else ("steel core" if core == "steel" else "FC"),
            "diameter_m": diameter, "W": W, "C": C, "K": K,
            "fill_factor": C * 4 / math.pi,                      # eq. 1.5a
            "metallic_area_m2": A, "modulus_pa": E,
            "modulus_from": "given" if modulus is not None else "typical",
            "EA_N": E * A, "mass_per_length_kg_m": W * d_mm**2 / 100,   # eq. 1.5b
            "min_breaking_force_N": K * d_mm**2 * GRADE}          # N, grade 1770


def rope_values(rp, r, e):
    """(EA, mass_per_length, derived) of the raw rope `rp` at entry `e`: the user's EA
    and mass_per_length where given, else those of `diameter` + `construction`
    (derived is None without a designation)."""
    given = [k for k in ("diameter", "construction") if k in rp]
    derived = None
    if given:
        if len(given) == 1:
            r.fail(e, "a rope designation needs both 'diameter' and 'construction' (e.g. "
                   "diameter: 20 mm, construction: 6x36 IWRC)")
        d = r.number(rp["diameter"], f"{e}.diameter", positive=True)
        mod = r.number(rp["modulus"], f"{e}.modulus", positive=True) \
            if "modulus" in rp else None
        if not isinstance(rp["construction"], str):
            r.fail(f"{e}.construction", "must be text such as '6x36 IWRC'")
        try:
            derived = derive(d, rp["construction"], mod)
        except ValueError as exc:
            r.fail(f"{e}.construction", str(exc))
        derived["EA_from"] = "given" if "EA" in rp else "designation"
        derived["mass_from"] = "given" if "mass_per_length" in rp else "designation"
    elif "modulus" in rp:
        r.fail(f"{e}.modulus", "the rope modulus is used with 'diameter' and "
               "'construction'; give EA instead, or add them")
    if "EA" in rp:
        EA = r.number(rp["EA"], f"{e}.EA", positive=True)
    elif derived:
        EA = derived["EA_N"]
    else:
        r.fail(e, "missing required key 'EA'; add it (N per fall), or give the rope's "
               "'diameter' and 'construction' (e.g. 6x36 IWRC)")
    if "mass_per_length" in rp:
        mass = r.number(rp["mass_per_length"], f"{e}.mass_per_length", nonneg=True)
    else:
        mass = derived["mass_per_length_kg_m"] if derived else 0.0
    return EA, mass, derived


def designations(data, r):
    """{rope name: derived dict} of the ropes of raw model `data` given by designation
    (what `cranefe check` shows)."""
    out = {}
    ropes = data.get("ropes") if isinstance(data, dict) else None
    for name, rp in (ropes or {}).items():
        if isinstance(rp, dict) and "diameter" in rp:
            out[name] = rope_values(rp, r, f"ropes.{name}")[2]
    return out
