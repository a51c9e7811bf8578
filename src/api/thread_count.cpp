#include "api/thread_count.hpp"

#include <mpi.h>
#include <omp.h>

#include <algorithm>
#include <cstdlib>

namespace neomesh {

namespace {
// Below this many vertices × dim² per rank a second OpenMP thread gains nothing (quads 100²,
// tets 12³, the DFG channel's 5,878 quads under adapt: the same time or slower), above it it
// does (quads 170²: 12% faster, hexahedra 20³: 20%); docs/benchmarks.md, "Threads and a shared
// machine".
constexpr double kThreadedWork = 6e4;
}  // namespace

int run_thread_count(const Mesh& mesh) {
  if (std::getenv("OMP_NUM_THREADS")) return 0;
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(mesh.comm(), MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int ranks = 1, size = 1;
  MPI_Comm_size(node, &ranks);
  MPI_Comm_free(&node);
  MPI_Comm_size(mesh.comm(), &size);
  const double work = static_cast<double>(mesh.num_vertices()) * mesh.dim() * mesh.dim() / size;
  return work < kThreadedWork ? 1 : std::max(1, omp_get_num_procs() / ranks);
}

}  // namespace neomesh
