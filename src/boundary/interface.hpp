// Fitting the mesh to an interface, the zero set of a level set φ (`adapt --fit`,
// docs/adaptivity.md). The interface is a closed chain of mesh edges (2D) or surface of mesh
// faces (3D): the facets between the cells inside (φ < 0 at the centroid) and the others,
// after a clean-up that keeps the fit possible. Its vertices slide on levels of φ the way
// boundary vertices slide on their geometry (sliding_vertices.hpp): vertex i on {φ = c_i},
// with c_i lowered from φ(x_i) to 0 in stages, so that the constraint is exact at every
// stage and no vertex jumps more than a fraction of its distance to the zero set.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "boundary/shape.hpp"
#include "energy/sliding_vertices.hpp"
#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

struct Interface {
  std::vector<std::uint8_t> inside;  // per local cell, after the clean-up
  // The facets between inside and outside cells whose inside cell is local (so each facet is
  // listed once over all processes), as local vertices (CSR) in the cyclic order of the
  // facet's boundary.
  std::vector<PetscInt> offsets = {0};
  std::vector<PetscInt> facet_vertices;
  // The local vertices on the interface, ascending: those of this process' facets and those
  // other processes' facets share with its cells.
  std::vector<PetscInt> vertices;
  int cells_flipped = 0;  // by the clean-up, summed over all processes

  PetscInt num_facets() const { return static_cast<PetscInt>(offsets.size()) - 1; }
};

// The interface at the coordinates `coords` (the view's local vertex order). The clean-up
// changes the side of a cell that would end with two facets on the zero set in a way no valid
// cell of its type can take: a triangle or tetrahedron with two interface facets (all its
// vertices would lie on the zero set), a quadrilateral or hexahedron with two opposite ones,
// or with adjacent ones where the zero set bends away from it (its corner between them would
// open beyond 180°). Throws Error if φ has the same sign at every centroid or the interface
// touches the domain's boundary. Collective: the sides of cells across the partition are
// exchanged (PartitionFacets); `vertices` holds every local vertex on the interface, ghosts
// included, and each facet is listed once over all processes, by its inside cell's.
Interface find_interface(const MeshView& view, const DofMap& dofs, std::span<const double> coords,
                         const LevelSetFunction& phi);

// The interface vertices held on levels of φ: vertex i on {φ = (1 − s) c_i}, where c_i is
// φ at its position when the constraint was made and s the stage (0: where they are; 1: the
// zero set). Keeps references to its arguments.
class InterfaceConstraint {
 public:
  InterfaceConstraint(const MeshView& view, const DofMap& dofs, const LevelSetFunction& phi,
                      std::vector<PetscInt> vertices, Vec x);

  void set_stage(double s);
  double stage() const { return stage_; }
  // Moves the owned interface vertices of the global Vec x onto their levels.
  void project(Vec x) const;
  // The largest |φ| / |∇φ| (the distance to the zero set, to first order) over the interface
  // vertices of x. Collective.
  double max_distance(Vec x) const;
  const std::vector<PetscInt>& vertices() const { return vertices_; }
  // For the Functional; keeps `constraint` alive.
  friend SlidingVertices sliding_vertices(std::shared_ptr<const InterfaceConstraint> constraint);

 private:
  void tangent_spaces(std::span<const double> x, std::span<double> out) const;
  Point point(const double* at) const;

  const MeshView& view_;
  const DofMap& dofs_;
  const LevelSetFunction& phi_;
  std::vector<PetscInt> vertices_;
  std::vector<double> start_level_;
  double stage_ = 0.0;
};

// The vertices of `a` and `b` (disjoint sets) sliding together.
SlidingVertices join(SlidingVertices a, SlidingVertices b);

}  // namespace neomesh
