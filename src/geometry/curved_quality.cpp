#include "geometry/curved_quality.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.hpp"
#include "core/petsc.hpp"

namespace neomesh {

namespace {

template <CurvedType Type>
CurvedScaledJacobian measure(const InputMesh& mesh, const std::vector<double>& x, PetscInt c) {
  using Traits = CurvedTraits<Type>;
  PetscInt points[kMaxCurvedNodes];
  curved_cell_points(mesh, c, points);
  typename Traits::Nodes nodes;
  for (int i = 0; i < Traits::nodes; ++i)
    for (int d = 0; d < Traits::dim; ++d) nodes(d, i) = x[points[i] * Traits::dim + d];
  return curved_scaled_jacobian<Type>(nodes);
}

}  // namespace

CurvedScaledJacobian curved_cell_quality(const InputMesh& mesh, const std::vector<double>& x,
                                         PetscInt c) {
  return visit_curved_type(mesh.high_order.types[c], [&]<CurvedType Type>(CurvedTag<Type>) {
    return measure<Type>(mesh, x, c);
  });
}

namespace {

// The summary of the cells `q` of types `types` (one per cell), their mean taken over `total`
// cells; summed over processes by reduce() after.
CurvedQualitySummary summarize(std::span<const CurvedScaledJacobian> q,
                               std::span<const CurvedType> types, double total) {
  CurvedQualitySummary s;
  std::array<std::int64_t, kCurvedTypes.size()> counts{};
  for (CurvedType t : types) ++counts[static_cast<int>(t)];
  for (CurvedType t : kCurvedTypes)
    if (counts[static_cast<int>(t)] > 0)
      s.cells_by_type.emplace_back(std::string(name(t)), counts[static_cast<int>(t)]);
  MetricStats& sj = s.scaled_jacobian;
  sj = {INFINITY, 0.0, -INFINITY};
  s.scaled_jacobian_lower_bound = INFINITY;
  for (const CurvedScaledJacobian& cell : q) {
    s.invalid += cell.certificate.validity == Validity::Invalid;
    s.undecided += cell.certificate.validity == Validity::Undecided;
    sj.min = std::min(sj.min, cell.upper);
    sj.max = std::max(sj.max, cell.upper);
    sj.mean += cell.upper / total;
    s.scaled_jacobian_lower_bound = std::min(s.scaled_jacobian_lower_bound, cell.lower);
  }
  s.not_valid = s.invalid + s.undecided;
  return s;
}

// The nodes of cell c of `block` (a block of curved cells of type Type) at `coords`.
template <CurvedType Type>
typename CurvedTraits<Type>::Nodes block_nodes(const CellBlock& block, PetscInt c,
                                               std::span<const double> coords) {
  constexpr int d = CurvedTraits<Type>::dim;
  typename CurvedTraits<Type>::Nodes x;
  for (int i = 0; i < CurvedTraits<Type>::nodes; ++i)
    for (int j = 0; j < d; ++j) x(j, i) = coords[d * block.cell(c)[i] + j];
  return x;
}

// Collective: the processes' summaries as one.
CurvedQualitySummary reduce(const CurvedQualitySummary& local, MPI_Comm comm) {
  constexpr int kTypes = static_cast<int>(kCurvedTypes.size());
  std::array<double, kTypes + 3> sums{};  // counts per type, invalid, undecided, mean
  for (const auto& [type, count] : local.cells_by_type)
    for (int t = 0; t < kTypes; ++t)
      if (name(kCurvedTypes[t]) == type) sums[t] = static_cast<double>(count);
  sums[kTypes] = static_cast<double>(local.invalid);
  sums[kTypes + 1] = static_cast<double>(local.undecided);
  sums[kTypes + 2] = local.scaled_jacobian.mean;
  std::array<double, 3> least = {local.scaled_jacobian.min, -local.scaled_jacobian.max,
                                 local.scaled_jacobian_lower_bound};
  MPI_Allreduce(MPI_IN_PLACE, sums.data(), static_cast<int>(sums.size()), MPI_DOUBLE, MPI_SUM,
                comm);
  MPI_Allreduce(MPI_IN_PLACE, least.data(), static_cast<int>(least.size()), MPI_DOUBLE, MPI_MIN,
                comm);
  CurvedQualitySummary s;
  for (int t = 0; t < kTypes; ++t)
    if (sums[t] > 0)
      s.cells_by_type.emplace_back(std::string(name(kCurvedTypes[t])),
                                   static_cast<std::int64_t>(sums[t]));
  s.invalid = static_cast<std::int64_t>(sums[kTypes]);
  s.undecided = static_cast<std::int64_t>(sums[kTypes + 1]);
  s.not_valid = s.invalid + s.undecided;
  s.scaled_jacobian = {least[0], sums[kTypes + 2], -least[1]};
  s.scaled_jacobian_lower_bound = least[2];
  return s;
}

}  // namespace

CurvedQualitySummary curved_quality(const InputMesh& mesh) {
  if (!mesh.curved()) fail("curved_quality: the mesh has no second-order cells");
  const std::vector<double> x = curved_point_coordinates(mesh);
  const PetscInt n = mesh.num_cells();
  std::vector<CurvedScaledJacobian> q(n);
#pragma omp parallel for schedule(dynamic, 64)
  for (PetscInt c = 0; c < n; ++c) q[c] = curved_cell_quality(mesh, x, c);
  return summarize(q, mesh.high_order.types, static_cast<double>(n));
}

CurvedQualitySummary curved_quality_on_root(const InputMesh& mesh, MPI_Comm comm) {
  // The other processes add nothing: no cells, and the neutral values of min and max.
  const CurvedQualitySummary s =
      mpi_rank(comm) == 0 ? curved_quality(mesh) : summarize({}, {}, 1.0);
  return reduce(s, comm);
}

CurvedQualitySummary curved_quality(const MeshView& cells, std::span<const double> coords,
                                    MPI_Comm comm) {
  std::vector<CurvedScaledJacobian> q(cells.num_cells);
  std::vector<CurvedType> types(cells.num_cells);
  for (const CellBlock& block : cells.blocks) {
    if (!block.curved) fail("internal error: the curved quality of a straight cell");
    std::fill_n(types.begin() + block.first_cell, block.size(), *block.curved);
    visit_curved_type(*block.curved, [&]<CurvedType Type>(CurvedTag<Type>) {
#pragma omp parallel for schedule(dynamic, 64)
      for (PetscInt c = 0; c < block.size(); ++c) {
        q[block.first_cell + c] = curved_scaled_jacobian<Type>(block_nodes<Type>(block, c, coords));
      }
    });
  }
  PetscInt local = cells.num_cells, total = 0;
  MPI_Allreduce(&local, &total, 1, MPIU_INT, MPI_SUM, comm);
  return reduce(summarize(q, types, static_cast<double>(total)), comm);
}

std::vector<char> certified_valid(const MeshView& cells, std::span<const double> coords,
                                  std::span<const char> only) {
  std::vector<char> valid(cells.num_cells, 0);
  for (const CellBlock& block : cells.blocks) {
    if (!block.curved) fail("internal error: the certificate of a straight cell");
    visit_curved_type(*block.curved, [&]<CurvedType Type>(CurvedTag<Type>) {
#pragma omp parallel for schedule(dynamic, 64)
      for (PetscInt c = 0; c < block.size(); ++c) {
        const PetscInt cell = block.first_cell + c;
        if (!only.empty() && !only[cell]) continue;
        valid[cell] =
            certify_jacobian<Type>(block_nodes<Type>(block, c, coords)).validity == Validity::Valid;
      }
    });
  }
  return valid;
}

}  // namespace neomesh
