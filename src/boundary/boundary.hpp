// What the boundary vertices may do during the optimization (docs/boundary.md, docs/method.md §7).
//
// Fixed (the thesis' H¹₀ setting): every boundary vertex stays where it is.
// Slide: boundary vertices move along the boundary of the input domain. The boundary is split
// at its features (features.hpp) into patches and ridges; corners stay put, a ridge vertex
// slides along its ridge, every other boundary vertex within its patch. Each patch slides on
// the most exact geometry known for it:
//   1. a shape named for its boundary part (`--shape part=circle:0,0,0.5`, shape.hpp);
//   2. the FEAT3 chart its mesh part is attached to;
//   3. the plane it lies in, if it is flat;
//   4. otherwise the input's own facets (discrete_geometry.hpp); a surface mesh's patch, a
//      Phong tessellation through their vertices (BoundaryOptions::surface_geometry).
// A ridge between two patches with analytic geometry follows their exact intersection,
// otherwise the input's ridge edges. Coordinates that stay exact by themselves — all of a
// corner's, the normal one of a vertex in an axis-aligned plane, the two others of one on an
// axis-aligned line — are fixed dofs; the other sliding vertices move in their tangent spaces
// and are projected back onto their geometry after each step (sliding_vertices.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <neomesh/options.hpp>
#include <neomesh/result.hpp>

#include "boundary/shape.hpp"
#include "energy/functional.hpp"
#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

class Boundary {
 public:
  // Classifies the boundary and builds its geometry; throws Error for a shape naming an
  // unknown part, or not passing through its part's vertices (naming the vertex). The view
  // must outlive the Boundary. Collective. `sub_facets`: the view's boundary facets are the
  // straight sub-facets of second-order faces (geometry/node_mesh.hpp); where a curved face folds
  // at a corner, one of them lies folded over the others, and is seen with its normal reversed,
  // so that its edges are no ridges and the nodes around it still slide on their surface.
  Boundary(const MeshView& view, const DofMap& dofs, const BoundaryOptions& options,
           bool sub_facets = false);
  ~Boundary();
  Boundary(const Boundary&) = delete;
  Boundary& operator=(const Boundary&) = delete;

  // False once the surface `view`'s vertices slide on is no longer the one this Boundary was
  // built on (Mesh::set_coordinates moved a surface mesh's surface): build a new Boundary.
  bool slides_on_surface_of(const MeshView& view) const;
  // Per local dof: 1 if that coordinate never moves.
  FixedDofs fixed_dofs() const;
  // The vertices that slide in tangent spaces, for the Functional (refers to this Boundary,
  // which must outlive it).
  SlidingVertices sliding_vertices() const;
  // Moves the owned sliding vertices of the global Vec x onto their geometry.
  void project(Vec x) const;
  // Per local vertex, the geometry it slides on: an index that names the same patch or ridge
  // on every rank, or -1 for a vertex that does not slide (interior, fixed, or in an
  // axis-aligned plane or line, which its fixed dofs keep it on).
  std::vector<int> sliding_geometry() const;
  // The point of geometry g (an index from sliding_geometry) closest to p.
  Point closest_point(int g, const Point& p) const;
  // Moves the owned boundary vertices of parts with a FEAT3 chart (corners too) onto it, as
  // FEAT3 does when it loads a mesh; summary() counts them. The constructor throws Error for a
  // vertex more than a few local mesh sizes off its chart (docs/boundary.md).
  void place_on_charts(Vec x) const;
  const BoundarySummary& summary() const;

  // The largest distance of a boundary vertex of x (global Vec) from the input's boundary,
  // over all ranks. Collective.
  double max_distance_from_input(Vec x) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace neomesh
