#include "mesh/raise_order.hpp"

#include <algorithm>
#include <array>
#include <map>

#include "core/error.hpp"

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
  std::map<std::array<PetscInt, 2>, PetscInt> edge_node;
  std::map<std::array<PetscInt, 4>, PetscInt> face_node;
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
    for (const CurvedEdge& e : f.edges) {
      std::array<PetscInt, 2> key = {p[e[0]], p[e[1]]};
      std::sort(key.begin(), key.end());
      auto [it, added] = edge_node.try_emplace(key, -1);
      if (added) it->second = add_node(p.data(), e);
      nodes.push_back(it->second);
    }
    for (const CurvedFace& face : f.faces) {
      std::array<PetscInt, 4> key = {p[face[0]], p[face[1]], p[face[2]], p[face[3]]};
      std::sort(key.begin(), key.end());
      auto [it, added] = face_node.try_emplace(key, -1);
      if (added) it->second = add_node(p.data(), face);
      nodes.push_back(it->second);
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
