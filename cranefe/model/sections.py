"""Cross-section properties from a section's shape and dimensions (m).

Local axes as for members: x along the member, the depth h along local z, the width b
along local y; `Iy` is about local y (bending in the x-z plane: the strong axis of an I,
channel or deep box), `Iz` about local z. Returns A, Iy, Iz, J and the shear areas Asy
(shear along y) and Asz (along z); `section_moduli` the elastic moduli Wy = Iy / max|z|,
Wz = Iz / max|y| of the extreme fibres. Root fillets (`r` of an I, `r1`, `r2` of an angle)
and corner radii (`ro`, `ri` of a box) are exact in A and the second moments (each a
circular spandrel, `_spandrel`); without them the corners are sharp. An angle is given in
its principal axes (`_angle`). Named rolled profiles: `profile_section` (profiles.csv).

Sources: areas and second moments are exact for the idealised shapes; torsion and
shear areas are the handbook formulas named at each shape: Young & Budynas, Roark's
Formulas for Stress and Strain, 7th ed., table 10.7 (torsion), and Cowper, "The shear
coefficient in Timoshenko's beam theory", J. Appl. Mech. 33 (1966) 335, table 1.
"""

import csv
import math
import os
import re

# shape -> (required dimensions, function); OPTIONAL: shape -> {dimension: default}
SHAPES = {}
OPTIONAL = {}


def _shape(*dims, **optional):
    def register(f):
        SHAPES[f.__name__.lstrip("_")] = (dims, f)
        OPTIONAL[f.__name__.lstrip("_")] = optional
        return f
    return register


# ------------------------------------------------------- pieces: rectangles and spandrels
# A section as a signed sum of rectangles and circular spandrels; each piece gives its
# integrals (A, int y, int z, int y^2, int z^2, int y z) about the shape's own origin.

def _rect(y0, y1, z0, z1, sign=1.0):
    """Integrals of the rectangle [y0, y1] x [z0, z1]."""
    dy, dz = y1 - y0, z1 - z0
    return [sign * v for v in (dy * dz, dz * (y1**2 - y0**2) / 2, dy * (z1**2 - z0**2) / 2,
                               dz * (y1**3 - y0**3) / 3, dy * (z1**3 - z0**3) / 3,
                               (y1**2 - y0**2) * (z1**2 - z0**2) / 4)]


def _spandrel(yc, zc, sy, sz, r, sign=1.0):
    """Integrals of the circular spandrel of radius r in the corner (yc, zc): the part of
    the square xi = sy (y - yc), eta = sz (z - zc) in [0, r]^2 outside the circle of radius
    r about (r, r) (a root fillet, or with sign -1 a rounded corner). In xi, eta (square
    minus quarter disc): int 1 = r^2 (1 - pi/4), int xi = r^3 (5/6 - pi/4),
    int xi^2 = r^4 (1 - 5 pi/16), int xi eta = r^4 (19/24 - pi/4)."""
    a0 = r**2 * (1 - math.pi / 4)
    m1 = r**3 * (5 / 6 - math.pi / 4)
    m2 = r**4 * (1 - 5 * math.pi / 16)
    m11 = r**4 * (19 / 24 - math.pi / 4)
    return [sign * v for v in (
        a0, yc * a0 + sy * m1, zc * a0 + sz * m1,
        yc**2 * a0 + 2 * yc * sy * m1 + m2, zc**2 * a0 + 2 * zc * sz * m1 + m2,
        yc * zc * a0 + (yc * sz + zc * sy) * m1 + sy * sz * m11)]


def _centroidal(pieces):
    """(A, yc, zc, Iy, Iz, Iyz) about the centroid of a signed sum of pieces
    (Iy = int z^2, Iz = int y^2, Iyz = int y z; parallel-axis theorem)."""
    A, Sy, Sz, Yy, Zz, Yz = (sum(p[k] for p in pieces) for k in range(6))
    yc, zc = Sy / A, Sz / A
    return A, yc, zc, Zz - A * zc**2, Yy - A * yc**2, Yz - A * yc * zc


def _moduli(Iy, Iz, corners):
    """Elastic section moduli (Wy, Wz) = (Iy / max|z|, Iz / max|y|) over the outline's
    corners (y, z) about the centroid."""
    return Iy / max(abs(z) for _, z in corners), Iz / max(abs(y) for y, _ in corners)


