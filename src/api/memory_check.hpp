// Refusing, before it starts, a run that will not fit in memory: a run past the machine's
// memory is killed by the kernel without a word (square-midpoint 4096², 16.8 M quads, after
// 103 s). The estimate is a fit of the peak resident memory of `neomesh smooth` with the
// defaults (peak_rss_mib of the report; docs/benchmarks.md, "Memory") to 60 MiB of libraries +
// a per vertex (the matrices' rows) + b per cell (targets, shapes, quality): 2D a = 1.02 KiB,
// b = 0.30 KiB; 3D a = 4.2 KiB, b = 0.04 KiB. It leaves out what a run spends only where the
// memory is free (a second AMG hierarchy, solver/component_preconditioner.hpp). A hierarchy of
// H(α) (--hess-pc hessian) multiplies what lies beyond the libraries by a factor measured on
// the boxes: 2.35 for quads, 1.85 for triangles, 3.6 for hexahedra, 2.0 for tetrahedra. What the
// process already holds of the peak (the libraries, the mesh read) is not asked of the machine
// again: counted twice, it refused square-midpoint 4096² (about 21 GiB estimated, 4.3 GiB
// held, 18.6 GiB available), which runs at a peak of 20.1 GiB.
#pragma once

#include <cstdint>
#include <string>

#include <mpi.h>

namespace neomesh {

// Bytes a process needs at its peak to optimize `vertices` vertices and `cells` cells of a
// `dim`-D mesh; `hessian_hierarchy`: the δ̃ solve is preconditioned by a hierarchy of H(α).
double estimated_peak_bytes(int dim, std::int64_t vertices, std::int64_t cells,
                            bool hessian_hierarchy = false);

// Collective: `bytes` summed over the processes on this one's node.
double node_sum(MPI_Comm comm, double bytes);

// Collective: throws Error (one line, naming `name`, the estimate and what is available) if the
// processes on one node together need more than it has beyond what they hold: the estimate
// less the libraries (loaded before any mesh), `held` (what making the mesh added to the
// process: the mesh, and what its reader freed, which malloc keeps for the run) and what
// keep_and_fault_in faulted in for the run. Else expects the run's peak (core/memory.hpp,
// expect_peak).
void check_memory_fits(MPI_Comm comm, int dim, std::int64_t local_vertices,
                       std::int64_t local_cells, bool hessian_hierarchy, double held,
                       const std::string& name);

}  // namespace neomesh
