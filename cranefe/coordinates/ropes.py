"""Finite-element ropes (effect ``rope_mass: N``): each fall of a rope with mass becomes N
two-node elements; the rope runs over frictionless sheaves and onto drums.

Kinematics (docs/theory.md, "Ropes with mass"): the rope material at an end of a fall
sits on the sheave (or drum, or anchor) at node P and moves with it, plus along the fall
direction e by the rope that has run over the sheave:

    u_material = u(P) + xi e

xi is a *slip coordinate* for a sheave pass (rope run over it in the path direction), is
-R theta at a drum at the path's start (hauling in pulls material back into the drum)
and +R theta at a drum at its end, and 0 at a dead end. Interior nodes of a fall are
ordinary translational nodes (only along the fall when sway is off).
"""

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..elements import rope_force


@dataclass(frozen=True)
class RopeMesh:
    """The discretisation of the ropes that carry mass."""

    ropes: tuple              # indices of discretised ropes in model.ropes
    coords: np.ndarray        # (ni, 3) interior nodes
    names: tuple              # (ni,)
    direction: np.ndarray     # (ni, 3) fall direction at each interior node
    slip_names: tuple         # (ns,) "rope hoist over S (pass 2)"
    # elements (ne,)
    rope: np.ndarray
    fall: np.ndarray          # fall number within its rope
    node: np.ndarray          # (ne, 2) expanded node index of each end (model nodes first)
    slip: np.ndarray          # (ne, 2) slip index, or -1
    drum: np.ndarray          # (ne, 2) drum index, or -1
    coef: np.ndarray          # (ne, 2) xi = coef * (slip or drum rotation)
    e: np.ndarray             # (ne, 3) element direction (that of its fall)
    length: np.ndarray        # (ne,)

    @property
    def n_interior(self):
        return len(self.coords)

    @property
    def n_slips(self):
        return len(self.slip_names)


def falls_of(rope):
    """Expanded falls (a, b) in path order: a tackle of n falls alternates P->X, X->P."""
    out = []
    for a, b, n in zip(rope.span_a, rope.span_b, rope.falls):
        for k in range(n):
            out.append((a, b) if k % 2 == 0 else (b, a))
    return out


def discretize(model, n_elements, include_massless=False):
    """RopeMesh with n_elements per fall for every rope with mass (or all ropes)."""
    nn = len(model.node_names)
    drum_names = {d.name: i for i, d in enumerate(model.drums)}
    coords, names, direction, slip_names = [], [], [], []
    el = {k: [] for k in ("rope", "fall", "node", "slip", "drum", "coef", "e", "length")}
    chosen = []
    for ri, rope in enumerate(model.ropes):
        if rope.mass_per_length <= 0 and not include_massless:
            continue
        chosen.append(ri)
        falls = falls_of(rope)
        first_drum = drum_names.get(rope.points[0], -1)
        last_drum = drum_names.get(rope.points[-1], -1)
        # slip of the material at each path point: index into slips, drum, coefficient
        point_slip = []
        for k in range(len(falls) + 1):
            if k == 0:
                point_slip.append((-1, first_drum, -model.drums[first_drum].radius
                                   if first_drum >= 0 else 0.0))
            elif k == len(falls):
                point_slip.append((-1, last_drum, model.drums[last_drum].radius
                                   if last_drum >= 0 else 0.0))
            else:
                point_slip.append((len(slip_names), -1, 1.0))
                slip_names.append(f"slip {rope.name} over "
                                  f"{model.node_names[falls[k][0]]} (pass {k})")
        extra = None
        if rope.extra_length > 0:
            # rope not in the spans (e.g. on the drum): a massless element of that length
            # between the rope's end (drum or anchor) and a slip coordinate where the
            # first (or, with the drum at the far end, last) fall begins
            at_end = last_drum >= 0 and first_drum < 0
            k = len(falls) if at_end else 0
            end_slip = point_slip[k]
            point_slip[k] = (len(slip_names), -1, 1.0)
            slip_names.append(f"slip {rope.name} (extra length)")
            f_dir = falls[-1] if at_end else falls[0]
            e = model.coords[f_dir[1]] - model.coords[f_dir[0]]
            ends = (point_slip[k], end_slip) if at_end else (end_slip, point_slip[k])
            node = f_dir[1] if at_end else f_dir[0]
            extra = (node, ends, e / np.linalg.norm(e))
        if extra is not None:
            node, (s0, s1), e = extra
            for key, val in (("rope", ri), ("fall", -1), ("node", (node, node)),
                             ("slip", (s0[0], s1[0])), ("drum", (s0[1], s1[1])),
                             ("coef", (s0[2], s1[2])), ("e", e),
                             ("length", rope.extra_length)):
                el[key].append(val)
        for f, (a, b) in enumerate(falls):
            pa, pb = model.coords[a], model.coords[b]
            e = (pb - pa) / np.linalg.norm(pb - pa)
            chain = [a]
            for j in range(1, n_elements):
                chain.append(nn + len(coords))
                coords.append(pa + (pb - pa) * j / n_elements)
                names.append(f"{rope.name} fall {f + 1} node {j}")
                direction.append(e)
            chain.append(b)
            le = np.linalg.norm(pb - pa) / n_elements
            for j in range(n_elements):
                s0 = point_slip[f] if j == 0 else (-1, -1, 0.0)
                s1 = point_slip[f + 1] if j == n_elements - 1 else (-1, -1, 0.0)
                el["rope"].append(ri)
                el["fall"].append(f)
                el["node"].append((chain[j], chain[j + 1]))
                el["slip"].append((s0[0], s1[0]))
                el["drum"].append((s0[1], s1[1]))
                el["coef"].append((s0[2], s1[2]))
                el["e"].append(e)
                el["length"].append(le)
    arr = {k: np.array(v, dtype=int if k in ("rope", "fall", "node", "slip", "drum")
                       else float) for k, v in el.items()}
    arr["node"] = arr["node"].reshape(-1, 2)
    for k in ("slip", "drum", "coef"):
        arr[k] = arr[k].reshape(-1, 2)
    arr["e"] = arr["e"].reshape(-1, 3)
    return RopeMesh(tuple(chosen), np.array(coords, dtype=float).reshape(-1, 3),
                    tuple(names), np.array(direction, dtype=float).reshape(-1, 3),
                    tuple(slip_names), **arr)