@_shape("b", "h")
def _rectangle(b, h, nu):
    """Solid rectangle. J: Saint-Venant's series (Roark table 10.7 case 4 in its exact
    form), J = a c^3 (1/3 - (64/pi^5)(c/a) sum_odd n^-5 tanh(n pi a / (2 c))) with
    a >= c the long and short sides. Shear: Cowper's 10 (1 + nu) / (12 + 11 nu)."""
    a, c = max(b, h), min(b, h)
    s = sum(math.tanh(n * math.pi * a / (2 * c)) / n**5 for n in range(1, 200, 2))
    J = a * c**3 * (1 / 3 - 64 / math.pi**5 * c / a * s)
    k = 10 * (1 + nu) / (12 + 11 * nu)
    A = b * h
    return dict(A=A, Iy=b * h**3 / 12, Iz=h * b**3 / 12, J=J, Asy=k * A, Asz=k * A,
                Wy=b * h**2 / 6, Wz=h * b**2 / 6)


@_shape("D")
def _circle(D, nu):
    """Solid circle: J = pi D^4 / 32; Cowper's 6 (1 + nu) / (7 + 6 nu)."""
    A = math.pi * D**2 / 4
    I = math.pi * D**4 / 64
    k = 6 * (1 + nu) / (7 + 6 * nu)
    return dict(A=A, Iy=I, Iz=I, J=2 * I, Asy=k * A, Asz=k * A, Wy=2 * I / D, Wz=2 * I / D)


@_shape("D", "t")
def _tube(D, t, nu):
    """Circular hollow section, outer diameter D, wall t: exact A, I and J = 2 I;
    Cowper's k = 6 (1 + nu)(1 + m^2)^2 / ((7 + 6 nu)(1 + m^2)^2 + (20 + 12 nu) m^2),
    m = d / D."""
    d = D - 2 * t
    A = math.pi * (D**2 - d**2) / 4
    I = math.pi * (D**4 - d**4) / 64
    m2 = (d / D) ** 2
    k = 6 * (1 + nu) * (1 + m2) ** 2 / ((7 + 6 * nu) * (1 + m2) ** 2 + (20 + 12 * nu) * m2)
    return dict(A=A, Iy=I, Iz=I, J=2 * I, Asy=k * A, Asz=k * A, Wy=2 * I / D, Wz=2 * I / D)


@_shape("b", "h", "t", ro=0.0, ri=0.0)
def _box(b, h, t, ro, ri, nu):
    """Rectangular hollow section b x h, uniform wall t, outer and inner corner radii ro,
    ri (0: sharp; EN 10210-2 hot-finished sections: ro = 1.5 t, ri = t). J with sharp
    corners: Bredt's thin-walled closed section, 4 A_m^2 t / s with the mid-line area
    A_m = (b - t)(h - t) and length s = 2 (b + h - 2 t) (Roark table 10.7 case 16); with
    radii EN 10210-2 annex B: It = t^3 s / 3 + 2 K A_m, K = 2 A_m t / s, with the
    mid-line corners of radius Rc = (ro + ri) / 2 (s = 2 (b - t + h - t) - 2 Rc (4 - pi),
    A_m = (b - t)(h - t) - Rc^2 (4 - pi)). Shear areas: the walls parallel to the shear,
    2 h t (along z) and 2 b t (along y)."""
    bi, hi = b - 2 * t, h - 2 * t
    pieces = [_rect(-b / 2, b / 2, -h / 2, h / 2), _rect(-bi / 2, bi / 2, -hi / 2, hi / 2, -1)]
    for sy in (-1, 1):
        for sz in (-1, 1):
            if ro:
                pieces.append(_spandrel(sy * b / 2, sz * h / 2, -sy, -sz, ro, -1))
            if ri:
                pieces.append(_spandrel(sy * bi / 2, sz * hi / 2, -sy, -sz, ri))
    A, _, _, Iy, Iz, _ = _centroidal(pieces)
    if ro or ri:
        Rc = (ro + ri) / 2
        s = 2 * (b - t + h - t) - 2 * Rc * (4 - math.pi)
        Am = (b - t) * (h - t) - Rc**2 * (4 - math.pi)
        J = t**3 * s / 3 + 2 * (2 * Am * t / s) * Am
    else:
        J = 4 * ((b - t) * (h - t)) ** 2 * t / (2 * (b + h - 2 * t))
    return dict(A=A, Iy=Iy, Iz=Iz, J=J, Asy=2 * b * t, Asz=2 * h * t, Wy=2 * Iy / h,
                Wz=2 * Iz / b)


