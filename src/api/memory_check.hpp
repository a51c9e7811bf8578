// Refusing, before it starts, a run that will not fit in memory: a run past the machine's
// memory is killed by the kernel without a word (square-midpoint 4096², 16.8 M quads, after
// 103 s). The estimate is a fit of the peak resident memory of `neomesh smooth` with the
// defaults (peak_rss_mib of the report; docs/benchmarks.md, "Memory") to libraries + a per
// vertex (the matrices' rows) + b per cell (targets, shapes, quality): 2D a = 1.28 KiB,
// b = 0.54 KiB (quads 512², 1024², triangles 512²: −2 … 0 %); 3D a = 6.4 KiB, b = 0.2 KiB
// (hexahedra 40³, 64³, tetrahedra 25³, 40³: 0 … +7 %). Per vertex alone, beyond the
// libraries, the 2D meshes took 1.8 (quads) to 2.4 KiB (triangles), the 3D ones 6.4
// (hexahedra) to 7.5 (tetrahedra): a triangle mesh has twice the cells per vertex.
#pragma once

#include <cstdint>
#include <string>

#include <mpi.h>

namespace neomesh {

// Bytes a process needs at its peak to optimize `vertices` vertices and `cells` cells of a
// `dim`-D mesh.
double estimated_peak_bytes(int dim, std::int64_t vertices, std::int64_t cells);

// Bytes this machine (node) can still give: MemAvailable, or less under a cgroup limit.
// NEOMESH_MEMORY_AVAILABLE_MIB, if set, replaces it (a limit the system does not show).
double available_bytes();

// Collective: throws Error (one line, naming `name`, the estimate and what is available) if the
// processes on one node together need more than it has.
void check_memory_fits(MPI_Comm comm, int dim, std::int64_t local_vertices,
                       std::int64_t local_cells, const std::string& name);

}  // namespace neomesh
