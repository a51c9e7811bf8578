#include "solver/desired_volumes.hpp"

#include <numeric>

#include "core/error.hpp"

namespace neomesh {

namespace {
// Passes of neighbour averaging for SizeMode::Smoothed: enough to remove cell-to-cell
// noise, few enough to keep the grading of a mesh (each pass widens the stencil by a cell).
constexpr int kSmoothingPasses = 4;

double global_sum(std::span<const double> values, MPI_Comm comm) {
  double local = std::accumulate(values.begin(), values.end(), 0.0), total = 0.0;
  MPI_Allreduce(&local, &total, 1, MPI_DOUBLE, MPI_SUM, comm);
  return total;
}
}  // namespace

SizeMode parse_size_mode(std::string_view name) {
  if (name == "uniform") return SizeMode::Uniform;
  if (name == "input") return SizeMode::Input;
  if (name == "smoothed") return SizeMode::Smoothed;
  fail("unknown size mode '{}' (use uniform, input or smoothed)", name);
}

void normalize_volumes(std::vector<double>& volumes, double total, MPI_Comm comm) {
  const double sum = global_sum(volumes, comm);
  if (!(sum > 0.0)) fail("the desired cell volumes sum to {} (must be positive)", sum);
  for (double& v : volumes) v *= total / sum;
}

std::vector<double> average_over_neighbours(const MeshView& view, const DofMap& dofs,
                                            std::span<const double> values) {
  // Per vertex, component 0 sums the incident cells' values and component 1 counts them
  // (every mesh has dim ≥ 2 components per vertex), so one reduction serves both.
  const int d = view.dim;
  std::vector<double> local(view.coords.size(), 0.0);
  for (const CellBlock& block : view.blocks)
    for (PetscInt c = 0; c < block.size(); ++c)
      for (int i = 0; i < num_vertices(block.type); ++i) {
        local[block.cell(c)[i] * d] += values[block.first_cell + c];
        local[block.cell(c)[i] * d + 1] += 1.0;
      }
  OwnedVec global = dofs.create_global_vector();
  dofs.add_local_to_global(local, global);
  dofs.global_to_local(global, local);

  std::vector<double> averaged(values.size());
  for (const CellBlock& block : view.blocks)
    for (PetscInt c = 0; c < block.size(); ++c) {
      double sum = 0.0;
      for (int i = 0; i < num_vertices(block.type); ++i) {
        const PetscInt v = block.cell(c)[i];
        sum += local[v * d] / local[v * d + 1];
      }
      averaged[block.first_cell + c] = sum / num_vertices(block.type);
    }
  return averaged;
}

std::vector<double> desired_volumes(SizeMode mode, const MeshView& view, const DofMap& dofs,
                                    std::span<const double> cell_volumes) {
  std::vector<double> volumes(cell_volumes.begin(), cell_volumes.end());
  const double total = global_sum(cell_volumes, dofs.comm());
  switch (mode) {
    case SizeMode::Uniform:
      std::fill(volumes.begin(), volumes.end(), 1.0);
      break;
    case SizeMode::Input:
      break;
    case SizeMode::Smoothed:
      for (int pass = 0; pass < kSmoothingPasses; ++pass)
        volumes = average_over_neighbours(view, dofs, volumes);
      break;
  }
  normalize_volumes(volumes, total, dofs.comm());
  return volumes;
}

}  // namespace neomesh
