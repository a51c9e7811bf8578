#include "geometry/curved_quality.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

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

CurvedQualitySummary curved_quality(const InputMesh& mesh) {
  if (!mesh.curved()) fail("curved_quality: the mesh has no second-order cells");
  const std::vector<double> x = curved_point_coordinates(mesh);
  const PetscInt n = mesh.num_cells();
  std::vector<CurvedScaledJacobian> q(n);
#pragma omp parallel for schedule(dynamic, 64)
  for (PetscInt c = 0; c < n; ++c) q[c] = curved_cell_quality(mesh, x, c);

  CurvedQualitySummary s;
  std::array<std::int64_t, kCurvedTypes.size()> counts{};
  for (CurvedType t : mesh.high_order.types) ++counts[static_cast<int>(t)];
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
    sj.mean += cell.upper / static_cast<double>(n);
    s.scaled_jacobian_lower_bound = std::min(s.scaled_jacobian_lower_bound, cell.lower);
  }
  s.not_valid = s.invalid + s.undecided;
  return s;
}

}  // namespace neomesh
