"""Spring-like elements as rows of elongation coefficients: K = R^T diag(c) R.

Massless ropes over their whole reeving (one row each), rope elements of ropes with mass,
truss members, axial and rotational springs (Heletiy 2016, eq. 5:
C_ij = sum_m C_m r_mi r_mj). Rows are in primitive coordinates (`coordinates.Layout`).
"""

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..coordinates.ropes import endpoint_maps, rope_rows
from ..elements import elongation_rows, span_geometry
from ..model import GROUND
from .coo import coo
from .materials import element_materials, element_sections


@dataclass(frozen=True)
class SpringRows:
    """All spring-like elements: K = R^T diag(c) R (primitive coordinates)."""

    R: sp.csr_matrix          # (ne, n_primitive) elongation rows
    c: np.ndarray             # (ne,) stiffness of each row
    psi: np.ndarray           # (ne,) absorption coefficient
    names: tuple              # (ne,) "rope hoist", "spring tower_bend", ...
    length: np.ndarray        # (ne,) deformable length (ropes, axial springs), else nan
    rope: np.ndarray          # (ne,) index of the rope a row belongs to, else -1
    spring: np.ndarray        # (ne,) index of the spring a row is, else -1
    member: np.ndarray        # (ne,) index of the truss member element a row is, else -1


@dataclass
class _Part:
    """Rows of one kind of element, concatenated by `spring_rows`."""

    R: sp.csr_matrix
    c: object                 # list or array (ne,), as the others
    psi: object
    names: object
    length: object
    rope: object
    spring: object
    member: object


def all_coords(model, layout, mm):
    """Coordinates of model nodes, then interior rope nodes, then member nodes."""
    n_mem = mm.n_interior if mm is not None else 0
    out = np.full((layout.n_nodes, 3), np.nan)
    out[:len(model.coords)] = model.coords
    if n_mem:
        out[layout.n_nodes - n_mem:] = mm.coords
    return out


def member_geometry(model, layout, mm, which):
    """Unit vectors and lengths of member elements `which`."""
    coords = all_coords(model, layout, mm)
    return span_geometry(coords, mm.node[which, 0], mm.node[which, 1])


def _massless_ropes(model, layout, massless):
    R, L = rope_rows(model, layout, massless)
    return _Part(R, [model.ropes[k].EA / l for k, l in zip(massless, L)],
                 [model.ropes[k].psi for k in massless],
                 [f"rope {model.ropes[k].name}" for k in massless], list(L), list(massless),
                 [-1] * len(massless), [-1] * len(massless))


def _rope_elements(model, layout, rm):
    """One row per element of ropes with mass: e . (u_end - u_start), EA / l_e."""
    dofs, B = endpoint_maps(rm, layout)
    EA, _ = element_materials(model, rm)
    v = np.einsum("ki,kij->kj", rm.e, B[:, 3:] - B[:, :3])
    ne = len(rm.length)
    R = coo([np.repeat(np.arange(ne), 8)], [dofs.ravel()], [v.ravel()], (ne, layout.size))
    psi = np.array([r.psi for r in model.ropes], dtype=float)
    names = np.array([f"rope {r.name}" for r in model.ropes], dtype=object)
    minus = np.full(ne, -1)
    return _Part(R, EA / rm.length, psi[rm.rope], names[rm.rope], rm.length, rm.rope, minus,
                 minus)


def _trusses(model, layout, mm):
    """One row per truss element, EA / l."""
    sec = element_sections(model, mm)
    t = np.flatnonzero(~mm.beam)
    e, l = member_geometry(model, layout, mm, t)
    cc, v = elongation_rows(e, np.ones(len(t)), layout.node(mm.node[t, 0]),
                            layout.node(mm.node[t, 1]))
    R = _rows_csr(cc, v, layout.size)
    names = np.array([f"member {m.name}" for m in model.members], dtype=object)
    minus = np.full(len(t), -1)
    return _Part(R, sec.E[t] * sec.A[t] / l, sec.psi[t], names[mm.member[t]], l, minus,
                 minus, t)


def _rows_csr(cols, vals, size):
    """CSR (ne, size) with row k holding vals[k] at the distinct columns cols[k] (ne, m):
    built directly (indptr every m entries), with no COO step."""
    ne, m = cols.shape
    order = np.argsort(cols, axis=1, kind="stable")
    return sp.csr_matrix((np.take_along_axis(vals, order, axis=1).ravel(),
                          np.take_along_axis(cols, order, axis=1).ravel(),
                          np.arange(0, m * ne + 1, m)), shape=(ne, size))


def _springs(model, layout):
    """Axial springs (elongation of a span) and rotational springs (relative rotation
    about their axis)."""
    rows, cols, vals, lengths = [], [], [], []
    for k, s in enumerate(model.springs):
        if s.type == "axial":
            e, l = span_geometry(model.coords, np.array(s.nodes[:1]), np.array(s.nodes[1:]))
            cc, v = elongation_rows(e, np.ones(1), layout.node([s.nodes[0]]),
                                    layout.node([s.nodes[1]]))
            rows.append(np.full(6, k))
            cols.append(cc[0])
            vals.append(v[0])
            lengths.append(float(l[0]))
        else:
            for sign, b in ((-1.0, s.bodies[0]), (1.0, s.bodies[1])):
                if b != GROUND:
                    rows.append(np.full(3, k))
                    cols.append(layout.body(b)[3:])
                    vals.append(sign * s.axis)
            lengths.append(np.nan)
    ns = len(model.springs)
    return _Part(coo(rows, cols, vals, (ns, layout.size)),
                 [s.stiffness for s in model.springs], [s.psi for s in model.springs],
                 [f"spring {s.name}" for s in model.springs], lengths, [-1] * ns,
                 list(range(ns)), [-1] * ns)


def spring_rows(model, layout, ropes_fe=None, members=None):
    """Rows of ropes, truss members, axial and rotational springs, with stiffness and psi.

    A massless rope is one row over its whole reeving (stiffness EA / L); a rope with
    mass (`ropes_fe`, a RopeMesh) contributes one row per element (EA / l_e).
    """
    fe = set(ropes_fe.ropes) if ropes_fe is not None else set()
    parts = [_massless_ropes(model, layout, [k for k in range(len(model.ropes))
                                             if k not in fe])]
    if fe:
        parts.append(_rope_elements(model, layout, ropes_fe))
    if members is not None and (~members.beam).any():
        parts.append(_trusses(model, layout, members))
    parts.append(_springs(model, layout))

    def cat(name, dtype=float):
        return np.concatenate([np.asarray(getattr(p, name), dtype=dtype).reshape(-1)
                               for p in parts])

    return SpringRows(sp.vstack([p.R for p in parts]).tocsr(), cat("c"), cat("psi"),
                      tuple(cat("names", object)), cat("length"), cat("rope", int),
                      cat("spring", int), cat("member", int))
