"""Joints, linear drives and inextensible ropes as linear constraints G q_map = 0, and
their master-slave elimination T_c (docs/theory.md, "Coordinates")."""

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from ..elements import elongation_rows, skew, span_geometry
from ..errors import ModelError
from ..model import GROUND
from .ropes import rope_rows


@dataclass(frozen=True)
class ConstraintRows:
    """Rows of G (in q_map) of one constraint, with how its reaction acts on points."""

    name: str
    owner: tuple              # ("joint" | "drive" | "rope" | "support", index in the model)
    rows: np.ndarray          # (k, n_map) dense
    groups: tuple             # (g1, g2) rigid groups a joint connects, else ()
    point: np.ndarray         # (3,) point where the reaction acts (joints), or None
    directions: np.ndarray    # (k, 3) force direction of each row at the point (joint
                              # translations) or zeros (rotations, ropes, drives)


def _constraint_rows(model, effects, layout, T_map, group_of_body, group_q, group_ref,
                     comps):
    out = []
    n_map = T_map.shape[1]

    def point_rows(g, p):
        """(3, n_map): translation of point p carried by group g."""
        m = np.zeros((3, n_map))
        if g == GROUND:
            return m
        c = p - group_ref[g]
        block = np.hstack([np.eye(3), -skew(c)])
        for k in comps:
            m[:, group_q[g, k]] += block[:, k]
        return m

    def rot_rows(g):
        m = np.zeros((3, n_map))
        if g != GROUND:
            for k in (3, 4, 5):
                if group_q[g, k] >= 0:
                    m[k - 3, group_q[g, k]] = 1.0
        return m

    for k, j in enumerate(model.joints):
        if j.type == "fixed":
            continue
        g1, g2 = (GROUND if b == GROUND else group_of_body[b] for b in j.bodies)
        if g1 == g2:
            continue                      # both in one rigid group: nothing to constrain
        p = model.coords[j.at]
        trans = point_rows(g1, p) - point_rows(g2, p)
        rot = rot_rows(g1) - rot_rows(g2)
        if j.type == "slider":
            tdirs = _perp(j.axis)
            rdirs = np.eye(3)
        else:
            tdirs = np.eye(3)
            rdirs = _perp(j.axis) if j.type == "hinge" else np.zeros((0, 3))
        rows = np.vstack([tdirs @ trans, rdirs @ rot])
        dirs = np.vstack([tdirs, np.zeros((len(rdirs), 3))])
        out.append(ConstraintRows(f"{j.type} joint at {model.node_names[j.at]}",
                                  ("joint", k), rows, (g1, g2), p, dirs))

    out += _support_rows(model, layout, T_map)
    for k, d in enumerate(model.linear_drives):
        a, c = d.nodes
        e, _ = span_geometry(model.coords, np.array([a]), np.array([c]))
        cols, vals = elongation_rows(e, np.ones(1), layout.node([a]), layout.node([c]))
        row = np.zeros(layout.size)
        np.add.at(row, cols[0], vals[0])
        out.append(ConstraintRows(f"linear drive {d.name}", ("drive", k),
                                  (row @ T_map)[None], (), None, np.zeros((1, 3))))
    if not effects.rope_elasticity:
        if effects.rope_mass > 0:
            raise ModelError("inextensible ropes (rope_elasticity: false) cannot carry "
                             "rope mass elements; set rope_mass: 0", model.file,
                             "effects.rope_elasticity")
        R, _ = rope_rows(model, layout)
        RT = (R @ T_map).toarray()
        for k, r in enumerate(model.ropes):
            out.append(ConstraintRows(f"rope {r.name} (inextensible)", ("rope", k),
                                      RT[k:k + 1], (), None, np.zeros((1, 3))))
    return out


def _support_rows(model, layout, T_map):
    """Supports: the displacement of the node along each restrained direction d and its
    rotation about each restrained axis, d . u = 0. A direction in which the node has no
    coordinate (the plane's normal; a rotation where no beam meets) gives a zero row,
    which the elimination drops."""
    out = []
    for k, s in enumerate(model.supports):
        rows = np.vstack([s.translations @ T_map[layout.node(s.node)].toarray(),
                          s.rotations @ T_map[layout.rot(s.node)].toarray()])
        dirs = np.vstack([s.translations, np.zeros((len(s.rotations), 3))])
        out.append(ConstraintRows(f"support at {model.node_names[s.node]}", ("support", k),
                                  rows, (), model.coords[s.node], dirs))
    return out


def _perp(axis):
    """(2, 3) orthonormal directions perpendicular to a unit axis."""
    _, _, vt = np.linalg.svd(axis[None])
    return vt[1:]


def _eliminate(constraints, n_map, rotation, length_scale):
    """Master-slave elimination of G q_map = 0 -> (T_c (n_map, n), kept master indices)."""
    if not constraints:
        return sp.identity(n_map, format="csr"), np.arange(n_map)
    G = np.vstack([c.rows for c in constraints])
    involved = np.flatnonzero(np.abs(G).sum(axis=0) > 0)
    if len(involved) == 0:
        return sp.identity(n_map, format="csr"), np.arange(n_map)
    GJ = G[:, involved]
    # rotations in length units (theta * model size) so pivoting compares like with like
    scale = np.where(rotation[involved], 1.0 / length_scale, 1.0)   # theta = x~ / L
    # translations are preferred as slaves, so joint rotations stay as the coordinates
    # (a hinge is described by its angle); the rank decision is unaffected by the weight
    prefer = np.where(rotation[involved], 1.0, 10.0)
    Q, R, piv = sla.qr(GJ * scale * prefer, pivoting=True, mode="economic")
    diag = np.abs(np.diag(R))
    rank = int(np.sum(diag > 1e-10 * diag[0])) if len(diag) else 0
    slaves, masters = piv[:rank], piv[rank:]
    # in scaled unknowns x~ = x / scale: R11 x~_s + R12 x~_m = 0
    W = -sla.solve_triangular(R[:rank, :rank], R[:rank, rank:])
    w = scale * prefer
    W = W * w[slaves][:, None] / w[masters][None, :]
    slave_global = involved[slaves]
    keep = np.setdiff1d(np.arange(n_map), slave_global)
    col_of = {q: k for k, q in enumerate(keep)}
    rows = list(keep)
    cols = list(range(len(keep)))
    vals = [1.0] * len(keep)
    for si, s in enumerate(slave_global):
        for mi, m in enumerate(involved[masters]):
            if W[si, mi] != 0:
                rows.append(s)
                cols.append(col_of[m])
                vals.append(W[si, mi])
    T_c = sp.coo_matrix((vals, (rows, cols)), shape=(n_map, len(keep))).tocsr()
    return T_c, keep
