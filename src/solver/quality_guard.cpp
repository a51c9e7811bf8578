#include "solver/quality_guard.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>

#include "geometry/quality.hpp"

namespace neomesh {

namespace {

// After this many halvings (displacement / 2^20) the marked vertices are reset to their
// input positions, which restores the input's cells exactly.
constexpr int kHalvings = 20;
// Then cells that mix reset and optimized vertices may still be below the threshold: their
// vertices are reset too, round by round, for at most this many rounds; after that every
// vertex is (the input itself meets the threshold).
constexpr int kResetRounds = 50;

double global_min(const std::vector<double>& values, MPI_Comm comm) {
  double local = std::numeric_limits<double>::infinity(), result = 0.0;
  for (double v : values) local = std::min(local, v);
  MPI_Allreduce(&local, &result, 1, MPI_DOUBLE, MPI_MIN, comm);
  return result;
}

std::vector<double> scaled_jacobians(const MeshView& view, const DofMap& dofs, Vec x) {
  std::vector<double> local(dofs.num_local_dofs());
  dofs.global_to_local(x, local);
  return cell_scaled_jacobians(view, local, &dofs);
}

}  // namespace

QualityGuardResult guard_worst_quality(const MeshView& view, const DofMap& dofs, Vec input, Vec x,
                                       const std::function<void(Vec)>& project,
                                       std::optional<double> threshold) {
  QualityGuardResult result;
  result.input_min = min_scaled_jacobian(view, dofs, input);
  if (threshold) result.input_min = std::min(result.input_min, *threshold);
  const OwnedVec optimum = copy_of(x);  // x as the method left it, to count what moved
  OwnedVec marked = dofs.create_global_vector(), ever_marked = dofs.create_global_vector();
  std::vector<double> local_marks(dofs.num_local_dofs());
  const int d = view.dim;

  for (int round = 0;; ++round) {
    const std::vector<double> sj = scaled_jacobians(view, dofs, x);
    if (round == 0) result.min_before = global_min(sj, dofs.comm());
    result.min_after = global_min(sj, dofs.comm());
    if (result.min_after >= result.input_min || round > kHalvings + kResetRounds) break;
    result.rounds = round + 1;

    // Mark every coordinate of every vertex of a cell below the threshold (on any rank).
    std::fill(local_marks.begin(), local_marks.end(), 0.0);
    for (const CellBlock& block : view.blocks)
      for (PetscInt c = 0; c < block.size(); ++c) {
        if (!(sj[block.first_cell + c] < result.input_min)) continue;
        for (int i = 0; i < block.nodes(); ++i)
          for (int j = 0; j < d; ++j) local_marks[block.cell(c)[i] * d + j] = 1.0;
      }
    NM_PETSC(VecZeroEntries(marked));
    dofs.add_local_to_global(local_marks, marked);

    // x ← input + ½ (x − input) on marked coordinates; from round kHalvings on, input itself.
    const double keep = round >= kHalvings ? 0.0 : 0.5;
    {
      VecReadView x0(input), m(marked);
      VecWriteView xv(x), ever(ever_marked);
      for (PetscInt i = 0; i < xv.size(); ++i) {
        if (m[i] == 0.0 || xv[i] == x0[i]) continue;
        xv[i] = x0[i] + keep * (xv[i] - x0[i]);
        ever[i] = 1.0;
      }
    }
    // A chord between two points of a curved boundary leaves it: back onto the boundary.
    if (project) project(x);
  }
  // Still below: the whole input, which meets the threshold (at most the input's worst cell).
  if (result.min_after < result.input_min) {
    NM_PETSC(VecCopy(input, x));
    {
      VecReadView x0(optimum), xv(x);
      VecWriteView ever(ever_marked);
      for (PetscInt i = 0; i < xv.size(); ++i)
        if (xv[i] != x0[i]) ever[i] = 1.0;
    }
    result.min_after = min_scaled_jacobian(view, dofs, x);
  }
  double moved_dofs = 0.0;
  NM_PETSC(VecSum(ever_marked, &moved_dofs));
  result.vertices_moved = static_cast<PetscInt>(moved_dofs) / d;
  return result;
}

double min_scaled_jacobian(const MeshView& view, const DofMap& dofs, Vec x) {
  return global_min(scaled_jacobians(view, dofs, x), dofs.comm());
}

namespace {

// Over all ranks' cells.
double global_mean(std::span<const double> values, const MeshView& view, MPI_Comm comm) {
  double sum = 0.0;
  for (double q : values) sum += q;
  std::int64_t cells = view.num_cells;
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, &cells, 1, MPI_INT64_T, MPI_SUM, comm);
  return cells > 0 ? sum / static_cast<double>(cells) : 0.0;
}

}  // namespace

double mean_scaled_jacobian(const MeshView& view, const DofMap& dofs, Vec x) {
  return global_mean(scaled_jacobians(view, dofs, x), view, dofs.comm());
}

double mean_inverse_mean_ratio(const MeshView& view, const DofMap& dofs, Vec x) {
  std::vector<double> local(dofs.num_local_dofs());
  dofs.global_to_local(x, local);
  return global_mean(cell_inverse_mean_ratios(view, local, &dofs), view, dofs.comm());
}

}  // namespace neomesh
