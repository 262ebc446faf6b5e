"""Plots of a sweep's outputs against its parameters (PNG)."""

import os

import numpy as np


def plot_table(table, folder):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from ..outpaths import make_folder, save_figure
    make_folder(folder, "--plots")
    ok = np.array([s == "ok" for s in table.status])
    paths = []
    for q, out in enumerate(table.outputs):
        n = len(table.parameters)
        fig, axes = plt.subplots(1, n, figsize=(4.2 * n, 3.6), squeeze=False)
        for p, ax in enumerate(axes[0]):
            c = table.values[ok, (p + 1) % n] if n > 1 else None
            sc = ax.scatter(table.values[ok, p], table.results[ok, q], c=c, s=14,
                            cmap="viridis")
            ax.set_xlabel(table.parameters[p])
            ax.set_ylabel(out)
            ax.grid(alpha=0.3)
            if n > 1:
                fig.colorbar(sc, ax=ax, label=table.parameters[(p + 1) % n])
        fig.suptitle(f"{table.name}: {out}")
        fig.tight_layout()
        path = os.path.join(folder, f"{out.replace('.', '_')}.png")
        save_figure(fig, path, dpi=100)
        plt.close(fig)
        paths.append(path)
    return paths