def _open_torsion(b, tf, h, tw):
    """Thin-walled open section of two flanges b x tf and a web of mid-line height
    h - tf: J = (2 b tf^3 + (h - tf) tw^3) / 3 (Roark table 10.7 case 26)."""
    return (2 * b * tf**3 + (h - tf) * tw**3) / 3


def _rolled_i_torsion(b, h, tw, tf, r):
    """Torsion constant of a rolled I or H with root fillets r: El Darwish & Johnston,
    "Torsion of structural shapes", J. Struct. Div. ASCE 91 (1965) 203, as used for the
    tables of SCI P363 (Steel Building Design: Design Data):
    J = 2/3 b tf^3 + 1/3 (h - 2 tf) tw^3 + 2 alpha N^4 - 0.420 tf^4 with
    alpha = -0.042 + 0.2204 tw/tf + 0.1355 r/tf - 0.0865 r tw/tf^2 - 0.0725 tw^2/tf^2
    and N = ((tf + r)^2 + (r + tw/4) tw) / (2 r + tf), the diameter of the largest circle
    inscribed at the web-flange junction."""
    alpha = (-0.042 + 0.2204 * tw / tf + 0.1355 * r / tf - 0.0865 * r * tw / tf**2
             - 0.0725 * tw**2 / tf**2)
    N = ((tf + r) ** 2 + (r + tw / 4) * tw) / (2 * r + tf)
    return 2 / 3 * b * tf**3 + (h - 2 * tf) * tw**3 / 3 + 2 * alpha * N**4 - 0.420 * tf**4


@_shape("b", "h", "tw", "tf", r=0.0)
def _i(b, h, tw, tf, r, nu):
    """Doubly symmetric I or H: flanges b x tf, overall depth h, web tw, root fillets of
    radius r between web and flanges (0: sharp, welded plates). J: sharp, the thin-walled
    `_open_torsion`; with fillets `_rolled_i_torsion`. Shear areas: along z, sharp the
    web (h - 2 tf) tw, with fillets EN 1993-1-1 eq. 6.2.6(3)a's A - 2 b tf + (tw + 2 r) tf
    (the tables' Avz); along y, 5/6 of the flanges 2 b tf."""
    hw = h - 2 * tf
    pieces = [_rect(-b / 2, b / 2, h / 2 - tf, h / 2), _rect(-b / 2, b / 2, -h / 2, -h / 2 + tf),
              _rect(-tw / 2, tw / 2, -hw / 2, hw / 2)]
    if r:
        pieces += [_spandrel(sy * tw / 2, sz * hw / 2, sy, -sz, r)
                   for sy in (-1, 1) for sz in (-1, 1)]
        A, _, _, Iy, Iz, _ = _centroidal(pieces)
        J, Asz = _rolled_i_torsion(b, h, tw, tf, r), A - 2 * b * tf + (tw + 2 * r) * tf
    else:
        A = 2 * b * tf + hw * tw
        Iy = (b * h**3 - (b - tw) * hw**3) / 12
        Iz = (2 * tf * b**3 + hw * tw**3) / 12
        J, Asz = _open_torsion(b, tf, h, tw), hw * tw
    return dict(A=A, Iy=Iy, Iz=Iz, J=J, Asy=5 / 6 * 2 * b * tf, Asz=Asz, Wy=2 * Iy / h,
                Wz=2 * Iz / b)


@_shape("b", "h", "tw", "tf")
def _channel(b, h, tw, tf, nu):
    """Channel: two flanges b x tf from the web's back, overall depth h, web tw. Iz about
    the centroidal axis parallel to the web (the centroid lies y_c from the web's back;
    the shear centre's offset from it is not modelled). Shear areas as the I."""
    hw = h - 2 * tf
    A = 2 * b * tf + hw * tw
    yc = (2 * b * tf * b / 2 + hw * tw * tw / 2) / A
    Iy = (b * h**3 - (b - tw) * hw**3) / 12
    Iz = 2 * (tf * b**3 / 12 + b * tf * (b / 2 - yc) ** 2) \
        + hw * tw**3 / 12 + hw * tw * (tw / 2 - yc) ** 2
    return dict(A=A, Iy=Iy, Iz=Iz, J=_open_torsion(b, tf, h, tw), Asy=5 / 6 * 2 * b * tf,
                Asz=hw * tw, Wy=2 * Iy / h, Wz=Iz / max(yc, b - yc))


