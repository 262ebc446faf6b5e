"""cranefe: dynamics of cranes and other rope systems.

The Python API (docs/api.md)::

    import cranefe
    model = cranefe.load("models/two_mass_hoist.yaml")
    result = cranefe.modes(model)          # also damping, simulate, luff, sweep
    result.frequency_hz, result.to_dict()  # the document `cranefe modes --json` prints

The pipeline, one folder per stage (docs/theory.md, "Pipeline")::

    model/ -> coordinates/ -> elements/ -> assembly/ -> statics -> system -> condense
        -> analysis/ -> outputs/ -> sweeps/ -> api -> studies/ -> cli/

The API functions are imported on first use, so ``import cranefe`` stays light.
"""

__version__ = "0.1.0"

_API = ("load", "modes", "damping", "simulate", "luff", "sweep", "loads")
__all__ = list(_API)


def __getattr__(name):
    if name in _API:
        from . import api
        return getattr(api, name)
    raise AttributeError(f"module 'cranefe' has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + list(_API))
