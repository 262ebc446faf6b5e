"""Cross-section properties from a section's shape and dimensions (m).

Local axes as for members: x along the member, the depth h along local z, the width b
along local y; `Iy` is about local y (bending in the x-z plane: the strong axis of an I,
channel or deep box), `Iz` about local z. Returns A, Iy, Iz, J and the shear areas Asy
(shear along y) and Asz (along z). Sharp corners, no fillets or corner radii: rolled
profiles from tables carry a little more area and torsion stiffness than these.

Sources: areas and second moments are exact for the idealised shapes; torsion and
shear areas are the handbook formulas named at each shape: Young & Budynas, Roark's
Formulas for Stress and Strain, 7th ed., table 10.7 (torsion), and Cowper, "The shear
coefficient in Timoshenko's beam theory", J. Appl. Mech. 33 (1966) 335, table 1.
"""

import math

# shape -> (required dimensions, function)
SHAPES = {}


def _shape(*dims):
    def register(f):
        SHAPES[f.__name__.lstrip("_")] = (dims, f)
        return f
    return register


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
    return A, b * h**3 / 12, h * b**3 / 12, J, k * A, k * A


@_shape("D")
def _circle(D, nu):
    """Solid circle: J = pi D^4 / 32; Cowper's 6 (1 + nu) / (7 + 6 nu)."""
    A = math.pi * D**2 / 4
    I = math.pi * D**4 / 64
    k = 6 * (1 + nu) / (7 + 6 * nu)
    return A, I, I, 2 * I, k * A, k * A


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
    return A, I, I, 2 * I, k * A, k * A


@_shape("b", "h", "t")
def _box(b, h, t, nu):
    """Rectangular hollow section b x h, uniform wall t, sharp corners. J: Bredt's
    thin-walled closed section, 4 A_m^2 t / s with the mid-line area A_m = (b - t)(h - t)
    and length s = 2 (b + h - 2 t) (Roark table 10.7 case 16). Shear areas: the walls
    parallel to the shear, 2 h t (along z) and 2 b t (along y)."""
    bi, hi = b - 2 * t, h - 2 * t
    A = b * h - bi * hi
    J = 4 * ((b - t) * (h - t)) ** 2 * t / (2 * (b + h - 2 * t))
    return A, (b * h**3 - bi * hi**3) / 12, (h * b**3 - hi * bi**3) / 12, J, \
        2 * b * t, 2 * h * t


def _open_torsion(b, tf, h, tw):
    """Thin-walled open section of two flanges b x tf and a web of mid-line height
    h - tf: J = (2 b tf^3 + (h - tf) tw^3) / 3 (Roark table 10.7 case 26)."""
    return (2 * b * tf**3 + (h - tf) * tw**3) / 3


@_shape("b", "h", "tw", "tf")
def _i(b, h, tw, tf, nu):
    """Doubly symmetric I or H: flanges b x tf, overall depth h, web tw. Shear areas:
    the web (h - 2 tf) tw along z, 5/6 of the flanges 2 b tf along y."""
    hw = h - 2 * tf
    A = 2 * b * tf + hw * tw
    Iy = (b * h**3 - (b - tw) * hw**3) / 12
    Iz = (2 * tf * b**3 + hw * tw**3) / 12
    return A, Iy, Iz, _open_torsion(b, tf, h, tw), 5 / 6 * 2 * b * tf, hw * tw


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
    return A, Iy, Iz, _open_torsion(b, tf, h, tw), 5 / 6 * 2 * b * tf, hw * tw


SHAPES["h"] = SHAPES["i"]       # an H section is an I with wide flanges


def section_properties(shape, dims, nu):
    """(A, Iy, Iz, J, Asy, Asz) of `shape` with its dimensions `dims` (a dict, m) and
    Poisson's ratio nu (for the shear coefficients of solid and tubular shapes)."""
    names, f = SHAPES[shape]
    return f(*(dims[n] for n in names), nu)
