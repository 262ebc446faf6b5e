"""cranefe: dynamics of cranes and other rope systems.

The pipeline (see docs/theory.md)::

    YAML --model.load--> Model --dofs--> DofMap --assemble--> System (K, M, f)
         --condense--> reduced system --modal--> ModalResult --cli--> tables / JSON
"""

__version__ = "0.1.0"
