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


def heat_maps(table, folder, prefix=""):
    """One heat map per output over the first two parameters of a grid (a panel per
    combination of the others' values; docs/sweeps.md, "Heat maps"), plus
    `OUTPUT_table.csv` laid out the same way. Returns the paths written."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from ..outpaths import make_folder, save_figure, write_text
    if len(table.parameters) < 2:
        return []
    make_folder(folder, "--plots")
    x, y = (np.unique(table.values[:, k]) for k in (0, 1))
    rest = np.unique(table.values[:, 2:], axis=0) if table.values.shape[1] > 2 else \
        np.zeros((1, 0))
    paths = []
    for q, out in enumerate(table.outputs):
        fig, axes = plt.subplots(1, len(rest), figsize=(4.6 * len(rest), 3.8),
                                 squeeze=False)
        rows = []
        for k, (ax, fixed) in enumerate(zip(axes[0], rest)):
            Z = np.full((len(y), len(x)), np.nan)
            sel = np.all(np.isclose(table.values[:, 2:], fixed), axis=1)
            for v, res in zip(table.values[sel], table.results[sel, q]):
                Z[np.searchsorted(y, v[1]), np.searchsorted(x, v[0])] = res
                rows.append([*v, res])
            im = ax.imshow(Z, origin="lower", aspect="auto", cmap="viridis")
            for i in range(len(y)):
                for j in range(len(x)):
                    if np.isfinite(Z[i, j]):
                        ax.text(j, i, f"{Z[i, j]:.3g}", ha="center", va="center",
                                fontsize=7, color="w")
            ax.set_xticks(range(len(x)), [f"{v:g}" for v in x])
            ax.set_yticks(range(len(y)), [f"{v:g}" for v in y])
            ax.set_xlabel(table.parameters[0])
            ax.set_ylabel(table.parameters[1])
            ax.set_title(", ".join(f"{p} = {v:g}" for p, v in
                                   zip(table.parameters[2:], fixed)) or out, fontsize=8)
            fig.colorbar(im, ax=ax, label=out)
        fig.suptitle(f"{table.name}: {out}")
        fig.tight_layout()
        base = os.path.join(folder, f"{prefix}{out.replace('.', '_')}_map")
        save_figure(fig, base + ".png", dpi=100)
        plt.close(fig)
        write_text(base + ".csv", ",".join([*table.parameters, out]) + "\n" + "".join(
            ",".join(f"{v:.9g}" for v in r) + "\n" for r in rows))
        paths += [base + ".png", base + ".csv"]
    return paths

