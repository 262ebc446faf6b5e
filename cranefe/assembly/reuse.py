"""Work that depends only on a model's structure, kept for the next model that shares it
(the variants of a sweep). Nothing is kept unless a `Reuse` is passed to `assemble`.

- DOF maps (coordinates, constraints, the transform u = T q, rope and member meshes),
  under `cranefe.coordinates.dofmap.structure_key` of the model and the effects;
- null spaces of pattern matrices (the sum of unit-scaled element matrices, which has the
  null space of K without its stiffness contrasts), under a digest of the matrix itself:
  the static solution's pattern depends only on geometry and on which elements exist, so
  a sweep over stiffnesses and masses finds it once.

Both are exact reuse (the same inputs give the same objects); `cranefe study sweeps`
measures what they save.
"""

import hashlib
from collections import Counter, OrderedDict

import numpy as np


class Reuse:
    """Least-recently-used stores of DOF maps and null spaces, with hit counts."""

    def __init__(self, size=16):
        self.size = size
        self._stores = {"dofs": OrderedDict(), "null_space": OrderedDict()}
        self.hits, self.misses = Counter(), Counter()

    def clear(self):
        """Forget everything kept, and the counts."""
        self.__init__(self.size)

    def _get(self, kind, key, make):
        store = self._stores[kind]
        if key in store:
            store.move_to_end(key)
            self.hits[kind] += 1
            return store[key]
        self.misses[kind] += 1
        value = store[key] = make()
        if len(store) > self.size:
            store.popitem(last=False)
        return value

    def dofs(self, model, effects):
        """`build_dofs(model, effects)`, built once per structure."""
        from ..coordinates.dofmap import build_dofs, structure_key
        return self._get("dofs", structure_key(model, effects),
                         lambda: build_dofs(model, effects))

    def null_space(self, P):
        """`pattern.null_space` of the sparse pattern matrix P, found once per matrix."""
        from .pattern import null_space
        P = P.tocsr()
        P.sort_indices()
        h = hashlib.sha1(repr(P.shape).encode())
        for a in (P.indptr, P.indices, P.data):
            h.update(np.ascontiguousarray(a).tobytes())
        return self._get("null_space", h.hexdigest(), lambda: null_space(P.toarray()))
