#include "mesh/facet_table.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "mesh/generate.hpp"
#include "mesh/input_topology.hpp"

namespace neomesh {
namespace {

// Two quads side by side: vertices 0 1 2 along y = 0, 3 4 5 along y = 1 (tensor order).
InputMesh two_quads() {
  MeshData data;
  data.dim = 2;
  data.cell_type = CellType::Quadrilateral;
  data.coords = {0, 0, 1, 0, 2, 0, 0, 1, 1, 1, 2, 1};
  data.cells = {0, 1, 3, 4, 1, 2, 4, 5};
  data.boundary_parts = {{"left", 1, {0, 3}, {}}, {"corner", 2, {2}, {}}};
  return input_from_data(data);
}

TEST(FacetTable, TwoQuadsHaveSevenEdgesOneInterior) {
  const InputMesh mesh = two_quads();
  const FacetTable table(mesh);
  EXPECT_EQ(table.size(), 7);
  const PetscInt shared[2] = {4, 1};
  const PetscInt f = table.find(shared, 2);
  ASSERT_GE(f, 0);
  EXPECT_FALSE(table.on_boundary(f));
  // DMPlex lists the first quad counter-clockwise (0 1 4 3): its edge 1→4 keeps that order.
  PetscInt v[4];
  ASSERT_EQ(table.vertices(f, v), 2);
  EXPECT_EQ(v[0], 1);
  EXPECT_EQ(v[1], 4);
  const PetscInt diagonal[2] = {0, 4};
  EXPECT_EQ(table.find(diagonal, 2), -1);
}

TEST(FacetTable, CellGraphLinksCellsAcrossFacets) {
  const InputMesh mesh = input_from_data(box(CellType::Hexahedron, 2));
  const CellGraph graph = FacetTable(mesh).cell_graph();
  ASSERT_EQ(graph.offsets.size(), 9u);
  for (PetscInt c = 0; c < 8; ++c) {
    EXPECT_EQ(graph.offsets[c + 1] - graph.offsets[c], 3);  // every cube of 2³ has 3 neighbours
    EXPECT_TRUE(std::is_sorted(graph.neighbours.begin() + graph.offsets[c],
                               graph.neighbours.begin() + graph.offsets[c + 1]));
  }
}

TEST(FacetTable, SixTetsOfACubeHaveTwelveBoundaryTriangles) {
  const InputMesh mesh = input_from_data(box(CellType::Tetrahedron, 1));
  const FacetTable table(mesh);
  PetscInt boundary = 0;
  for (PetscInt f = 0; f < table.size(); ++f) boundary += table.on_boundary(f);
  EXPECT_EQ(boundary, 12);
  EXPECT_EQ(table.size(), 18);
}

TEST(InputTopology, VertexSetsBecomeFacetsAndIsolatedPoints) {
  InputMesh mesh = two_quads();
  const FacetTable table(mesh);
  const InputTopology t = input_topology(mesh, table, "two quads");
  ASSERT_EQ(t.facets.size(), 1);  // "left": the edge 0–3
  EXPECT_EQ(t.facets.tags[0], 1);
  ASSERT_EQ(t.points.size(), 1);  // "corner" has no edge of its own
  EXPECT_EQ(t.points.vertices[0], 2);
  ASSERT_EQ(mesh.groups.size(), 3u);  // the point group comes first: (0, 2), (1, 1), (1, 2)
  EXPECT_EQ(mesh.groups[0].dim, 0);
  EXPECT_EQ(t.boundary_part[2], 0);
  EXPECT_EQ(t.boundary_part[3], 1);
  EXPECT_EQ(t.part_count[0], 1);
  EXPECT_EQ(t.on_boundary, std::vector<std::uint8_t>(6, 1));
}

TEST(InputTopology, FacetThatIsNoFaceOfTheCellsNamesTheSource) {
  InputMesh mesh = two_quads();
  const PetscInt diagonal[2] = {0, 4};
  mesh.facets.add(diagonal, 2, 7);
  const FacetTable table(mesh);
  try {
    input_topology(mesh, table, "in.msh");
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("in.msh: has lower-dimensional elements"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace neomesh
