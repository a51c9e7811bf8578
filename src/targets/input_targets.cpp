#include "targets/input_targets.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <tuple>
#include <utility>

#include "core/error.hpp"
#include "targets/desired_volumes.hpp"

namespace neomesh {

namespace {

// 0 below `from`, 1 above `to`, linear between.
double ramp(double x, double from, double to) {
  return std::clamp((x - from) / (to - from), 0.0, 1.0);
}

template <int Dim>
using Mat = Eigen::Matrix<double, Dim, Dim>;

// One input cell, from one eigen-decomposition of S Sᵀ = Q diag(λ) Qᵀ (S = J / det J^(1/d)):
// V = Q diag(√λ) Qᵀ, log V, and the log-stretches' spread.
template <int Dim>
struct InputCell {
  Mat<Dim> S, Q;
  Eigen::Matrix<double, Dim, 1> log_stretches;  // ½ log λ, ascending

  explicit InputCell(const Mat<Dim>& shape) : S(shape) {
    // The closed form of 2×2 and 3×3 (where two stretches are close its eigenvectors are less
    // accurate, but log V does not depend on them there).
    Eigen::SelfAdjointEigenSolver<Mat<Dim>> eigen;
    eigen.computeDirect(S * S.transpose());
    Q = eigen.eigenvectors();
    log_stretches = 0.5 * eigen.eigenvalues().array().log();
  }
  Mat<Dim> log_stretch() const { return Q * log_stretches.asDiagonal() * Q.transpose(); }
  double anisotropy() const { return log_stretches[Dim - 1] - log_stretches[0]; }
  // S_w = V^w R = V^(w−1) S.
  Mat<Dim> kept_shape(double w) const {
    return Q * ((w - 1.0) * log_stretches).array().exp().matrix().asDiagonal() * Q.transpose() * S;
  }
};

// A cell of a mesher's design without its skew (see the header), as the metric M = SᵀS of its
// shape in the reference frame (det M = 1): the rectangle or brick of its mean edge lengths (a
// Q1 cell's Jacobian at its centre has the means of its parallel edges as columns), the right
// pyramid over the rectangle of its base edges, of the same height over its base.
template <int Dim>
Mat<Dim> right_angled_metric(CellType type, const Mat<Dim>& S) {
  const Mat<Dim> gram = S.transpose() * S;
  Mat<Dim> M = gram.diagonal().asDiagonal();
  if constexpr (Dim == 3)
    if (type == CellType::Pyramid)  // h² = det(SᵀS) / det(base Gram)
      M(2, 2) = gram.determinant() / gram.template topLeftCorner<2, 2>().determinant();
  return M / std::pow(M.determinant(), 1.0 / Dim);
}

// S_w with S_wᵀ S_w = M^w: only TᵀT enters the energy (docs/method.md §9), so the symmetric
// root does. Also returns log σ_max(S_w) for the weight.
template <int Dim>
std::pair<Mat<Dim>, double> metric_shape(const Mat<Dim>& M, double w) {
  Eigen::SelfAdjointEigenSolver<Mat<Dim>> eigen;
  eigen.computeDirect(M);
  const Eigen::Matrix<double, Dim, 1> half_logs = 0.5 * w * eigen.eigenvalues().array().log();
  return {eigen.eigenvectors() * half_logs.array().exp().matrix().asDiagonal() *
              eigen.eigenvectors().transpose(),
          half_logs.maxCoeff()};
}

template <int Dim>
double log_anisotropy(const Mat<Dim>& log_stretch) {
  const auto logs = Eigen::SelfAdjointEigenSolver<Mat<Dim>>()
                        .computeDirect(log_stretch, Eigen::EigenvaluesOnly)
                        .eigenvalues();
  return logs[Dim - 1] - logs[0];
}

double global_max(double local, MPI_Comm comm) {
  MPI_Allreduce(MPI_IN_PLACE, &local, 1, MPI_DOUBLE, MPI_MAX, comm);
  return local;
}

// The input share of every cell for TargetMode::Smoothed (see the header).
template <int Dim>
void coherent_shares(const MeshView& view, const DofMap& dofs,
                     const std::vector<std::optional<InputCell<Dim>>>& input,
                     std::span<const double> edge_ratios, std::vector<double>& input_share) {
  const std::size_t cells = input.size();
  std::vector<Mat<Dim>> log_stretch(cells, Mat<Dim>::Zero());
  std::vector<double> own(cells, 0.0);
#pragma omp parallel for schedule(static)
  for (std::size_t c = 0; c < cells; ++c)
    if (input[c]) log_stretch[c] = input[c]->log_stretch(), own[c] = input[c]->anisotropy();
  // One pass per cell type of the mesh, on every rank (the averages are collective).
  std::array<int, kNumCellTypes> present{};
  for (const CellBlock& block : view.blocks) present[static_cast<int>(block.type)] = 1;
  MPI_Allreduce(MPI_IN_PLACE, present.data(), kNumCellTypes, MPI_INT, MPI_MAX, dofs.comm());
  for (const CellType type : kAllCellTypes) {
    if (!present[static_cast<int>(type)]) continue;
    std::vector<double> weight(cells, 0.0), weighted_own(cells, 0.0);
    for (const CellBlock& block : view.blocks)
      if (block.type == type)
        for (PetscInt c = block.first_cell; c < block.first_cell + block.size(); ++c)
          if (input[c]) weight[c] = 1.0, weighted_own[c] = own[c];
    const std::vector<double> share = average_over_neighbours(view, dofs, weight);
    const std::vector<double> mean_own = average_over_neighbours(view, dofs, weighted_own);
    std::array<std::vector<double>, Dim * Dim> mean;
    for (int i = 0; i < Dim; ++i)
      for (int j = i; j < Dim; ++j) {
        std::vector<double> component(cells);
        for (std::size_t c = 0; c < cells; ++c) component[c] = weight[c] * log_stretch[c](i, j);
        mean[i * Dim + j] = average_over_neighbours(view, dofs, component);
      }
#pragma omp parallel for schedule(static)
    for (std::size_t c = 0; c < cells; ++c) {
      if (weight[c] == 0.0 || !(share[c] > 0.0)) continue;
      Mat<Dim> m;
      for (int i = 0; i < Dim; ++i)
        for (int j = i; j < Dim; ++j) m(i, j) = m(j, i) = mean[i * Dim + j][c] / share[c];
      const double anisotropy = log_anisotropy<Dim>(m);
      // log f: how much more the cell is stretched than its edges are long (not for simplices,
      // see the header).
      const double shear = is_simplex(type) ? 0.0 : own[c] - std::log(edge_ratios[c]);
      input_share[c] = ramp(anisotropy, std::log(kStretched.from), std::log(kStretched.to)) *
                       ramp(anisotropy / std::max(mean_own[c] / share[c], std::log(1.5)),
                            kCoherence.from, kCoherence.to) *
                       (1.0 - ramp(shear, std::log(kSheared.from), std::log(kSheared.to)));
    }
  }
}

template <int Dim>
CellTargets input_targets(TargetMode mode, const MeshView& view, const DofMap& dofs,
                          std::span<const double> cell_volumes, std::span<const double> jacobians,
                          std::span<const double> edge_ratios, std::vector<double> ideal_volumes) {
  const std::size_t cells = cell_volumes.size();
  CellTargets t = ideal_targets(std::move(ideal_volumes));
  // Each valid cell's J = s V R, det V = 1.
  std::vector<std::optional<InputCell<Dim>>> input(cells);
  double most_stretched = 0.0;
  // Cell by cell, on every thread (an eigen-decomposition each: 0.15 s of tetrahedra 40³ on one).
#pragma omp parallel for schedule(static) reduction(max : most_stretched)
  for (std::size_t c = 0; c < cells; ++c) {
    const Mat<Dim> J = Eigen::Map<const Mat<Dim>>(jacobians.data() + c * Dim * Dim);
    const double det = J.determinant();
    if (!(det > 0.0) || !(cell_volumes[c] > 0.0)) continue;
    input[c].emplace(J / std::pow(det, 1.0 / Dim));
    most_stretched = std::max(most_stretched, input[c]->anisotropy());
  }
  if (mode == TargetMode::Input) {
    for (std::size_t c = 0; c < cells; ++c) t.input_share[c] = input[c] ? 1.0 : 0.0;
  } else if (global_max(most_stretched, dofs.comm()) > std::log(kStretched.from)) {
    // (The mean's anisotropy is at most the largest cell's: no stretched cell, none kept.)
    coherent_shares<Dim>(view, dofs, input, edge_ratios, t.input_share);
  }
  // No cell kept: the thesis' ideal targets, exactly.
  const double most_kept =
      t.input_share.empty() ? 0.0 : *std::max_element(t.input_share.begin(), t.input_share.end());
  if (global_max(most_kept, dofs.comm()) == 0.0) return t;

  // S = V^w R, v = v_input^w v_sizes^(1−w) scaled to the mesh volume, k = (C a)^w.
  double total = 0.0;
  for (double v : cell_volumes) total += v;
  MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_DOUBLE, MPI_SUM, dofs.comm());
  t.shapes.assign(cells * Dim * Dim, 0.0);
  t.weights.assign(cells, 1.0);
  std::vector<double> stiffness(cells, kKeptStiffness);
  for (const CellBlock& block : view.blocks)
    if (block.type == CellType::Wedge)
      std::fill_n(stiffness.begin() + block.first_cell, block.size(), kKeptWedgeStiffness);
  std::vector<CellType> types(cells);
  for (const CellBlock& block : view.blocks)
    std::fill_n(types.begin() + block.first_cell, block.size(), block.type);
#pragma omp parallel for schedule(static)
  for (std::size_t c = 0; c < cells; ++c) {
    Eigen::Map<Mat<Dim>> S(t.shapes.data() + c * Dim * Dim);
    const double w = t.input_share[c];
    if (w == 0.0) {
      S.setIdentity();
      continue;
    }
    // log σ_max of the kept shape: a = σ_max^d is the isotropic cell spanning the longest edge
    // over the cell's volume.
    double log_longest = w * input[c]->log_stretches[Dim - 1];
    if (mode == TargetMode::Smoothed && right_angled_target(types[c]))
      std::tie(S, log_longest) =
          metric_shape<Dim>(right_angled_metric<Dim>(types[c], input[c]->S), w);
    else
      S = input[c]->kept_shape(w);
    t.volumes[c] = std::exp(w * std::log(cell_volumes[c]) + (1.0 - w) * std::log(t.volumes[c]));
    t.weights[c] = std::exp(w * std::log(stiffness[c]) + Dim * log_longest);
  }
  normalize_volumes(t.volumes, total, dofs.comm());
  return t;
}

}  // namespace