def angle_geometry(h, b, t, r1=0.0, r2=0.0):
    """An angle's legs h (along z') and b (along y') from the heel at the origin, thickness
    t, root fillet r1 and toe radii r2: (A, (yc, zc), Iy', Iz', Iy'z') about its centroid
    in the legs' axes, and the principal angle theta (rad) from y' to the major axis u."""
    pieces = [_rect(0, b, 0, t), _rect(0, t, t, h)]
    if r1:
        pieces.append(_spandrel(t, t, 1, 1, r1))
    if r2:
        pieces += [_spandrel(b, t, -1, -1, r2, -1), _spandrel(t, h, -1, -1, r2, -1)]
    A, yc, zc, Iy, Iz, Iyz = _centroidal(pieces)
    # the major axis u at theta from y': int (z cos - y sin)^2 largest (Mohr's circle)
    theta = 0.5 * math.atan2(-2 * Iyz, Iy - Iz)
    return A, (yc, zc), Iy, Iz, Iyz, theta


@_shape("h", "b", "t", r1=0.0, r2=0.0)
def _angle(h, b, t, r1, r2, nu):
    """Angle with legs h and b, thickness t, root fillet r1 and toe radii r2 (EN 10056-1:
    r2 = r1 / 2), in its principal axes: local y is the major axis u (for an equal angle
    the axis of symmetry, from the heel towards the root), local z the minor axis v, so
    Iy = Iu, Iz = Iv (`angle_geometry`). Moduli from the sharp outline's corners in u, v.
    J: the two legs as thin rectangles with El Darwish & Johnston's junction term (see
    `_angle_torsion`). Shear areas: each leg carries the shear along its own length, so
    with the legs at 45 degrees to u and v (equal angle) both are A / 2."""
    A, (yc, zc), _, _, _, th = angle_geometry(h, b, t, r1, r2)
    Iu_v = angle_principal(h, b, t, r1, r2)
    c, s = math.cos(th), math.sin(th)
    pts = [(y - yc, z - zc) for y, z in ((0, 0), (b, 0), (b, t), (t, t), (t, h), (0, h))]
    uv = [(y * c + z * s, -y * s + z * c) for y, z in pts]
    Wy, Wz = _moduli(*Iu_v, uv)
    return dict(A=A, Iy=Iu_v[0], Iz=Iu_v[1], J=_angle_torsion(h, b, t, r1), Asy=A / 2,
                Asz=A / 2, Wy=Wy, Wz=Wz)


def _angle_torsion(h, b, t, r1):
    """Torsion constant of an angle: the legs as thin rectangles with Roark's correction
    at their two free ends, plus a junction term in El Darwish & Johnston's form (J.
    Struct. Div. ASCE 91 (1965) 203): J = (h + b - t) t^3 / 3 - 0.21 t^4 + alpha D^4, with
    D = 2 ((3 r1 + 2 t) - sqrt(2) (2 r1 + t)) the diameter of the largest circle inscribed
    at the root. alpha = 0.0405 + 0.0589 r1 / t is fitted here to finite-element
    Saint-Venant solutions (sectionproperties 3.10.2, 6-node triangles, converged to 1e-4)
    of 19 EN 10056-1 angles with r1 / t from 0.64 to 1.5: within 0.11 % of all of them
    (tests/test_sections_profiles.py). SCI P363 prints values about 2 % higher."""
    D = 2 * ((3 * r1 + 2 * t) - math.sqrt(2) * (2 * r1 + t)) if r1 else 0.0
    return (h + b - t) * t**3 / 3 - 0.21 * t**4 + (0.0405 + 0.0589 * r1 / t) * D**4


def angle_principal(h, b, t, r1=0.0, r2=0.0):
    """(Iu, Iv): the principal second moments of an angle (major, minor)."""
    _, _, Iy, Iz, Iyz, _ = angle_geometry(h, b, t, r1, r2)
    m, d = (Iy + Iz) / 2, math.hypot((Iy - Iz) / 2, Iyz)
    return m + d, m - d


