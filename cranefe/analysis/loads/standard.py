"""EN 13001-2 (Crane safety - General design - Part 2: Load actions) dynamic factors
phi1-phi7 as data and formulas, each with the clause it comes from (docs/loads.md).

Clause and table numbers follow the widely quoted structure of EN 13001-2:2004/2014
(4.2.2 regular loads, 4.2.4 exceptional loads); the project holds no copy of the
standard, so every entry names its clause in ``CLAUSES`` and docs/loads.md says which
numbers are quoted from secondary sources and must be checked against the user's copy.
The same phi2 classes are in EN 1991-3:2006 (actions induced by cranes), 2.6, Table 2.5.
"""

import numpy as np

from ...errors import ModelError

# where each factor is defined (EN 13001-2; docs/loads.md "Clauses" for the caveats)
CLAUSES = {
    "phi1": "EN 13001-2, 4.2.2.1 hoisting and gravity effects acting on the mass of the "
            "crane",
    "phi2": "EN 13001-2, 4.2.2.2 hoisting an unrestrained grounded load; Table 2 "
            "(beta2, phi2,min per hoisting class), Table 3 (v_h per hoist drive class)",
    "phi3": "EN 13001-2, 4.2.2.3 sudden release of a part of the hoist load",
    "phi4": "EN 13001-2, 4.2.2.4 loads caused by travelling on uneven surface",
    "phi5": "EN 13001-2, 4.2.2.5 loads caused by acceleration of all crane drives",
    "phi6": "EN 13001-2, 4.2.4.2 test loads",
    "phi7": "EN 13001-2, 4.2.4.3 loads due to buffer forces",
}

# Table 2 (EN 1991-3 Table 2.5): hoisting class -> (beta2 [s/m], phi2,min)
HOISTING_CLASSES = {"HC1": (0.17, 1.05), "HC2": (0.34, 1.10), "HC3": (0.51, 1.15),
                    "HC4": (0.68, 1.20)}

# Table 3: characteristic hoisting speed v_h per hoist drive class and load combination.
# Entries: ("max", f) -> f * v_h,max; ("creep", 1) -> the creep speed v_h,CS; None: the
# combination does not apply. The C1 row is quoted from secondary sources (docs/loads.md).
DRIVE_CLASSES = {
    "HD1": {"A1": ("max", 1.0), "B1": ("max", 1.0), "C1": None},
    "HD2": {"A1": ("creep", 1.0), "B1": ("creep", 1.0), "C1": ("max", 1.0)},
    "HD3": {"A1": ("creep", 1.0), "B1": ("creep", 1.0), "C1": None},
    "HD4": {"A1": ("max", 0.5), "B1": ("max", 0.5), "C1": ("max", 1.0)},
    "HD5": {"A1": ("max", 0.0), "B1": ("max", 0.0), "C1": ("max", 0.5)},
}
DRIVE_CLASS_TEXT = {
    "HD1": "creep speed not available, or the drive can be started without it",
    "HD2": "the crane driver can select a creep speed",
    "HD3": "the drive control ensures creep speed until the load is lifted off",
    "HD4": "stepless control: the driver increases the speed steplessly",
    "HD5": "stepless automatic control: after pre-tensioning the hoist medium the "
           "acceleration is independent of the driver (lift-off at v_h = 0)",
}

# 4.2.2.3: beta3 for the release of a part of the load
BETA3 = {"slow": 0.5, "fast": 1.0}
BETA3_TEXT = {"slow": "grabs or similar slow-release devices",
              "fast": "magnets or similar rapid-release devices"}

# 4.2.2.5 guidance for phi5: (lowest, highest, when it applies)
PHI5_GUIDANCE = (
    (1.0, 1.0, "centrifugal forces"),
    (1.0, 1.5, "drives without backlash (or backlash without dynamic effect) and with "
               "smooth changes of force"),
    (1.5, 2.0, "drives without backlash but with sudden changes of force"),
    (3.0, 3.0, "drives with considerable backlash, unless estimated more accurately by "
               "an elastic-kinetic (spring-mass) model"),
)

PHI4_NEEDS = ("phi4 (travelling on uneven surface) is not a number of the standard's "
              "tables: it needs the track's steps and gaps (height of a step, width of a "
              "gap), the travel speed, the wheel diameter and the crane's masses and "
              "stiffnesses (an elastic-kinetic model) or measurements; within the rail "
              "tolerances of EN 1993-6 EN 1991-3 sets phi4 = 1.0")


def phi1(a):
    """4.2.2.1: the crane's own mass times phi1 = 1 +/- a, 0 <= a <= 0.1 (upper and
    lower value: lifting off and setting down excite the crane's own vibrations)."""
    if not 0.0 <= a <= 0.1:
        raise ModelError(f"phi1 = 1 +/- a needs 0 <= a <= 0.1 (got a = {a})")
    return 1.0 + a, 1.0 - a


