#include "solver/targets.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.hpp"
#include "solver/desired_volumes.hpp"

namespace neomesh {

namespace {

using Matrix = Eigen::MatrixXd;

// f(A) for a symmetric A, applied to its eigenvalues.
template <typename F>
Matrix symmetric_function(const Matrix& a, F f) {
  const Eigen::SelfAdjointEigenSolver<Matrix> eigen(a);
  return eigen.eigenvectors() * eigen.eigenvalues().unaryExpr(f).asDiagonal() *
         eigen.eigenvectors().transpose();
}

Matrix log_of(const Matrix& a) {
  return symmetric_function(a, [](double x) { return std::log(x); });
}
Matrix exp_of(const Matrix& a) {
  return symmetric_function(a, [](double x) { return std::exp(x); });
}

// log of the anisotropy (largest over smallest stretch) of a symmetric log-stretch.
double log_anisotropy(const Matrix& log_stretch) {
  const Eigen::VectorXd logs =
      Eigen::SelfAdjointEigenSolver<Matrix>(log_stretch, Eigen::EigenvaluesOnly).eigenvalues();
  return logs.maxCoeff() - logs.minCoeff();
}

// 0 below `from`, 1 above `to`, linear between.
double ramp(double x, double from, double to) {
  return std::clamp((x - from) / (to - from), 0.0, 1.0);
}

}  // namespace

CellTargets ideal_targets(std::vector<double> volumes) {
  CellTargets t;
  t.kept.assign(volumes.size(), 0.0);
  t.volumes = std::move(volumes);
  return t;
}

CellTargets input_targets(KeptInput kept, const MeshView& view, const DofMap& dofs,
                          std::span<const double> cell_volumes, std::span<const double> jacobians,
                          std::vector<double> ideal_volumes) {
  const int d = view.dim;
  const std::size_t cells = cell_volumes.size();
  CellTargets t = ideal_targets(std::move(ideal_volumes));
  if (jacobians.size() != cells * d * d || t.volumes.size() != cells)
    fail("internal error: {} Jacobian entries for {} cells", jacobians.size(), cells);

  // Each valid cell's J = V R, det V = 1: log V (symmetric), R, and its anisotropy.
  std::vector<Matrix> log_stretch(cells, Matrix::Zero(d, d)), rotation(cells);
  std::vector<double> valid(cells, 0.0), own(cells, 0.0);
  for (std::size_t c = 0; c < cells; ++c) {
    const Matrix J = Eigen::Map<const Matrix>(jacobians.data() + c * d * d, d, d);
    const double det = J.determinant();
    if (!(det > 0.0) || !(cell_volumes[c] > 0.0)) continue;
    const Matrix S = J / std::pow(det, 1.0 / d);
    log_stretch[c] = 0.5 * log_of(S * S.transpose());
    rotation[c] = exp_of(-log_stretch[c]) * S;
    own[c] = log_anisotropy(log_stretch[c]);
    valid[c] = 1.0;
  }

  if (kept == KeptInput::All) {
    t.kept = valid;
  } else {
    // Over the cells of its own type sharing a vertex with each cell: the mean of log V,
    // component by component, and the mean of the cells' own log-anisotropies. Layers are made
    // of one type (prisms or quads on a wall); the many tetrahedra or triangles around a
    // layer's outer cells, with their scattered small stretches, would hide the layer.
    // One pass per cell type of the mesh, on every rank (the averages are collective).
    std::array<int, kNumCellTypes> present{};
    for (const CellBlock& block : view.blocks) present[static_cast<int>(block.type)] = 1;
    MPI_Allreduce(MPI_IN_PLACE, present.data(), kNumCellTypes, MPI_INT, MPI_MAX, dofs.comm());
    for (const CellType type : kAllCellTypes) {
      if (!present[static_cast<int>(type)]) continue;
      std::vector<double> weight(cells, 0.0), weighted_own(cells, 0.0);
      for (const CellBlock& block : view.blocks)
        if (block.type == type)
          for (PetscInt c = block.first_cell; c < block.first_cell + block.size(); ++c) {
            weight[c] = valid[c];
            weighted_own[c] = valid[c] * own[c];
          }
      const std::vector<double> share = average_over_neighbours(view, dofs, weight);
      const std::vector<double> mean_own = average_over_neighbours(view, dofs, weighted_own);
      std::vector<std::vector<double>> mean(static_cast<std::size_t>(d * d));
      for (int i = 0; i < d; ++i)
        for (int j = i; j < d; ++j) {
          std::vector<double> component(cells);
          for (std::size_t c = 0; c < cells; ++c) component[c] = weight[c] * log_stretch[c](i, j);
          mean[i * d + j] = average_over_neighbours(view, dofs, component);
        }
      for (std::size_t c = 0; c < cells; ++c) {
        if (weight[c] == 0.0 || !(share[c] > 0.0)) continue;
        Matrix m(d, d);
        for (int i = 0; i < d; ++i)
          for (int j = i; j < d; ++j) m(i, j) = m(j, i) = mean[i * d + j][c] / share[c];
        const double anisotropy = log_anisotropy(m);
        t.kept[c] = ramp(anisotropy, std::log(kStretched.from), std::log(kStretched.to)) *
                    ramp(anisotropy / std::max(mean_own[c] / share[c], std::log(1.5)),
                         kCoherence.from, kCoherence.to);
      }
    }
  }

  // S = V^w R, v = v_input^w v_sizes^(1−w) scaled to the mesh volume, k = (C a)^w.
  double total = 0.0;
  for (double v : cell_volumes) total += v;
  MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_DOUBLE, MPI_SUM, dofs.comm());
  t.shapes.assign(cells * d * d, 0.0);
  t.weights.assign(cells, 1.0);
  for (std::size_t c = 0; c < cells; ++c) {
    Eigen::Map<Matrix> S(t.shapes.data() + c * d * d, d, d);
    const double w = t.kept[c];
    if (w == 0.0) {
      S.setIdentity();
      continue;
    }
    S = exp_of(w * log_stretch[c]) * rotation[c];
    t.volumes[c] = std::exp(w * std::log(cell_volumes[c]) + (1.0 - w) * std::log(t.volumes[c]));
    // a = σ_max^d: the isotropic cell spanning the longest edge over the cell's volume.
    const double largest_log_stretch =
        Eigen::SelfAdjointEigenSolver<Matrix>(log_stretch[c], Eigen::EigenvaluesOnly)
            .eigenvalues()
            .maxCoeff();
    t.weights[c] = std::exp(w * (std::log(kKeptStiffness) + d * largest_log_stretch));
  }
  normalize_volumes(t.volumes, total, dofs.comm());
  return t;
}

KeptCells count_kept(std::span<const double> kept, MPI_Comm comm) {
  long long counts[3] = {0, 0, 0};
  for (double w : kept) ++counts[w >= 1.0 ? 0 : w > 0.0 ? 1 : 2];
  MPI_Allreduce(MPI_IN_PLACE, counts, 3, MPI_LONG_LONG, MPI_SUM, comm);
  return {counts[0], counts[1], counts[2]};
}

}  // namespace neomesh
