#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/ostream.h>

#include "formats/mesh_writers.hpp"
#include "mesh/cell_order.hpp"

namespace neomesh {

namespace {

// Medit's section of each cell type (the order of CellType) and of boundary facets by their
// number of vertices.
constexpr const char* kCellSection[kNumCellTypes] = {"Triangles", "Quadrilaterals", "Tetrahedra",
                                                     "Hexahedra", "Prisms",         "Pyramids"};
const char* facet_section(PetscInt vertices) {
  return vertices == 2 ? "Edges" : vertices == 3 ? "Triangles" : "Quadrilaterals";
}

// The vertices of one element, 1-based, and its reference.
void write_element(std::ostream& f, const PetscInt* v, int n, int ref) {
  for (int i = 0; i < n; ++i) fmt::print(f, "{} ", v[i] + 1);
  fmt::print(f, "{}\n", ref);
}

}  // namespace

void write_medit(const GatheredMesh& g, std::ostream& f) {
  const InputMesh& mesh = g.mesh;
  // A 2D mesh in the plane z = 0 is written as Medit's 2D mesh (what MMG2D reads); one in
  // another plane keeps its third coordinate.
  const int dimension = mesh.dim == 2 && !mesh.plane && !mesh.surface ? 2 : 3;
  fmt::print(f, "MeshVersionFormatted 2\n\nDimension {}\n\n", dimension);
  const std::vector<double> xyz = coordinates_in_space(mesh);
  // Vertex references: the point data "medit:ref" (as the reader and meshio name them), or 0.
  const DataArray* refs = nullptr;
  for (const DataArray& a : mesh.point_data)
    if (a.name == "medit:ref" && a.components == 1) refs = &a;
  fmt::print(f, "Vertices\n{}\n", mesh.num_vertices());
  for (PetscInt v = 0; v < mesh.num_vertices(); ++v) {
    for (int i = 0; i < dimension; ++i) fmt::print(f, "{:.17g} ", xyz[3 * v + i]);
    const double ref = refs ? refs->values[v] : 0.0;
    fmt::print(f, "{}\n", std::abs(ref) < 0x1p62 ? static_cast<long long>(ref) : 0LL);
  }

  for (CellType t : kAllCellTypes) {
    const auto count = std::count(mesh.cell_types.begin(), mesh.cell_types.end(), t);
    if (count == 0) continue;
    fmt::print(f, "\n{}\n{}\n", kCellSection[static_cast<int>(t)], count);
    for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
      if (mesh.cell_types[c] != t) continue;
      const PetscInt* cell = mesh.cell_vertices.data() + mesh.cell_offsets[c];
      PetscInt medit[8];
      for (int i = 0; i < num_vertices(t); ++i) medit[i] = cell[gmsh_from_canonical(t)[i]];
      write_element(f, medit, num_vertices(t), mesh.cell_tags[c]);
    }
  }

  // Boundary facets of groups, a section per number of vertices, in the order the sections'
  // first facets come in (a file read keeps its order).
  const TaggedEntities& facets = mesh.facets;
  const auto size = [&](PetscInt k) { return facets.offsets[k + 1] - facets.offsets[k]; };
  std::vector<PetscInt> sizes;
  for (PetscInt k = 0; k < facets.size(); ++k)
    if (std::find(sizes.begin(), sizes.end(), size(k)) == sizes.end()) sizes.push_back(size(k));
  for (PetscInt n : sizes) {
    PetscInt count = 0;
    for (PetscInt k = 0; k < facets.size(); ++k) count += size(k) == n;
    fmt::print(f, "\n{}\n{}\n", facet_section(n), count);
    for (PetscInt k = 0; k < facets.size(); ++k)
      if (size(k) == n)
        write_element(f, facets.vertices.data() + facets.offsets[k], static_cast<int>(n),
                      facets.tags[k]);
  }
  fmt::print(f, "\nEnd\n");
}

}  // namespace neomesh
