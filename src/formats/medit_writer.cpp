#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/ostream.h>

#include "core/error.hpp"
#include "formats/mesh_writers.hpp"
#include "mesh/cell_order.hpp"

namespace neomesh {

namespace {

// Medit's section of each cell type (the order of CellType) and of boundary facets by their
// number of vertices.
constexpr const char* kCellSection[kNumCellTypes] = {"Triangles", "Quadrilaterals", "Tetrahedra",
                                                     "Hexahedra", "Prisms",         "Pyramids"};
// (`points`: a curved mesh's facets have their other nodes too)
const char* facet_section(int dim, int points) {
  if (dim == 2) return points == 2 ? "Edges" : "EdgesP2";
  return points == 3 ? "Triangles" : points == 4 ? "Quadrilaterals" : "TrianglesP2";
}

// The vertices of one element, 1-based, and its reference.
void write_element(std::ostream& f, const PetscInt* v, int n, int ref) {
  for (int i = 0; i < n; ++i) fmt::print(f, "{} ", v[i] + 1);
  fmt::print(f, "{}\n", ref);
}

}  // namespace

void require_medit_curved_types(const InputMesh& mesh, const std::string& target) {
  for (const CurvedType t : mesh.high_order.types)
    if (t != CurvedType::Triangle6 && t != CurvedType::Tetrahedron10)
      fail(
          "cannot write {}: it has {} cells, and of second-order cells Medit files hold only "
          "TrianglesP2 and TetrahedraP2 in a node order their readers agree on; write it to .msh, "
          ".vtu, .vtk, .exo or .cgns",
          target, name(t));
}

void write_medit(const GatheredMesh& g, std::ostream& f) {
  const InputMesh& mesh = g.mesh;
  // A 2D mesh in the plane z = 0 is written as Medit's 2D mesh (what MMG2D reads); one in
  // another plane keeps its third coordinate.
  const int dimension = mesh.dim == 2 && !mesh.plane && !mesh.surface ? 2 : 3;
  fmt::print(f, "MeshVersionFormatted 2\n\nDimension {}\n\n", dimension);
  const std::vector<double> xyz = points_in_space(mesh);
  // Vertex references: the point data "medit:ref" (as the reader and meshio name them), or 0.
  const DataArray* refs = nullptr;
  for (const DataArray& a : mesh.point_data)
    if (a.name == "medit:ref" && a.components == 1) refs = &a;
  fmt::print(f, "Vertices\n{}\n", mesh.num_points());
  for (PetscInt v = 0; v < mesh.num_points(); ++v) {
    for (int i = 0; i < dimension; ++i) fmt::print(f, "{:.17g} ", xyz[3 * v + i]);
    const double ref = refs && v < mesh.num_vertices() ? refs->values[v] : 0.0;
    fmt::print(f, "{}\n", std::abs(ref) < 0x1p62 ? static_cast<long long>(ref) : 0LL);
  }

  for (CellType t : kAllCellTypes) {
    const auto count = std::count(mesh.cell_types.begin(), mesh.cell_types.end(), t);
    if (count == 0) continue;
    if (mesh.curved()) {  // TrianglesP2 or TetrahedraP2 (mesh_io refuses the others)
      fmt::print(f, "\n{}P2\n{}\n", kCellSection[static_cast<int>(t)], count);
      for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
        PetscInt points[kMaxCurvedNodes], medit[kMaxCurvedNodes];
        const int n = curved_cell_points(mesh, c, points);
        for (int i = 0; i < n; ++i) medit[i] = points[facts(mesh.high_order.types[c]).vtk_order[i]];
        write_element(f, medit, n, mesh.cell_tags[c]);
      }
      continue;
    }
    fmt::print(f, "\n{}\n{}\n", kCellSection[static_cast<int>(t)], count);
    for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
      if (mesh.cell_types[c] != t) continue;
      const PetscInt* cell = mesh.cell_vertices.data() + mesh.cell_offsets[c];
      PetscInt medit[8];
      for (int i = 0; i < num_vertices(t); ++i) medit[i] = cell[gmsh_from_canonical(t)[i]];
      write_element(f, medit, num_vertices(t), mesh.cell_tags[c]);
    }
  }

  // Boundary facets of groups, a section per number of points, in the order the sections'
  // first facets come in (a file read keeps its order).
  const TaggedEntities& facets = mesh.facets;
  const CurvedFacets curved(mesh);
  std::vector<std::vector<PetscInt>> points(facets.size());
  std::vector<std::size_t> sizes;
  for (PetscInt k = 0; k < facets.size(); ++k) {
    points[k].resize(9);
    points[k].resize(curved.points(k, points[k].data()));
    if (std::find(sizes.begin(), sizes.end(), points[k].size()) == sizes.end())
      sizes.push_back(points[k].size());
  }
  for (std::size_t n : sizes) {
    const auto count =
        std::count_if(points.begin(), points.end(), [&](const auto& p) { return p.size() == n; });
    fmt::print(f, "\n{}\n{}\n", facet_section(mesh.dim, static_cast<int>(n)), count);
    for (PetscInt k = 0; k < facets.size(); ++k)
      if (points[k].size() == n)
        write_element(f, points[k].data(), static_cast<int>(n), facets.tags[k]);
  }
  fmt::print(f, "\nEnd\n");
}

}  // namespace neomesh
