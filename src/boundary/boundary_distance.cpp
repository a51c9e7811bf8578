#include "boundary/boundary_distance.hpp"

#include <algorithm>

#include "boundary/discrete_geometry.hpp"

namespace neomesh {

DistanceToBoundary::DistanceToBoundary(const BoundarySurface& s) {
  std::vector<Point> points(s.num_vertices(), Point::Zero());
  for (PetscInt v = 0; v < s.num_vertices(); ++v)
    for (int j = 0; j < s.dim; ++j) points[v][j] = s.coords[v * s.dim + j];
  std::vector<std::array<int, 3>> simplices;
  for (PetscInt f = 0; f < s.num_facets(); ++f) {
    const PetscInt* v = s.facet_vertices.data() + s.facet_offsets[f];
    const PetscInt n = s.facet_offsets[f + 1] - s.facet_offsets[f];
    if (n == 2)
      simplices.push_back({static_cast<int>(v[0]), static_cast<int>(v[1]), 0});
    else  // a fan: quadrilateral faces in two triangles
      for (PetscInt k = 1; k + 1 < n; ++k)
        simplices.push_back(
            {static_cast<int>(v[0]), static_cast<int>(v[k]), static_cast<int>(v[k + 1])});
  }
  facets_ =
      std::make_unique<SimplexSet>(std::move(points), std::move(simplices), s.dim == 2 ? 2 : 3);
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
