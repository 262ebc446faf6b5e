"""Plausibility warnings: numbers that load fine but are likely a slip of units.

Not errors: a model may be unusual on purpose. Each warning names the entry, what is
odd and the likely mistake (docs/model-format.md, "Checks and exit status"):

- a rope stretched statically by more than `STRETCH` of its length (a steel wire rope
  breaks near 2 % strain): EA given in kN as if in N;
- a mass, or an axial stiffness (ropes' EA/L and axial springs), more than `SPREAD`
  times away from the model's median of its kind (three or more of a kind): a mass in
  t written as kg, a stiffness in N/mm written as N/m;
- a mode slower than a pendulum as long as the model allows (the longest rope path or
  the model's size, whichever is longer): something is far too soft or too heavy for
  the geometry, as EA = 11000 "kN" read as N gives a 0.1 Hz bounce below the pendulum.

The functions take plain arrays (static tensions, frequencies) so that this stage needs
nothing downstream of the model.
"""

import numpy as np

STRETCH = 0.03        # static strain: beyond steel's breaking strain (about 0.015-0.02)
SPREAD = 1e3          # a mass or axial stiffness this far from the median of its kind
PENDULUM = 1.0        # a mode slower than sqrt(g / (PENDULUM * longest length))


def rope_lengths(model):
    """(nr,) deformable length of each rope: sum of falls x span + extra_length, m."""
    c = model.coords
    return np.array([float(np.linalg.norm(c[r.span_b] - c[r.span_a], axis=1) @ r.falls)
                     + r.extra_length for r in model.ropes])


def warnings(model, rope_tension=None, omega=None):
    """Plausibility warnings of `model`.

    rope_tension : (nr, 2) smallest and largest static tension of each rope (N), or None
    omega : (m,) angular frequencies of its elastic modes (rad/s), or None
    """
    out = []
    if rope_tension is not None:
        out += _stretch(model, np.asarray(rope_tension)[:, 1])
    out += _spread("mass", "kg", _masses(model), lighter="a mass in t written as kg? "
                   "(write '{v:.4g} t')", heavier="a mass in g, or a wrong exponent?")
    out += _spread("axial stiffness", "N/m", _axial(model),
                   lighter="EA or a stiffness in kN (kN/m) written as N (N/m)?",
                   heavier="a stiffness in N/mm written as N/m, or a wrong exponent?")
    if omega is not None:
        out += _pendulum(model, np.asarray(omega, dtype=float))
    return out


def _stretch(model, tension):
    out = []
    for r, S in zip(model.ropes, tension):
        strain = S / r.EA
        if np.isfinite(strain) and strain > STRETCH:
            out.append(
                f"ropes.{r.name}: the static tension {S:.4g} N stretches the rope by "
                f"{100 * strain:.3g} % of its length (EA = {r.EA:.4g} N), beyond the "
                f"breaking strain of a steel rope (about 2 %): EA given in kN as if in N? "
                f"(write 'EA: {r.EA:.6g} kN' if so)")
    return out


def _masses(model):
    """[(entry, kg)] of the point masses and the bodies with mass."""
    names = model.node_names
    out = [(f"masses.{names[i]}", float(m)) for i, m in zip(model.masses.nodes,
                                                              model.masses.mass)]
    return out + [(f"bodies.{b.name}.mass", float(b.mass)) for b in model.bodies
                  if b.mass > 0]


def _axial(model):
    """[(entry, N/m)] of the ropes (EA / deformable length) and the axial springs."""
    out = [(f"ropes.{r.name}.EA", r.EA / L) for r, L in zip(model.ropes,
                                                            rope_lengths(model)) if L > 0]
    return out + [(f"springs.{s.name}.stiffness", float(s.stiffness))
                  for s in model.springs if s.type == "axial"]


def _spread(kind, unit, values, lighter, heavier):
    """Values more than SPREAD away from the median of their kind (3 or more: the
    median is then one of the model's own values, not dragged by the odd one)."""
    if len(values) < 3:
        return []
    med = float(np.median([x for _, x in values]))
    out = []
    for entry, x in values:
        if x <= 0 or med <= 0:
            continue
        ratio = x / med
        if ratio < 1 / SPREAD or ratio > SPREAD:
            word, hint = ("lighter" if kind == "mass" else "softer", lighter) \
                if ratio < 1 else ("heavier" if kind == "mass" else "stiffer", heavier)
            times = 1 / ratio if ratio < 1 else ratio          # at least SPREAD
            out.append(f"{entry}: the {kind} {x:.4g} {unit} is {times:,.0f} times {word} than "
                       f"the model's median {kind} ({med:.4g} {unit}): "
                       f"{hint.format(v=x)}")
    return out


def _pendulum(model, omega):
    g = float(np.linalg.norm(model.gravity))
    elastic = omega[omega > 0]
    if g == 0 or not len(elastic) or not model.ropes:
        return []
    size = float(np.ptp(model.coords, axis=0).max()) if len(model.coords) else 0.0
    longest = max([size, *rope_lengths(model)]) * PENDULUM
    w_min = float(elastic.min())
    if longest <= 0 or w_min**2 * longest >= g:
        return []
    length = g / w_min**2
    return [f"the slowest mode ({w_min / (2 * np.pi):.3g} Hz) is slower than a pendulum "
            f"as long as the longest rope or the whole model ({longest:.4g} m: "
            f"{np.sqrt(g / longest) / (2 * np.pi):.3g} Hz); it swings like a pendulum "
            f"{length:.4g} m long: a stiffness far too small or a mass far too large for "
            "the geometry (EA in kN written as N? a mass in t written as kg? see the "
            "other warnings)"]