def endpoint_maps(rm, layout):
    """Element end displacements in primitive coordinates.

    Returns (dofs (ne, 8), B (ne, 6, 8)): [u_start; u_end] = B @ u[dofs], where each end
    is u(node) + coef * xi * e (xi a slip coordinate or a drum rotation). Unused slots
    point at dof 0 with zero coefficients.
    """
    ne = len(rm.length)
    dofs = np.zeros((ne, 8), dtype=int)
    B = np.zeros((ne, 6, 8))
    for end in (0, 1):
        dofs[:, 4 * end:4 * end + 3] = layout.node(rm.node[:, end])
        B[:, 3 * end:3 * end + 3, 4 * end:4 * end + 3] = np.eye(3)
        slip, drum = rm.slip[:, end], rm.drum[:, end]
        xi = np.where(slip >= 0, layout.slip(np.maximum(slip, 0)),
                      np.where(drum >= 0, layout.drum(np.maximum(drum, 0)), 0))
        dofs[:, 4 * end + 3] = xi
        coef = np.where((slip >= 0) | (drum >= 0), rm.coef[:, end], 0.0)
        B[:, 3 * end:3 * end + 3, 4 * end + 3] = coef[:, None] * rm.e
    return dofs, B


def rope_rows(model, layout, which=None, coords=None):
    """Massless ropes: one elongation row per rope over its whole path (seed eq. 2-3).

    Returns (R (len(which), n_primitive), deformable lengths L): rows for the ropes
    `which` (default all) at the positions `coords` (default: the model's reference
    geometry). A drum at an end hauls in ``radius * rotation``, which stretches the rope:
    coefficient +radius on the drum's rotation.
    """
    which = list(range(len(model.ropes)) if which is None else which)
    coords = model.coords if coords is None else coords
    ropes = [model.ropes[k] for k in which]
    if not ropes:
        return sp.csr_matrix((0, layout.size)), np.zeros(0)
    a = np.concatenate([r.span_a for r in ropes])
    b = np.concatenate([r.span_b for r in ropes])
    falls = np.concatenate([r.falls for r in ropes])
    rope = np.repeat(np.arange(len(ropes)), [len(r.falls) for r in ropes])
    extra = np.array([r.extra_length for r in ropes])
    state = rope_force(coords, a, b, falls, rope, np.zeros(len(ropes)), np.ones(len(ropes)),
                       extra)
    rows = [np.repeat(rope, 6)]
    cols = [np.hstack([layout.node(a), layout.node(b)]).ravel()]
    vals = [state.grad.ravel()]
    for k, r in enumerate(ropes):
        for d in r.end_drums:
            rows.append([k])
            cols.append([layout.drum(d)])
            vals.append([model.drums[d].radius])
    R = sp.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(len(ropes), layout.size)).tocsr()
    return R, state.L
