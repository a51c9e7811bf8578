#include "targets/desired_volumes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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

double domain_coverage(std::span<const double> cell_volumes, MPI_Comm comm) {
  double sums[2] = {0.0, 0.0};  // Σ|v_K| and Σ v_K, reduced together
  for (double v : cell_volumes) {
    sums[0] += std::abs(v);
    sums[1] += v;
  }
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, comm);
  return sums[1] > 0.0 ? sums[0] / sums[1] : std::numeric_limits<double>::infinity();
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
      for (int i = 0; i < block.nodes(); ++i) {
        local[block.cell(c)[i] * d] += values[block.first_cell + c];
        local[block.cell(c)[i] * d + 1] += 1.0;
      }
  dofs.sum_over_ranks(local);

  std::vector<double> averaged(values.size());
  for (const CellBlock& block : view.blocks)
#pragma omp parallel for schedule(static)
    for (PetscInt c = 0; c < block.size(); ++c) {
      double sum = 0.0;
      for (int i = 0; i < block.nodes(); ++i) {
        const PetscInt v = block.cell(c)[i];
        sum += local[v * d] / local[v * d + 1];
      }
      averaged[block.first_cell + c] = sum / block.nodes();
    }
  return averaged;
}

namespace {

// Cells of a tangled input have no meaningful volume of their own (an inverted simplex's is
// negative): those with volume ≤ 0 take the mean of their neighbours with a positive one,
// growing inwards pass by pass, and in the end the mean of all positive volumes.
void fill_in_non_positive_volumes(const MeshView& view, const DofMap& dofs,
                                  std::vector<double>& volumes) {
  const MPI_Comm comm = dofs.comm();
  std::vector<double> known(volumes.size());
  for (int pass = 0;; ++pass) {
    std::size_t unknown = 0;
    for (std::size_t c = 0; c < volumes.size(); ++c) {
      known[c] = volumes[c] > 0.0 ? 1.0 : 0.0;
      if (known[c] == 0.0) volumes[c] = 0.0;
      unknown += known[c] == 0.0;
    }
    unsigned long global_unknown = unknown;
    MPI_Allreduce(MPI_IN_PLACE, &global_unknown, 1, MPI_UNSIGNED_LONG, MPI_SUM, comm);
    if (global_unknown == 0) return;
    if (pass == kSmoothingPasses) {
      const double mean = global_sum(volumes, comm) / std::max(global_sum(known, comm), 1.0);
      for (std::size_t c = 0; c < volumes.size(); ++c)
        if (known[c] == 0.0) volumes[c] = mean;
      return;
    }
    const std::vector<double> sum = average_over_neighbours(view, dofs, volumes);
    const std::vector<double> share = average_over_neighbours(view, dofs, known);
    for (std::size_t c = 0; c < volumes.size(); ++c)
      if (known[c] == 0.0 && share[c] > 0.0) volumes[c] = sum[c] / share[c];
  }
}

}  // namespace

std::vector<double> desired_volumes_from_input(SizeMode volume_source, const MeshView& view,
                                               const DofMap& dofs,
                                               std::span<const double> cell_volumes) {
  std::vector<double> volumes(cell_volumes.begin(), cell_volumes.end());
  const double total = global_sum(cell_volumes, dofs.comm());
  if (volume_source != SizeMode::Uniform) fill_in_non_positive_volumes(view, dofs, volumes);
  switch (volume_source) {
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
