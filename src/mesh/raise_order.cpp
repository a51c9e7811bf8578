#include "mesh/raise_order.hpp"

#include <array>

#include "core/error.hpp"
#include "mesh/nodes_by_corners.hpp"

namespace neomesh {

std::optional<CurvedType> raised_type(CellType linear) {
  switch (linear) {
    case CellType::Triangle:
      return CurvedType::Triangle6;
    case CellType::Quadrilateral:
      return CurvedType::Quadrilateral9;
    case CellType::Tetrahedron:
      return CurvedType::Tetrahedron10;
    case CellType::Hexahedron:
      return CurvedType::Hexahedron27;
    case CellType::Wedge:
      return CurvedType::Wedge18;
    default:
      return std::nullopt;
  }
}

void raise_to_second_order(InputMesh& mesh) {
  if (mesh.curved()) fail("the mesh is already of second order");
  if (mesh.surface) fail("raising a surface mesh to second order is not supported");
  for (CellType t : mesh.cell_types)
    if (!raised_type(t))
      fail("{} cannot be raised to second order: neomesh has no curved {} yet", facts(t).plural,
           name(t));
  const std::vector<double> xyz = coordinates_in_space(mesh);
  HighOrderNodes& h = mesh.high_order;
  // A node at the mean of `corners` (Gmsh corner positions p): the straight map's image of an
  // edge's midpoint, and the multilinear map's of a quadrilateral's centre or a hexahedron's.
  const auto add_node = [&](const PetscInt* p, const auto& corners) {
    const PetscInt node = h.num_nodes();
    for (int j = 0; j < 3; ++j) {
      double sum = 0.0;
      for (auto i : corners) sum += xyz[3 * p[i] + j];
      h.xyz.push_back(sum / static_cast<double>(corners.size()));
    }
    return node;
  };
  NodesByCorners shared;  // the edges' and faces' nodes made so far
  std::array<PetscInt, kMaxCurvedNodes> p{};
  std::vector<PetscInt> nodes;
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    const CellType linear = mesh.cell_types[c];
    const CurvedType type = *raised_type(linear);
    const CurvedFacts& f = facts(type);
    const int corners = num_vertices(linear);
    const PetscInt* v = mesh.cell_vertices.data() + mesh.cell_offsets[c];
    for (int i = 0; i < corners; ++i) p[i] = v[facts(linear).gmsh_order[i]];
    nodes.clear();
    // An edge's or face's node is made by the first cell that reaches it: the next number.
    for (const CurvedEdge& e : f.edges) {
      const PetscInt node = shared.add(std::array{p[e[0]], p[e[1]]}, h.num_nodes());
      nodes.push_back(node == h.num_nodes() ? add_node(p.data(), e) : node);
    }
    for (const CurvedFace& q : f.faces) {
      const PetscInt node =
          shared.add(std::array{p[q[0]], p[q[1]], p[q[2]], p[q[3]]}, h.num_nodes());
      nodes.push_back(node == h.num_nodes() ? add_node(p.data(), q) : node);
    }
    if (corners + static_cast<int>(f.edges.size() + f.faces.size()) < f.nodes) {
      std::vector<int> all(corners);
      for (int i = 0; i < corners; ++i) all[i] = i;
      nodes.push_back(add_node(p.data(), all));  // the centre
    }
    h.add(type, nodes.data());
  }
}

}  // namespace neomesh
