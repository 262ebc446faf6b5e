"""What the studies share: CSV tables and matplotlib figures written into results/, and
the measured blocks of docs/ pages they regenerate."""

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


def _markers(study, name):
    return (f"<!-- BEGIN cranefe study {study}: {name} -->",
            f"<!-- END cranefe study {study}: {name} -->")


def doc_block(text, study, name):
    """The text between a study's markers `name` on a docs page."""
    begin, end = _markers(study, name)
    return text[text.index(begin) + len(begin):text.index(end)].strip("\n")


def replace_doc_block(text, study, name, block):
    """`text` with the block between a study's markers `name` replaced by `block`."""
    begin, end = _markers(study, name)
    a, b = text.index(begin) + len(begin), text.index(end)
    return text[:a] + "\n" + block.rstrip("\n") + "\n" + text[b:]


def rewrite_doc_blocks(path, study, blocks):
    """Regenerate a docs page's measured blocks, (name, markdown) pairs, between the
    study's markers (written whole, atomically). [path], or [] when the page or one of
    its markers is missing (a checkout without docs/, a page not quoting the study)."""
    from ..outpaths import write_text
    if not os.path.exists(path):
        return []
    with open(path) as fh:
        text = fh.read()
    try:
        for name, md in blocks:
            text = replace_doc_block(text, study, name, md)
    except ValueError:
        return []
    write_text(path, text)
    return [path]
