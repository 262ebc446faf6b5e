"""Parameter sweeps: many variants of one model, run locally or on a Dask cluster.

spec.py (the sweep file and its variants) -> evaluate.py (one variant, in a worker) ->
engine.py (serial, processes or Dask; journal and resume) -> table.py (HDF5 table),
plots.py. Format: docs/sweeps.md.
"""