CellTargets input_targets(TargetMode mode, const MeshView& view, const DofMap& dofs,
                          std::span<const double> cell_volumes, std::span<const double> jacobians,
                          std::span<const double> edge_ratios, std::vector<double> ideal_volumes) {
  const std::size_t cells = cell_volumes.size();
  const int d = view.cell_dim();  // a surface cell's Jacobian is that of its image in its frame
  const std::size_t entries = static_cast<std::size_t>(d * d) * cells;
  if (jacobians.size() != entries || ideal_volumes.size() != cells || edge_ratios.size() != cells)
    fail("internal error: {} Jacobian entries, {} edge ratios and {} volumes for {} cells",
         jacobians.size(), edge_ratios.size(), ideal_volumes.size(), cells);
  if (d == 2)
    return input_targets<2>(mode, view, dofs, cell_volumes, jacobians, edge_ratios,
                            std::move(ideal_volumes));
  return input_targets<3>(mode, view, dofs, cell_volumes, jacobians, edge_ratios,
                          std::move(ideal_volumes));
}

KeptCells count_kept(std::span<const double> input_share, MPI_Comm comm) {
  long long counts[3] = {0, 0, 0};
  for (double w : input_share) ++counts[w >= 1.0 ? 0 : w > 0.0 ? 1 : 2];
  MPI_Allreduce(MPI_IN_PLACE, counts, 3, MPI_LONG_LONG, MPI_SUM, comm);
  return {counts[0], counts[1], counts[2]};
}

}  // namespace neomesh
