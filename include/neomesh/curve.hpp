// Curving a straight mesh onto its geometry (`neomesh curve`; docs/user-guide.md, "Curved
// meshes"): raise its cells to second order and put the boundary's nodes on the exact shapes of
// their parts.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <mpi.h>

#include <neomesh/mesh.hpp>

namespace neomesh {

struct CurveOptions {
  int order = 2;  // the order to raise to: 2 is the only one there is
  // (part name, shape spec) pairs, as BoundaryOptions::shapes: boundary part `name` lies on the
  // shape, e.g. ("cylinder", "circle:0,0,0.5"). Parts attached to a FEAT3 chart lie on it
  // unless a shape names them.
  std::vector<std::pair<std::string, std::string>> shapes;
};

struct CurveSummary {
  std::int64_t vertices_on_geometry = 0;  // boundary vertices put on a shape or chart
  std::int64_t nodes_on_geometry = 0;     // second-order boundary nodes put on one
  std::int64_t nodes_straight = 0;        // those of parts without geometry: left straight
  double max_vertex_move = 0.0;           // the farthest a vertex moved onto its geometry
  double max_off_geometry = 0.0;          // the largest distance of a placed node from it
};

// Reads a straight mesh of triangles, quadrilaterals, tetrahedra or hexahedra (with a FEAT3
// mesh's chart files, as Mesh::read), raises every cell to second order (triangle6,
// quadrilateral9, tetrahedron10, hexahedron27; the vertices keep their numbers) and puts the
// boundary vertices and nodes of parts with a shape or chart on it. The interior nodes stay
// where the straight cells have them, so a cell next to a strongly bent boundary may be
// invalid: quality().curved counts them. `summary`, if given, is filled on every process.
// Throws Error in one line for a mesh already curved, wedges or pyramids, an order other than
// 2, and as Mesh::read. Collective.
Mesh curve_mesh(const std::vector<std::filesystem::path>& inputs, const CurveOptions& options,
                CurveSummary* summary = nullptr, MPI_Comm comm = MPI_COMM_WORLD);

}  // namespace neomesh
