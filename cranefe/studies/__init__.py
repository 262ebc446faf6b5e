"""Studies: what accuracy costs in time. Each module ``cranefe/studies/NAME.py`` has

``DESCRIPTION`` (one line) and ``run(outdir, quick=False) -> list[str]`` writing CSV and PNG
files into ``outdir`` (``results/`` by default) and returning their paths. Errors are
measured against exact answers; times are ratios measured in one run where possible.
"""

import pkgutil

NAMES = tuple(sorted(m.name for m in pkgutil.iter_modules(__path__)
                     if not m.name.startswith("_")))
