"""Numbers for JSON documents: finite floats, None for NaN and infinity."""

import math


def num(x):
    """A finite float, or None (JSON has no NaN or infinity)."""
    x = float(x)
    return x if math.isfinite(x) else None


def timings(t):
    """Timings rounded to the microsecond, as every document reports them."""
    return {k: round(v, 6) for k, v in t.items()}
