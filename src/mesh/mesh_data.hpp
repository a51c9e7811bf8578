// MeshData: a whole mesh as plain arrays on one process. The generators and the FEAT3
// reader produce it; PlexMesh::from_data turns it into a (distributable) DMPlex.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mesh/cell_type.hpp"
#include "mesh/chart.hpp"

namespace neomesh {

// A named set of vertices, usually one side of the domain's boundary (FEAT3 MeshPart,
// a generator's "left"/"bottom"/"circle"). Written to Gmsh as a physical group of the
// boundary facets whose vertices all lie in the set.
struct VertexSet {
  std::string name;
  int tag = 0;  // Gmsh physical tag; unique among the mesh's sets
  std::vector<std::int64_t> vertices;
  std::string chart;  // name of the Chart the set lies on (FEAT3), or empty
};

struct MeshData {
  int dim = 2;
  CellType cell_type = CellType::Quadrilateral;
  std::vector<double> coords;       // vertex-major, `dim` values per vertex
  std::vector<std::int64_t> cells;  // num_vertices(cell_type) per cell, canonical order
  std::vector<VertexSet> boundary_parts;
  std::vector<Chart> charts;  // FEAT3 <Chart> blocks, referred to by VertexSet::chart

  std::int64_t num_vertices() const { return static_cast<std::int64_t>(coords.size()) / dim; }
  std::int64_t num_cells() const {
    return static_cast<std::int64_t>(cells.size()) / neomesh::num_vertices(cell_type);
  }
};

}  // namespace neomesh
