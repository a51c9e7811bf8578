"""Meshes as arrays and as meshio.Mesh objects: what neomesh optimizes (cells of the mesh's
dimension) goes to the C++ Mesh; what it never changes (lower-dimensional cells such as
boundary lines, point and cell data, cell sets, a 2D mesh's z) is kept beside it in Python, in
the same numbering, and comes back out of to_meshio()."""

from __future__ import annotations

import numpy as np

from . import _neomesh

# meshio's names of the cell types neomesh optimizes, in the order of neomesh::CellType;
# first-order cells list their vertices in the same order in meshio and in Gmsh.
_TYPES = ["triangle", "quad", "tetra", "hexahedron", "wedge", "pyramid"]
_DIM = {"triangle": 2, "quad": 2, "tetra": 3, "hexahedron": 3, "wedge": 3, "pyramid": 3}
_VERTICES = {"triangle": 3, "quad": 4, "tetra": 4, "hexahedron": 8, "wedge": 6, "pyramid": 5}
# Other meshio types and their dimension: kept unchanged, never optimized.
_LOWER = {"vertex": 0, "line": 1, "line3": 1, "triangle": 2, "quad": 2}


def _blocks(cells):
    """meshio's cells (a dict, a list of (type, array) or of CellBlocks) as [(type, array)]."""
    if isinstance(cells, dict):
        cells = list(cells.items())
    out = []
    for block in cells:
        if hasattr(block, "type") and hasattr(block, "data"):
            cell_type, data = block.type, block.data
        else:
            cell_type, data = block
        out.append((str(cell_type), np.asarray(data)))
    return out


def from_arrays(points, cells, comm=None, name="mesh from arrays", allow_inverted=True,
                _extra=None):
    """A Mesh from meshio-style arrays: `points` (n × 2 or 3), `cells` a dict {type: array} or a
    list of (type, array) with meshio's type names (triangle, quad, tetra, hexahedron, wedge,
    pyramid; types may be mixed). Cells of a lower dimension (boundary lines, faces, vertices)
    are kept for to_meshio(), not optimized. A vertex's number is its row in `points`; under
    MPI the first process' arrays are distributed (the others' are ignored)."""
    points = np.asarray(points, dtype=float)
    if points.ndim != 2 or points.shape[1] not in (2, 3):
        raise _neomesh.Error(f"points: expected an n × 2 or n × 3 array (got shape {points.shape})")
    blocks = _blocks(cells)
    dims = {_DIM[t] for t, _ in blocks if t in _DIM}
    if not dims:
        raise _neomesh.Error(
            "cells: no cells neomesh optimizes (" + ", ".join(_TYPES) + ")"
            + (f"; got {', '.join(sorted({t for t, _ in blocks}))}" if blocks else ""))
    dim = max(dims)
    if dim > points.shape[1]:
        raise _neomesh.Error(f"points: {dim}D cells need {dim} coordinates per point")
    kept = []
    for t, data in blocks:
        if t in _DIM and _DIM[t] == dim:
            if data.ndim != 2 or data.shape[1] != _VERTICES[t]:
                raise _neomesh.Error(
                    f"cells: '{t}' cells need {_VERTICES[t]} vertices each (got shape {data.shape})")
            kept.append(True)
        elif _LOWER.get(t, 99) < dim:
            kept.append(False)
        else:
            raise _neomesh.Error(f"cells: neomesh does not optimize '{t}' cells")
    # 2D cells with 3 coordinates: in a plane z = constant, a 2D mesh whose z comes back in
    # to_meshio(); otherwise a surface mesh, which keeps its 3 coordinates.
    z, columns = None, dim
    if dim == 2 and points.shape[1] == 3:
        z = points[:, 2]
        if len(z) and np.ptp(z) > 1e-12 * max(1.0, np.abs(points).max()):
            z, columns = None, 3
    flat = [data.astype(np.int64).ravel() for (t, data), k in zip(blocks, kept) if k]
    types = [np.full(len(data), _TYPES.index(t), dtype=np.uint8)
             for (t, data), k in zip(blocks, kept) if k]
    mesh = _neomesh.Mesh._from_arrays(
        np.ascontiguousarray(points[:, :columns]), np.concatenate(flat), np.concatenate(types), comm,
        name, allow_inverted)
    extra = {"columns": points.shape[1], "z": None if z is None else z.copy(),
             "blocks": [(t, None if k else data.copy(), len(data))
                        for (t, data), k in zip(blocks, kept)]}
    extra.update(_extra or {})
    mesh._meshio = extra
    return mesh


def from_meshio(m, comm=None, allow_inverted=True):
    """A Mesh from a meshio.Mesh: its cells as from_arrays takes them; its point data, cell
    data, cell sets and field data come back unchanged from to_meshio()."""
    extra = {
        "point_data": {k: np.asarray(v).copy() for k, v in m.point_data.items()},
        "cell_data": {k: [np.asarray(a).copy() for a in v] for k, v in m.cell_data.items()},
        "cell_sets": {k: [None if a is None else np.asarray(a).copy() for a in v]
                      for k, v in m.cell_sets.items()},
        "field_data": dict(m.field_data),
    }
    return from_arrays(m.points, m.cells, comm=comm, name="mesh from meshio",
                       allow_inverted=allow_inverted, _extra=extra)


