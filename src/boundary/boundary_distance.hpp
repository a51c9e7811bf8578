// How far a mesh's boundary vertices are from another mesh's boundary: what `smooth`, `adapt`
// and `quality --reference` report to show that sliding kept the domain (docs/boundary.md).
#pragma once

#include <memory>
#include <span>

#include <mpi.h>

#include "boundary/shape.hpp"
#include "mesh/boundary_surface.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

class SimplexSet;

// Distances to the facets of a boundary surface (closest points through a grid).
class DistanceToBoundary {
 public:
  explicit DistanceToBoundary(const BoundarySurface& surface);
  ~DistanceToBoundary();
  double operator()(const Point& p) const;

 private:
  std::unique_ptr<SimplexSet> facets_;
};

// The largest distance of an owned boundary vertex of `view` (at `coords`, dim values per local
// vertex) from `reference`, over all ranks of `comm`. Collective.
double max_boundary_distance(const MeshView& view, std::span<const double> coords,
                             const DistanceToBoundary& reference, MPI_Comm comm);

}  // namespace neomesh
