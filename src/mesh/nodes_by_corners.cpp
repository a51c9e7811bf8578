#include "mesh/nodes_by_corners.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace neomesh {

NodesByCorners::Key NodesByCorners::key(std::span<const PetscInt> corners) {
  Key key;
  if (corners.size() > key.size()) fail("internal error: a face of {} corners", corners.size());
  key.fill(-1);
  std::copy(corners.begin(), corners.end(), key.begin());
  sort_facet_key(key, static_cast<int>(corners.size()));
  return key;
}

PetscInt NodesByCorners::find(std::span<const PetscInt> corners) const {
  const auto it = node_.find(key(corners));
  return it == node_.end() ? -1 : it->second;
}

PetscInt NodesByCorners::add(std::span<const PetscInt> corners, PetscInt node) {
  return node_.emplace(key(corners), node).first->second;
}

void NodesByCorners::add_cell(CurvedType type, const PetscInt* points) {
  const CurvedFacts& f = facts(type);
  // Gmsh's order: the corners, a node per edge of f.edges, then per face of f.faces.
  const PetscInt* node = points + num_vertices(f.linear);
  for (const CurvedEdge& e : f.edges) add(std::array{points[e[0]], points[e[1]]}, *node++);
  for (const CurvedFace& q : f.faces)
    add(std::array{points[q[0]], points[q[1]], points[q[2]], points[q[3]]}, *node++);
}

}  // namespace neomesh
