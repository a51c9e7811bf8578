// What a mesh file carries besides the mesh: per-cell and per-vertex fields and named facet
// groups (Mesh::write, Optimizer::cell_fields).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace neomesh {

// A per-cell or per-vertex field written with the mesh (.vtu, .vtk; .msh keeps the mesh only).
struct Field {
  std::string name;
  // `components` values per local cell (in this process' order) or per vertex of
  // Mesh::vertex_numbers()
  std::vector<double> values;
  int components = 1;
};

// Facets (edges in 2D, faces in 3D) that an output lists as the physical group `name`
// (replacing an input group of that name): in .msh, .vtu and .vtk as facet elements, in .mesh
// as references, in .exo as a side set. On every process its own facets, each once over all
// processes.
struct FacetGroup {
  std::string name;
  std::vector<std::int64_t> offsets = {0};  // facet f is vertices[offsets[f], offsets[f + 1])
  std::vector<std::int64_t> vertices;       // vertex numbers (vertex_numbers()), cyclic order
};

}  // namespace neomesh
