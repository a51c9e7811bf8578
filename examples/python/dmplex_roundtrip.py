"""Hand neomesh a PETSc DMPlex built with petsc4py, and put the smoothed coordinates back into
it: a PETSc application keeps its own DM and lets neomesh move the vertices.

    python3 dmplex_roundtrip.py            # also: mpiexec -n 2 python3 dmplex_roundtrip.py
"""
import numpy as np
from mpi4py import MPI
from petsc4py import PETSc

import neomesh

comm = PETSc.COMM_WORLD

# The application's mesh: 16 × 16 quadrilaterals of [0,1]², interior vertices jittered.
dm = PETSc.DMPlex().createBoxMesh([16, 16], simplex=False, interpolate=True, comm=comm)
dm.distribute()
x = dm.getCoordinatesLocal()
xy = x.getArray().reshape(-1, 2)
interior = np.all((xy > 1e-12) & (xy < 1 - 1e-12), axis=1)
# A function of the position, so that a vertex that several processes hold moves alike on all;
# at most 0.01 per coordinate, 16% of an edge: no cell inverts.
p = xy[interior]
xy[interior] += 0.01 * np.column_stack([np.sin(91 * p[:, 0] + 37 * p[:, 1]),
                                        np.cos(53 * p[:, 0] - 71 * p[:, 1])])
dm.setCoordinatesLocal(x)

mesh = neomesh.Mesh.from_dm(dm)  # neomesh's own copy; dm stays the application's
result = neomesh.smooth(mesh, boundary="fixed")
if comm.rank == 0:
    print(result)

# Back by the DM's vertex numbering (DMPlexGetVertexNumbering; ghosts as -(n+1)).
numbers = dm.getVertexNumbering().getIndices()
numbers = np.where(numbers < 0, -(numbers + 1), numbers)
points = mesh.points  # every vertex, by number, on every process
moved = np.abs(points[numbers] - xy).max()
x.setArray(points[numbers].ravel())
dm.setCoordinatesLocal(x)
largest = comm.tompi4py().allreduce(moved, op=MPI.MAX)
if comm.rank == 0:
    q = result.quality_after["metrics"]["scaled_jacobian"]
    q0 = result.quality_before["metrics"]["scaled_jacobian"]
    print(f"{mesh.num_cells} cells on {comm.size} process(es): scaled Jacobian min "
          f"{q0['min']:.3f} -> {q['min']:.3f}; the DM's vertices moved by up to {largest:.3g}")
