// Refusing, before it starts, a run that will not fit in memory: a run past the machine's
// memory is killed by the kernel without a word (square-midpoint 4096², 16.8 M quads, after
// 103 s). The estimate is the measured peak resident memory per vertex (the matrices' rows):
// `neomesh smooth` with the defaults, peak_rss_mib of the report (docs/benchmarks.md,
// "Memory"): 2D 1.9 KiB per vertex (quads 512², 1024²) to 2.3 (triangles 512²), 3D 6.5 KiB
// (hexahedra 40³, 64³; tetrahedra 25³, 40³), plus about 60 MiB for the libraries. The check
// takes 2.0 KiB in 2D: rather a run that just fits refused less often than one killed.
#pragma once

#include <cstdint>
#include <string>

#include <mpi.h>

namespace neomesh {

// Bytes a process needs at its peak to optimize `vertices` vertices of a `dim`-D mesh.
double estimated_peak_bytes(int dim, std::int64_t vertices);

// Bytes this machine (node) can still give: MemAvailable, or less under a cgroup limit.
// NEOMESH_MEMORY_AVAILABLE_MIB, if set, replaces it (a limit the system does not show).
double available_bytes();

// Collective: throws Error (one line, naming `name`, the estimate and what is available) if the
// processes on one node together need more than it has.
void check_memory_fits(MPI_Comm comm, int dim, std::int64_t local_vertices,
                       const std::string& name);

}  // namespace neomesh