def _runs(types):
    """Consecutive runs of one cell type: [(type index, start, end)]."""
    if len(types) == 0:
        return []
    edges = np.flatnonzero(np.diff(types)) + 1
    starts = np.concatenate([[0], edges])
    ends = np.concatenate([edges, [len(types)]])
    return [(int(types[s]), int(s), int(e)) for s, e in zip(starts, ends)]


def _cell_blocks(flat, types):
    offsets = np.concatenate([[0], np.cumsum([_VERTICES[_TYPES[t]] for t in types])])
    blocks = []
    for t, s, e in _runs(types):
        n = _VERTICES[_TYPES[t]]
        blocks.append((_TYPES[t], flat[offsets[s]:offsets[e]].reshape(e - s, n)))
    return blocks


def cells(mesh):
    """The cells by number as meshio lists them: [(type name, (n, vertices) array)], one entry
    per run of cells of one type (collective; every process gets the whole list)."""
    _, flat, types = mesh._arrays()
    return _cell_blocks(flat, types)


def to_meshio(mesh):
    """The mesh at its current coordinates as a meshio.Mesh, with what from_meshio/from_arrays
    kept (lower-dimensional cells, point and cell data, cell sets, z of a 2D mesh) unchanged
    (collective; every process gets the whole mesh)."""
    import meshio

    points, flat, types = mesh._arrays()
    optimized = _cell_blocks(flat, types)
    extra = getattr(mesh, "_meshio", None)
    if extra is None:
        return _file_mesh(meshio, mesh, points, flat, types)
    if extra["columns"] == 3 and points.shape[1] == 2:
        z = extra["z"] if extra["z"] is not None else np.zeros(len(points))
        points = np.column_stack([points, z])
    # The blocks in their input order: the optimized ones take their cells in turn.
    offsets = np.concatenate([[0], np.cumsum([_VERTICES[_TYPES[t]] for t in types])])
    out, start = [], 0
    for t, data, count in extra["blocks"]:
        if data is None:
            n = _VERTICES[t]
            out.append((t, flat[offsets[start]:offsets[start + count]].reshape(count, n)))
            start += count
        else:
            out.append((t, data))
    return meshio.Mesh(points, out, point_data=extra.get("point_data"),
                       cell_data=extra.get("cell_data"), cell_sets=extra.get("cell_sets"),
                       field_data=extra.get("field_data"))


# meshio's names of the facets and single vertices in groups, by their number of vertices.
_ENTITIES = {1: "vertex", 2: "line", 3: "triangle", 4: "quad"}
_TYPE_DIM = {"vertex": 0, "line": 1, **_DIM}


def _file_mesh(meshio, mesh, points, flat, types):
    """A mesh read from a file as meshio has it: the cells, then the facets and vertices in
    groups; the groups as cell sets (and as Gmsh's physical tags with field data, which
    meshio's Gmsh writer needs); the file's point and cell data."""
    data = mesh._file_data()
    offsets = np.concatenate([[0], np.cumsum([_VERTICES[_TYPES[t]] for t in types])])
    runs = _runs(types)
    blocks = [(_TYPES[t], flat[offsets[s]:offsets[e]].reshape(e - s, -1)) for t, s, e in runs]
    tags = [data["cell_tags"][s:e] for _, s, e in runs]
    starts, ends = data["entity_offsets"][:-1], data["entity_offsets"][1:]
    kinds = {}
    for k, (s, e) in enumerate(zip(starts, ends)):
        kinds.setdefault(int(e - s), []).append(k)
    for n, entities in sorted(kinds.items(), reverse=True):
        vertices = np.stack([data["entity_vertices"][starts[k]:ends[k]] for k in entities])
        blocks.append((_ENTITIES[n], vertices))
        tags.append(data["entity_tags"][entities])
    cell_sets = {}
    field_data = {}
    for dim, tag, name in data["groups"]:
        cell_sets[name] = [np.flatnonzero(t == tag) if _TYPE_DIM[b] == dim
                           else np.array([], dtype=int) for (b, _), t in zip(blocks, tags)]
        field_data[name] = np.array([tag, dim])
    cell_data = {"gmsh:physical": [np.asarray(t) for t in tags]} if data["groups"] else {}
    for name, values in data["cell_data"].items():
        per_cell = [values[s:e] for _, s, e in runs]
        for _, vertices in blocks[len(runs):]:  # the file's cell data do not cover facets
            per_cell.append(np.full((len(vertices), *values.shape[1:]), np.nan))
        cell_data[name] = per_cell
    return meshio.Mesh(points, blocks, point_data=dict(data["point_data"]),
                       cell_data=cell_data, cell_sets=cell_sets, field_data=field_data)
