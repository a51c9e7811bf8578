#include "api/memory_check.hpp"

#include <algorithm>
#include <string>

#include "core/collective_error.hpp"
#include "core/error.hpp"
#include "core/memory.hpp"

namespace neomesh {

namespace {

constexpr double kKiB = 1024.0, kMiB = 1024.0 * kKiB, kGiB = 1024.0 * kMiB;
constexpr double kLibraries = 60 * kMiB;
constexpr double kPerVertex2D = 1.02 * kKiB, kPerVertex3D = 4.2 * kKiB;
constexpr double kPerCell2D = 0.30 * kKiB, kPerCell3D = 0.04 * kKiB;

// With a hierarchy of H(α), what lies beyond the libraries grows by a factor measured on the
// boxes (docs/benchmarks.md, "Memory"): from the grid of squares or cubes (a cell per vertex) to
// the split one (2 triangles, 5.6 tetrahedra per vertex), quads 2.35 → triangles 1.85,
// hexahedra 3.6 → tetrahedra 2.0; a mesh between them, in proportion.
double hessian_hierarchy_factor(int dim, double cells_per_vertex) {
  const double split = dim == 2 ? 2.0 : 5.6;
  const double grid_factor = dim == 2 ? 2.35 : 3.6, split_factor = dim == 2 ? 1.85 : 2.0;
  const double t = std::clamp((cells_per_vertex - 1.0) / (split - 1.0), 0.0, 1.0);
  return grid_factor + t * (split_factor - grid_factor);
}

// "21.5 GiB", or "40 MiB" below a GiB.
std::string size_text(double bytes) {
  return bytes >= kGiB ? fmt::format("{:.1f} GiB", bytes / kGiB)
                       : fmt::format("{:.0f} MiB", bytes / kMiB);
}

}  // namespace

double estimated_peak_bytes(int dim, std::int64_t vertices, std::int64_t cells,
                            bool hessian_hierarchy) {
  const double factor = !hessian_hierarchy || vertices == 0
                            ? 1.0
                            : hessian_hierarchy_factor(
                                  dim, static_cast<double>(cells) / static_cast<double>(vertices));
  return kLibraries +
         factor * (static_cast<double>(vertices) * (dim == 2 ? kPerVertex2D : kPerVertex3D) +
                   static_cast<double>(cells) * (dim == 2 ? kPerCell2D : kPerCell3D));
}

double node_sum(MPI_Comm comm, double bytes) {
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  MPI_Allreduce(MPI_IN_PLACE, &bytes, 1, MPI_DOUBLE, MPI_SUM, node);
  MPI_Comm_free(&node);
  return bytes;
}

void check_memory_fits(MPI_Comm comm, int dim, std::int64_t local_vertices,
                       std::int64_t local_cells, bool hessian_hierarchy, double held,
                       const std::string& name) {
  const double peak = estimated_peak_bytes(dim, local_vertices, local_cells, hessian_hierarchy);
  // What this process does not hold yet.
  const double further = std::max(0.0, peak - kLibraries - held - kept_bytes());
  const double need = node_sum(comm, peak), more = node_sum(comm, further);
  const double have = available_bytes();
  std::string message;
  if (more > have)
    message = fmt::format(
        "{}: the run needs about {} of memory, {} more than it holds, and this machine has {} "
        "available; run it on more machines (mpiexec over several nodes) or a larger one",
        name, size_text(need), size_text(more), size_text(std::max(0.0, have)));
  throw_if_any(comm, message);
  expect_peak(resident_bytes() + further);
}

}  // namespace neomesh
