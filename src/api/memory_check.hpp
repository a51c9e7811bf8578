// Refusing, before it starts, a run that will not fit in memory: a run past the machine's
// memory is killed by the kernel without a word (square-midpoint 4096², 16.8 M quads, after
// 103 s). The estimate is a fit of the peak resident memory of `neomesh smooth` with the
// defaults (peak_rss_mib of the report; docs/benchmarks.md, "Memory") to 60 MiB of libraries +
// a per vertex (the matrices' rows) + b per cell (targets, shapes, quality): 2D a = 0.97 KiB,
// b = 0.37 KiB; 3D a = 4.1 KiB, b = 0.13 KiB. It leaves out what a run spends only where the
// memory is free (a second AMG hierarchy, solver/component_preconditioner.hpp), and options
// that build a hierarchy of H(α) too (--hess-pc hessian: about twice the memory).
#pragma once

#include <cstdint>
#include <string>

#include <mpi.h>

namespace neomesh {

// Bytes a process needs at its peak to optimize `vertices` vertices and `cells` cells of a
// `dim`-D mesh.
double estimated_peak_bytes(int dim, std::int64_t vertices, std::int64_t cells);

// Collective: estimated_peak_bytes summed over the processes on this one's node.
double node_peak_bytes(MPI_Comm comm, int dim, std::int64_t local_vertices,
                       std::int64_t local_cells);

// Collective: throws Error (one line, naming `name`, the estimate and what is available) if the
// processes on one node together need more than it has.
void check_memory_fits(MPI_Comm comm, int dim, std::int64_t local_vertices,
                       std::int64_t local_cells, const std::string& name);

}  // namespace neomesh
