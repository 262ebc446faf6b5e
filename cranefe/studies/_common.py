"""What the studies share: CSV tables and matplotlib figures written into results/."""

import csv
import os


def write_csv(outdir, name, rows, keys=None):
    """rows: dicts; floats written with 6 significant digits. Returns the path."""
    keys = keys or list(rows[0])
    path = os.path.join(outdir, name)
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{r[k]:.6g}" if isinstance(r[k], float) else r[k])
                        for k in keys})
    return path


def pyplot():
    """matplotlib.pyplot on the off-screen Agg back end (imported only by studies)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def save(fig, outdir, name):
    """Lay out, write as PNG into outdir and close; returns the path."""
    import matplotlib.pyplot as plt
    fig.tight_layout()
    path = os.path.join(outdir, name)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
