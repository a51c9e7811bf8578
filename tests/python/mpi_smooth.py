"""Run by test_mpi.py under `mpiexec -n 2`: the same calls on a communicator; prints the points
as JSON on rank 0 for the test to compare with a serial run."""
import json
import sys

import numpy as np
from mpi4py import MPI

import neomesh

comm = MPI.COMM_WORLD
path = sys.argv[1]
mesh = neomesh.Mesh.read(path, comm=comm)
assert mesh.comm.Get_size() == comm.Get_size()
owned = comm.allreduce(len(mesh.vertex_numbers))
assert owned == mesh.num_vertices, (owned, mesh.num_vertices)
rows = []
result = neomesh.smooth(mesh, progress=rows.append)
assert len(rows) >= result.iterations > 0  # (untangling rows come first)
smoothed = mesh.points  # collective: every rank asks
sizes = neomesh.adapt(mesh, lambda p: np.hypot(p[:, 0], p[:, 1]) - 0.5, max_iter=10)
points = mesh.points  # collective: every rank asks
groups = sorted(mesh.to_meshio().cell_sets)  # the file's groups, on every rank
if comm.rank == 0:
    print(json.dumps({"ranks": comm.size, "processes": result.processes,
                      "smoothed": smoothed.tolist(), "points": points.tolist(), "groups": groups, "iterations": result.iterations,
                      "adapt_iterations": sizes.iterations}))
