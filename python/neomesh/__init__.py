"""neomesh: move a mesh's vertices so that its cells become well shaped and correctly sized.

    >>> import neomesh
    >>> mesh = neomesh.Mesh.read("plate.msh")
    >>> result = neomesh.smooth(mesh, boundary="fixed")   # moves mesh's vertices in place
    >>> result.quality_after["metrics"]["scaled_jacobian"]["min"]

The options of smooth() and adapt() are the command line's (``--feature-angle`` is
``feature_angle=``, ``--no-guard`` is ``no_guard=True``); help(neomesh.smooth) lists them.
Every failure raises neomesh.Error (a bad option: neomesh.OptionError) with neomesh's one-line
message. docs/python.md has the whole tour.
"""

from __future__ import annotations

import json as _json
import re as _re
import textwrap as _textwrap

# petsc4py and mpi4py first where installed: they own the initialization of PETSc and MPI.
try:
    from petsc4py import PETSc as _PETSc  # noqa: F401
except ImportError:  # pragma: no cover - neomesh then initializes PETSc itself
    pass

from . import _neomesh
from ._neomesh import Error, LevelSet, Mesh, OptionError, SizeField, __version__
from ._meshio import from_arrays as _from_arrays
from ._meshio import from_meshio as _from_meshio
from ._meshio import to_meshio as _to_meshio
from ._meshio import cells as _cells

__all__ = [
    "Error",
    "LevelSet",
    "Mesh",
    "OptionError",
    "Optimizer",
    "Result",
    "SizeField",
    "adapt",
    "smooth",
    "__version__",
]

# The names users see in tracebacks and help(): neomesh.Error, not neomesh._neomesh.Error.
for _type in (Error, OptionError, LevelSet, Mesh, SizeField):
    _type.__module__ = __name__

Mesh.from_arrays = staticmethod(_from_arrays)
Mesh.from_meshio = staticmethod(_from_meshio)
Mesh.to_meshio = _to_meshio
Mesh.cells = property(_cells, doc=_cells.__doc__)


class Result:
    """What a smooth() or adapt() call did: the command line's JSON report as attributes.

    The report's top-level entries are attributes (``result.quality_before``,
    ``result.boundary_change``, ``result.smooth_options``, ...), and so are those of its
    "result" section (``result.iterations``, ``result.stop_reason``, ``result.history``: one
    dict per iteration, ``result.final_energy``, ...). ``to_dict()`` is the report itself.
    """

    def __init__(self, report: dict):
        self._report = report

    def to_dict(self) -> dict:
        """The report as the command line's ``--report`` writes it, without the run's files,
        timings and memory (input, output, threads, times, peak_rss_mib*, seconds)."""
        return _json.loads(_json.dumps(self._report))

    def __getattr__(self, name: str):
        report = self.__dict__.get("_report", {})
        if name in report:
            return report[name]
        if name in report.get("result", {}):
            return report["result"][name]
        raise AttributeError(f"Result has no field {name!r}")

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(self._report) | set(self._report["result"]))

    def __repr__(self) -> str:
        r = self._report["result"]
        q0 = self._report["quality_before"]["metrics"]["scaled_jacobian"]
        q1 = self._report["quality_after"]["metrics"]["scaled_jacobian"]
        return (
            f"<neomesh.Result: {r['iterations']} iterations, {r['stop_reason']}; "
            f"min scaled Jacobian {q0['min']:.3g} -> {q1['min']:.3g}>"
        )


class Optimizer:
    """Optimizes one mesh call after call, each starting warm from the last (a simulation's
    time steps): ``opt = Optimizer(mesh)``, then ``opt.adapt(field, **options)`` per step.

    The mesh's vertices move in place; a call that raises (a bad option, an exception in
    ``progress`` or the size field, Ctrl-C) leaves them where they were.
    """

    def __init__(self, mesh: Mesh):
        self.mesh = mesh
        self._optimizer = _neomesh._Optimizer(mesh)

    def smooth(self, progress=None, **options) -> Result:
        return Result(self._optimizer.smooth(progress, **options))

    def adapt(self, size_field, progress=None, fit=None, **options) -> Result:
        return Result(self._optimizer.adapt(size_field, fit, progress, **options))

    def forget_warm_start(self) -> None:
        """The next smooth() or adapt() starts cold (the mesh was changed in another way)."""
        self._optimizer.forget_warm_start()

    def write(self, path: str) -> None:
        """Writes the mesh as the command line does after a run: with the last call's cell
        fields (energy, Q, desired volume, ...) in .vtu, and after a fit the facet group
        "interface" and the vertex fields interface and phi (collective)."""
        self._optimizer.write(path)

    def cell_fields(self) -> dict:
        """Per cell (by cell number) after a call: energy, det_G_min, Q (actual / desired
        volume), desired_volume, ... (collective)."""
        return self._optimizer.cell_fields()


def smooth(mesh: Mesh, progress=None, **options) -> Result:
    return Optimizer(mesh).smooth(progress, **options)


def adapt(mesh: Mesh, size_field, progress=None, fit=None, **options) -> Result:
    return Optimizer(mesh).adapt(size_field, progress, fit, **options)


def _option_docs(task: str) -> str:
    """The options of `task` as a docstring section, from the option table, by group in the
    order of the command line's --help."""
    groups = {}
    for o in _neomesh._options(task):
        lines = groups.setdefault(o["group"] or "Options", [])
        extra = f"; thesis=True sets {o['thesis']}" if o["thesis"] else ""
        choices = f" ({' | '.join(repr(c) for c in o['choices'])})" if o["choices"] else ""
        lines.append(f"      {o['name']}: {o['type']}{choices} = {o['default']}{extra}")
        # The table's help names other options by their flags: here by their keywords.
        text = _re.sub(r"--([a-z0-9-]+)", lambda m: m.group(1).replace("-", "_"), o["help"])
        lines += _textwrap.wrap(text, 92, initial_indent=" " * 10, subsequent_indent=" " * 10)
    return "".join(f"\n    {group}:\n" + "\n".join(lines) + "\n" for group, lines in groups.items())


smooth.__doc__ = (
    """Improves the shape of every cell of `mesh`, moving its vertices in place (the command
    line's ``neomesh smooth``); returns the Result.

    progress: called once per iteration with the iteration table's row (a dict: k, defect,
        energy, alpha, ...); an exception it raises reaches the caller, the mesh as before.
    options: the command line's options as keywords (below), checked as it checks them
        (neomesh.OptionError names the keyword).
"""
    + _option_docs("smooth")
)
Optimizer.smooth.__doc__ = smooth.__doc__

adapt.__doc__ = (
    """Moves the vertices of `mesh` in place so that cells are small where the size field is
    small (the command line's ``neomesh adapt``); returns the Result.

    size_field: where cells should be small, as the distance d to a surface (desired relative
        volume floor + |d|^power): a Python function d(points) taking an (n, dim) numpy array
        of the cells' centroids and returning n values (one call per evaluation, vectorised);
        a level-set expression string such as "sqrt(x^2+y^2)-0.5" (muparser, t the time); a
        neomesh.SizeField (circle, sphere, plane, box, level_set, metric, cell_values,
        stretched) or a neomesh.LevelSet.
    fit: a neomesh.LevelSet (or True with a level-set size field): afterwards pull a chain of
        edges (2D) / surface of faces (3D) onto its zero set.
    progress: as for smooth().
    options: the command line's options as keywords (below).
"""
    + _option_docs("adapt")
)
Optimizer.adapt.__doc__ = adapt.__doc__
