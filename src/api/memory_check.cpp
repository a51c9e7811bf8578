#include "api/memory_check.hpp"

#include <string>

#include "core/collective_error.hpp"
#include "core/error.hpp"
#include "core/memory.hpp"

namespace neomesh {

namespace {

constexpr double kKiB = 1024.0, kMiB = 1024.0 * kKiB, kGiB = 1024.0 * kMiB;
constexpr double kLibraries = 60 * kMiB;
constexpr double kPerVertex2D = 0.97 * kKiB, kPerVertex3D = 4.1 * kKiB;
constexpr double kPerCell2D = 0.37 * kKiB, kPerCell3D = 0.13 * kKiB;

}  // namespace

double estimated_peak_bytes(int dim, std::int64_t vertices, std::int64_t cells) {
  return kLibraries + static_cast<double>(vertices) * (dim == 2 ? kPerVertex2D : kPerVertex3D) +
         static_cast<double>(cells) * (dim == 2 ? kPerCell2D : kPerCell3D);
}

double node_peak_bytes(MPI_Comm comm, int dim, std::int64_t local_vertices,
                       std::int64_t local_cells) {
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  double need = estimated_peak_bytes(dim, local_vertices, local_cells);
  MPI_Allreduce(MPI_IN_PLACE, &need, 1, MPI_DOUBLE, MPI_SUM, node);
  MPI_Comm_free(&node);
  return need;
}

void check_memory_fits(MPI_Comm comm, int dim, std::int64_t local_vertices,
                       std::int64_t local_cells, const std::string& name) {
  const double need = node_peak_bytes(comm, dim, local_vertices, local_cells);
  const double have = available_bytes();
  std::string message;
  if (need > have)
    message = fmt::format(
        "{}: the run needs about {:.1f} GiB of memory on this machine and {:.1f} GiB are "
        "available; run it on more machines (mpiexec over several nodes) or a larger one",
        name, need / kGiB, have / kGiB);
  throw_if_any(comm, message);
}

}  // namespace neomesh