def phi2(hoisting_class, v_h):
    """4.2.2.2, Table 2: phi2 = phi2,min + beta2 v_h (v_h in m/s, the characteristic
    hoisting speed of Table 3 for the drive class); array v_h allowed."""
    beta2, phi2_min = _hc(hoisting_class)
    return phi2_min + beta2 * np.asarray(v_h, dtype=float)


def _hc(name):
    try:
        return HOISTING_CLASSES[name]
    except KeyError:
        raise ModelError(f"unknown hoisting class {name!r}: use one of "
                         f"{', '.join(HOISTING_CLASSES)}") from None


def characteristic_speed(drive_class, v_max, v_creep=None, combination="A1"):
    """Table 3: the steady hoisting speed v_h [m/s] to use in phi2 for a hoist drive
    class (HD1-HD5) and load combination (A1, B1: regular; C1: phi2C, exceptional).
    Returns None where the standard gives no value (the case does not arise)."""
    if drive_class not in DRIVE_CLASSES:
        raise ModelError(f"unknown hoist drive class {drive_class!r}: use one of "
                         f"{', '.join(DRIVE_CLASSES)}")
    row = DRIVE_CLASSES[drive_class].get(combination, "missing")
    if row == "missing":
        raise ModelError(f"unknown load combination {combination!r}: use A1, B1 or C1")
    if row is None:
        return None
    kind, f = row
    if kind == "creep":
        if v_creep is None:
            raise ModelError(f"{drive_class} lifts at creep speed: give v_creep")
        return float(v_creep)
    return f * float(v_max)


def phi3(dm_over_m, release="fast"):
    """4.2.2.3: phi3 = 1 - (dm/m)(1 + beta3), the hoist load m losing dm; beta3 = 0.5
    (slow release: grabs) or 1.0 (fast release: magnets), or a number."""
    beta3 = BETA3[release] if isinstance(release, str) else float(release)
    if not 0.0 <= dm_over_m <= 1.0:
        raise ModelError(f"the released part dm/m must lie in [0, 1] (got {dm_over_m})")
    return 1.0 - dm_over_m * (1.0 + beta3)


def phi5_guidance(backlash=False, sudden=False, centrifugal=False):
    """4.2.2.5: the standard's guidance range (low, high, text) for phi5."""
    if centrifugal:
        return PHI5_GUIDANCE[0]
    if backlash:
        return PHI5_GUIDANCE[3]
    return PHI5_GUIDANCE[2] if sudden else PHI5_GUIDANCE[1]


def phi6(phi2_value=None, test="dynamic"):
    """4.2.4.2: test loads. Dynamic test phi6 = 0.5 (1 + phi2); static test phi6 = 1."""
    if test == "static":
        return 1.0
    if test != "dynamic":
        raise ModelError(f"test must be 'dynamic' or 'static' (got {test!r})")
    return 0.5 * (1.0 + float(phi2_value))


def phi7(xi):
    """4.2.4.3: buffer forces. phi7 = 1.25 for 0 <= xi <= 0.5, 1.25 + 0.7 (xi - 0.5)
    for 0.5 < xi <= 1, xi the buffer characteristic (`buffer_characteristic`)."""
    if not 0.0 <= xi <= 1.0:
        raise ModelError(f"the buffer characteristic xi must lie in [0, 1] (got {xi})")
    return 1.25 if xi <= 0.5 else 1.25 + 0.7 * (xi - 0.5)


def buffer_characteristic(stroke, force):
    """xi = (energy absorbed) / (peak force * full stroke) of a buffer's force-stroke
    curve (trapezoidal rule on the samples): 0.5 for a linear spring, 1 for a constant
    force."""
    u, F = np.asarray(stroke, float), np.asarray(force, float)
    work = float(np.sum(0.5 * (F[1:] + F[:-1]) * np.diff(u)))
    return work / (float(F.max()) * float(u[-1] - u[0]))


def behaves_like(v_h, phi2_values):
    """The hoisting class a crane behaves like from its computed phi2 at speeds v_h.

    Returns a dict: ``within`` the lowest class whose line phi2,min + beta2 v_h is at or
    above every computed point (None: above HC4 somewhere), ``closest`` the class whose
    line is nearest in the least-squares sense, and per class the largest excess
    ``max(phi2 - line)`` (negative: the class covers the crane with that margin).
    """
    v, p = np.asarray(v_h, float), np.asarray(phi2_values, float)
    excess = {hc: float(np.max(p - phi2(hc, v))) for hc in HOISTING_CLASSES}
    rms = {hc: float(np.sqrt(np.mean((p - phi2(hc, v))**2))) for hc in HOISTING_CLASSES}
    within = next((hc for hc in HOISTING_CLASSES if excess[hc] <= 0.0), None)
    return {"within": within, "closest": min(rms, key=rms.get), "excess": excess,
            "rms": rms}
