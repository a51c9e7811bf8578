#include "formats/medit_reader.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"
#include "formats/mesh_test_util.hpp"
#include "formats/mesh_writers.hpp"

namespace neomesh {
namespace {

std::string error_reading(const std::string& text) {
  return testing::read_error(text, "in.mesh", [](const auto& path) { read_medit(path); });
}

::testing::AssertionResult has(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' lacks '" << part << "'";
}

InputMesh read_text(const std::string& text, const std::string& name) {
  const auto path = testing::scratch_dir("ReadMedit") / name;
  std::ofstream(path) << text;
  return read_medit(path);
}

// A unit cube of a hexahedron (domain 3) and a prism on its top (domain 4), the bottom face and
// the prism's top in boundary groups 1 and 2, an unreferenced face, corners and a comment.
const std::string kHexPrism = R"(MeshVersionFormatted 2
# written by hand
Dimension
3
Vertices
12
0 0 0 7
1 0 0 7
1 1 0 7
0 1 0 7
0 0 1 0
1 0 1 0
1 1 1 0
0 1 1 0
0 0 2 0
1 0 2 0
0 1 2 0
5 5 5 0
Hexahedra
1
1 2 3 4 5 6 7 8 3
Prisms
1
5 6 8 9 10 11 4
Quadrilaterals
2
1 4 3 2 1
1 2 6 5 0
Triangles
1
9 10 11 2
Corners
2 1 2
End
)";

TEST(ReadMedit, ReadsCellsWithTheirDomainsAndReferencedBoundaryFacets) {
  const InputMesh mesh = read_text(kHexPrism, "hex_prism.mesh");
  ASSERT_EQ(mesh.dim, 3);
  EXPECT_EQ(mesh.cell_types, (std::vector<CellType>{CellType::Hexahedron, CellType::Wedge}));
  EXPECT_EQ(mesh.num_vertices(), 11);  // vertex 12 is used by no element
  // The hexahedron's Gmsh order 1 2 3 4 5 6 7 8 is canonical 0 1 3 2 4 5 7 6.
  EXPECT_EQ(std::vector<PetscInt>(mesh.cell_vertices.begin(), mesh.cell_vertices.begin() + 8),
            (std::vector<PetscInt>{0, 1, 3, 2, 4, 5, 7, 6}));
  EXPECT_EQ(mesh.cell_tags, (std::vector<int>{3, 4}));
  ASSERT_EQ(mesh.facets.size(), 2);  // the unreferenced quadrilateral is not kept
  EXPECT_EQ(mesh.facets.tags, (std::vector<int>{1, 2}));
  EXPECT_EQ(mesh.facets.vertices,
            (std::vector<PetscInt>{0, 3, 2, 1, 8, 9, 10}));  // quadrilaterals, then triangles
  ASSERT_EQ(mesh.groups.size(), 4u);
  EXPECT_EQ(mesh.groups[0].dim, 2);
  EXPECT_EQ(mesh.groups[3].dim, 3);
  EXPECT_EQ(mesh.groups[3].tag, 4);
}

TEST(WriteMedit, WritesWhatReadsBackTheSame) {
  const InputMesh mesh = read_text(kHexPrism, "hex_prism.mesh");
  std::ostringstream out;
  write_medit(GatheredMesh{mesh, {}, true}, out);
  const InputMesh again = read_text(out.str(), "again.mesh");
  EXPECT_EQ(again.coords, mesh.coords);
  EXPECT_EQ(again.cell_types, mesh.cell_types);
  EXPECT_EQ(again.cell_vertices, mesh.cell_vertices);
  EXPECT_EQ(again.cell_tags, mesh.cell_tags);
  EXPECT_EQ(again.facets.vertices, mesh.facets.vertices);
  EXPECT_EQ(again.facets.tags, mesh.facets.tags);
  ASSERT_EQ(again.groups.size(), mesh.groups.size());
}

TEST(ReadMedit, Reads2DMeshesWithEdgesAsTheirBoundary) {
  const InputMesh mesh = read_text(
      "MeshVersionFormatted 1\nDimension 2\nVertices\n4\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
      "Triangles\n2\n1 2 3 5\n1 3 4 5\nEdges\n2\n1 2 9\n2 3 0\nEnd\n",
      "square.mesh");
  ASSERT_EQ(mesh.dim, 2);
  EXPECT_EQ(mesh.num_cells(), 2);
  EXPECT_EQ(mesh.coords, (std::vector<double>{0, 0, 1, 0, 1, 1, 0, 1}));
  EXPECT_EQ(mesh.facets.tags, std::vector<int>{9});
  std::ostringstream out;
  write_medit(GatheredMesh{mesh, {}, true}, out);
  EXPECT_TRUE(has(out.str(), "Dimension 2\n"));
  EXPECT_TRUE(has(out.str(), "Edges\n1\n1 2 9\n"));
}

TEST(ReadMedit, NamesTheLineOfAnError) {
  EXPECT_TRUE(has(error_reading("solid x\n"),
                  "in.mesh:1: not a valid Medit file (it does not start with "
                  "MeshVersionFormatted, but 'solid')"));
  EXPECT_TRUE(has(error_reading("MeshVersionFormatted 2\nDimension 3\nVertices\n2\n0 0 0 0\n"),
                  "in.mesh:4: not a valid Medit file (truncated: the file ends inside Vertices, "
                  "which announces 2 entries)"));
  EXPECT_TRUE(has(error_reading("MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 0 x 0\n"),
                  "in.mesh:5: not a valid Medit file (expected a coordinate in Vertices, found "
                  "'x')"));
  EXPECT_TRUE(has(error_reading("MeshVersionFormatted 2\nDimension 3\nBogus 3\n"),
                  "in.mesh:3: not a valid Medit file (unknown keyword 'Bogus')"));
  EXPECT_TRUE(has(error_reading("MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 0 0 0\n"
                                "Triangles\n1\n1 2 3 0\nEnd\n"),
                  "in.mesh: Triangles 1 refers to vertex 2, which is out of range (1..1)"));
  std::string repeated = kHexPrism;
  repeated.replace(repeated.find("5 6 8 9 10 11 4"), 15, "5 6 8 9 10 10 4");
  EXPECT_TRUE(has(error_reading(repeated), "in.mesh: Prisms 1 has a repeated vertex"));
}

// A tetrahedron10 whose nodes 5..10 are its edges (0,1) (1,2) (2,0) (0,3) (1,3) (2,3), as Gmsh
// writes TetrahedraP2, with a TrianglesP2 facet.
TEST(ReadMedit, ReadsP2TetrahedraInGmshsOrderWithTheirFacets) {
  const InputMesh mesh = read_text(
      "MeshVersionFormatted 2\nDimension 3\nVertices\n10\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
      "0.5 0 0 0\n0.5 0.5 0 0\n0 0.5 0 0\n0 0 0.5 0\n0.5 0 0.5 0\n0 0.5 0.5 0\nTetrahedraP2\n1\n"
      "1 2 3 4 5 6 7 8 9 10 2\nTrianglesP2\n1\n1 3 2 7 6 5 4\nEnd\n",
      "tet10.mesh");
  ASSERT_TRUE(mesh.curved());
  EXPECT_EQ(mesh.high_order.types, std::vector{CurvedType::Tetrahedron10});
  // Gmsh's edges (0,1) (1,2) (2,0) (3,0) (3,2) (3,1): the file's nodes 5, 6, 7, 8, 10, 9.
  EXPECT_EQ(mesh.high_order.nodes, (std::vector<PetscInt>{0, 1, 2, 3, 5, 4}));
  EXPECT_EQ(mesh.high_order.xyz[3 * 5 + 1], 0.5);  // node 10 at (0, 0.5, 0.5)
  EXPECT_EQ(mesh.facets.size(), 1);
  PetscInt points[9];
  EXPECT_EQ(CurvedFacets(mesh).points(0, points), 6);
}

TEST(ReadMedit, RefusesWhatNeomeshDoesNotOptimizeInOneLine) {
  EXPECT_TRUE(has(error_reading("MeshVersionFormatted 2\nDimension 3\nVertices\n2\n0 0 0 0\n"
                                "1 0 0 0\nEdges\n1\n1 2 0\nEnd\n"),
                  "in.mesh: has no 2D or 3D cells (only 1D elements)"));
  EXPECT_TRUE(has(error_reading("MeshVersionFormatted 2\nDimension 3\nHexahedraQ2\n0\n"),
                  "in.mesh: has HexahedraQ2, whose node order Medit files do not agree on"));
  EXPECT_TRUE(has(error_reading("MeshVersionFormatted 2\nDimension 4\n"),
                  "Dimension 4; neomesh reads 2 or 3"));
}

}  // namespace
}  // namespace neomesh
