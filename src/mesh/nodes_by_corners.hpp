// The high-order node on an edge or face of a curved mesh, found by the entity's corners (as
// points, input numbers): every cell that holds the entity reaches the same node, whatever order
// it lists the corners in. So raise_to_second_order shares the nodes it makes, CurvedFacets finds
// those of the group facets, and the node mesh (geometry/node_mesh.hpp) those of its facets and of
// the serendipity cells' virtual face centres.
#pragma once

#include <array>
#include <map>
#include <span>

#include <petscsys.h>
#include "mesh/curved_type.hpp"

namespace neomesh {

class NodesByCorners {
 public:
  // The node of the entity with these corners (2 to 8, in any order); -1 if none is known.
  PetscInt find(std::span<const PetscInt> corners) const;
  // Makes `node` that entity's unless it has one already; returns the entity's node.
  PetscInt add(std::span<const PetscInt> corners, PetscInt node);
  // Adds the nodes of a curved cell's edges and quadrilateral faces; `points` are its points in
  // Gmsh order (curved_cell_points).
  void add_cell(CurvedType type, const PetscInt* points);
  bool empty() const { return node_.empty(); }

 private:
  using Key = std::array<PetscInt, 8>;  // the corners sorted, then -1
  static Key key(std::span<const PetscInt> corners);
  std::map<Key, PetscInt> node_;
};

}  // namespace neomesh
