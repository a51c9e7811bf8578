#include "boundary/boundary_distance.hpp"

#include <algorithm>
#include <numeric>

#include "boundary/discrete_geometry.hpp"

namespace neomesh {

DistanceToBoundary::DistanceToBoundary(const BoundarySurface& s) {
  std::vector<PetscInt> all(s.num_facets());
  std::iota(all.begin(), all.end(), PetscInt{0});
  FacetSimplices facets = facet_simplices(s, all);
  facets_ = std::make_unique<SimplexSet>(std::move(facets.points), std::move(facets.simplices),
                                         facets.corners);
}

DistanceToBoundary::~DistanceToBoundary() = default;

double DistanceToBoundary::operator()(const Point& p) const {
  return facets_->closest(p).distance;
}

double max_boundary_distance(const MeshView& view, std::span<const double> coords,
                             const DistanceToBoundary& reference, MPI_Comm comm) {
  double largest = 0.0;
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    if (!view.on_boundary[v] || !view.owned[v]) continue;
    Point p = Point::Zero();
    for (int j = 0; j < view.dim; ++j) p[j] = coords[v * view.dim + j];
    largest = std::max(largest, reference(p));
  }
  MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, comm);
  return largest;
}

}  // namespace neomesh
