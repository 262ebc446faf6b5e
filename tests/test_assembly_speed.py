"""The fast paths of loading and assembly (issue 14) give what the per-element paths gave:
member pairs read in C-speed passes keep their messages, truss rows built straight into
CSR equal the COO assembly, and the floor script assembles cranefe's matrices."""

import numpy as np
import pytest
import scipy.sparse as sp

from cranefe.assembly.springs import _rows_csr
from cranefe.errors import ModelError
from cranefe.model.generate import panels_for, to_yaml, tower_crane
from cranefe.model import load
from cranefe.studies import _floor
from cranefe.system import assemble

TRUSS = """
cranefe: 1
nodes: {{A: [0, 0, 0], B: [4, 0, 0], C: [2, 0, 3], D: [2, 3, 0]}}
ground: [A, B, D]
masses: {{C: 100}}
members:
  bars: {{type: truss, pairs: {pairs}, E: 2.1e11, A: 1.0e-3, rho: 7850}}
effects: {{structure: flexible}}
"""


@pytest.mark.parametrize("pairs, entry, words", [
    ("[[A, C], [B, C, D]]", "members.bars.pairs[1]", "must be a pair"),
    ("[[A, C], B]", "members.bars.pairs[1]", "must be a pair"),
    ("[[A, C], [B, X]]", "members.bars.pairs[1][1]", "unknown node 'X'"),
    ("[[A, C], [C, C]]", "members.bars.pairs[1]", "zero-length element"),
])
def test_member_pairs_keep_their_messages(model_from, pairs, entry, words):
    with pytest.raises(ModelError) as err:
        model_from(TRUSS.format(pairs=pairs))
    assert entry in str(err.value) and words in str(err.value)


def test_member_pairs_are_the_named_nodes(model_from):
    m = model_from(TRUSS.format(pairs="[[A, C], [C, B], [D, C]]"))
    idx = {n: i for i, n in enumerate(m.node_names)}
    expect = [[idx["A"], idx["C"]], [idx["C"], idx["B"]], [idx["D"], idx["C"]]]
    np.testing.assert_array_equal(m.members[0].pairs, expect)


def test_rows_built_as_csr_equal_the_coo_assembly():
    rng = np.random.default_rng(1)
    cols = np.array([rng.choice(40, 6, replace=False) for _ in range(25)])
    vals = rng.standard_normal(cols.shape)
    R = _rows_csr(cols, vals, 40)
    ref = sp.coo_matrix((vals.ravel(), (np.repeat(np.arange(25), 6), cols.ravel())),
                        shape=(25, 40)).tocsr()
    assert R.has_sorted_indices and (R != ref).nnz == 0      # same entries, exactly


def test_floor_assembles_the_same_matrices(tmp_path):
    # the study's assembly ratio compares like with like: cranefe's K and M on the
    # floor's coordinates (node translations less ground and the load's sideways motion)
    yml = to_yaml(tower_crane(panels=panels_for(600)), str(tmp_path / "c.yaml"))
    s = assemble(load(yml))
    K, M = _floor.assemble(_floor.read(yml))
    names = list(_floor.read(yml)["nodes"])
    free = [f"node {n} {a}" for n in names for a in "xyz"]
    order = [s.dofs.labels.index(lab) for lab in free if lab in s.dofs.labels]
    assert len(order) == K.shape[0] == s.K.shape[0]
    Kc, Mc = s.K[order][:, order], s.M[order][:, order]
    # summation order differs: round-off of the largest entries (1e-13 relative)
    assert abs(Kc - K).max() <= 1e-13 * abs(K).max()
    assert abs(Mc - M).max() <= 1e-13 * abs(M).max()