SHAPES["h"] = SHAPES["i"]       # an H section is an I with wide flanges
OPTIONAL["h"] = OPTIONAL["i"]


def _evaluate(shape, dims, nu):
    names, f = SHAPES[shape]
    opt = OPTIONAL[shape]
    return f(*(dims[n] for n in names), *(dims.get(n, v) for n, v in opt.items()), nu)


def section_properties(shape, dims, nu):
    """(A, Iy, Iz, J, Asy, Asz) of `shape` with its dimensions `dims` (a dict, m) and
    Poisson's ratio nu (for the shear coefficients of solid and tubular shapes)."""
    p = _evaluate(shape, dims, nu)
    return tuple(p[k] for k in ("A", "Iy", "Iz", "J", "Asy", "Asz"))


def section_moduli(shape, dims):
    """(Wy, Wz): elastic section moduli of `shape`'s extreme fibres, Iy / max|z| and
    Iz / max|y| (for the normal stress N/A +- My/Wy +- Mz/Wz)."""
    p = _evaluate(shape, dims, 0.3)
    return p["Wy"], p["Wz"]


# ------------------------------------------------------------------- named profiles

_TABLE = None
PROFILES_CSV = os.path.join(os.path.dirname(__file__), "profiles.csv")


def profile_table():
    """{normalised name: row dict} of profiles.csv (the rows' numbers as floats, blank
    cells None), read once."""
    global _TABLE
    if _TABLE is None:
        with open(PROFILES_CSV, newline="") as fh:
            rows = csv.DictReader(line for line in fh if not line.startswith("#"))
            _TABLE = {normalise_profile(r["name"]): {
                k: (v if k in ("name", "family") else float(v) if v else None)
                for k, v in r.items()} for r in rows}
    return _TABLE


def normalise_profile(name):
    """'HEB 200', 'heb200', 'L 100x10', 'L100x100x10', 'SHS 100 x 100 x 5.0' -> one key:
    upper-case family, no blanks, 'x' separators, no trailing '.0', an equal angle's and a
    square section's second leg/side written out."""
    s = re.sub(r"\s+", "", str(name)).upper().replace("X", "x").replace("Ø", "")
    s = re.sub(r"(\d+)\.0+(?=x|$)", r"\1", s)
    m = re.fullmatch(r"(L|SHS)(\d+(?:\.\d+)?)x(\d+(?:\.\d+)?)", s)
    if m:                                   # L 100x10 -> L100x100x10, SHS 100x5 likewise
        s = f"{m[1]}{m[2]}x{m[2]}x{m[3]}"
    return s


def _hollow_from_name(key):
    """Dimensions (m) of a hot-finished CHS/SHS/RHS named by its size (EN 10210-2 corner
    radii ro = 1.5 t, ri = t), or None."""
    m = re.fullmatch(r"CHS(\d+(?:\.\d+)?)x(\d+(?:\.\d+)?)", key)
    if m:
        return "tube", {"D": float(m[1]) / 1e3, "t": float(m[2]) / 1e3}
    m = re.fullmatch(r"(?:SHS|RHS)(\d+(?:\.\d+)?)x(\d+(?:\.\d+)?)x(\d+(?:\.\d+)?)", key)
    if m:
        h, b, t = (float(v) / 1e3 for v in m.groups())
        return "box", {"b": b, "h": h, "t": t, "ro": 1.5 * t, "ri": t}
    return None


def profile_shape(name):
    """(shape, dims in m) of a named profile: a row of profiles.csv (IPE, HEA, HEB, HEM,
    equal angles L, CHS, SHS, RHS) or a hollow section named by its size; None if unknown.
    """
    key = normalise_profile(name)
    row = profile_table().get(key)
    if row is None:
        return _hollow_from_name(key)
    mm = {k: (v / 1e3 if isinstance(v, float) else v) for k, v in row.items()}
    fam = row["family"]
    if fam in ("IPE", "HEA", "HEB", "HEM"):
        return "i", {"b": mm["b"], "h": mm["h"], "tw": mm["tw"], "tf": mm["tf"], "r": mm["r1"]}
    if fam == "L":
        return "angle", {"h": mm["h"], "b": mm["b"], "t": mm["t"], "r1": mm["r1"],
                         "r2": mm["r2"]}
    return _hollow_from_name(key)


def profile_names():
    """The tabulated profiles' names, in the table's order."""
    return [r["name"] for r in profile_table().values()]
