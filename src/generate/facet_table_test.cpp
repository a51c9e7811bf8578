#include "mesh/facet_table.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "generate/generate.hpp"
#include "mesh/input_topology.hpp"
#include "mesh/plex_builder.hpp"

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

// One cell of `type` with its vertices at `coords` (canonical order).
InputMesh single_cell(CellType type, std::vector<double> coords) {
  InputMesh mesh;
  mesh.dim = dimension(type);
  mesh.coords = std::move(coords);
  PetscInt v[8];
  for (int i = 0; i < num_vertices(type); ++i) v[i] = i;
  mesh.add_cell(type, v, 0);
  return mesh;
}

// The facet table claims DMPlexInterpolate's facets and their vertex order: check it against
// PETSc for every 3D type (the cone orders of cell_order.hpp included).
TEST(FacetTable, AgreesWithDMPlexInterpolateOnEverySolidCell) {
  const std::vector<std::pair<CellType, std::vector<double>>> cells = {
      {CellType::Tetrahedron, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}},
      {CellType::Hexahedron,
       {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1}},
      {CellType::Wedge, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1}},
      {CellType::Pyramid, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0.5, 0.5, 1}}};
  for (const auto& [type, coords] : cells) {
    SCOPED_TRACE(std::string(name(type)));
    const InputMesh mesh = single_cell(type, coords);
    const FacetTable table(mesh);
    ASSERT_EQ(table.size(), facts(type).num_facets);
    OwnedDM dm = build_plex(PETSC_COMM_SELF, mesh), interpolated;
    NM_PETSC(DMPlexInterpolate(dm, interpolated.out()));
    PetscInt faces, vStart, vEnd;
    const PetscInt* cone;
    NM_PETSC(DMPlexGetConeSize(interpolated, 0, &faces));
    NM_PETSC(DMPlexGetCone(interpolated, 0, &cone));
    NM_PETSC(DMPlexGetDepthStratum(interpolated, 0, &vStart, &vEnd));
    ASSERT_EQ(faces, table.size());
    for (PetscInt k = 0; k < faces; ++k) {
      PetscInt n = 0, *closure = nullptr;
      NM_PETSC(DMPlexGetTransitiveClosure(interpolated, cone[k], PETSC_TRUE, &n, &closure));
      std::vector<PetscInt> plex;
      for (PetscInt i = 0; i < n; ++i)
        if (closure[2 * i] >= vStart && closure[2 * i] < vEnd)
          plex.push_back(closure[2 * i] - vStart);
      NM_PETSC(DMPlexRestoreTransitiveClosure(interpolated, cone[k], PETSC_TRUE, &n, &closure));
      const PetscInt f = table.find(plex.data(), static_cast<int>(plex.size()));
      ASSERT_GE(f, 0);
      PetscInt ours[4];
      ASSERT_EQ(table.vertices(f, ours), static_cast<int>(plex.size()));
      EXPECT_EQ(std::vector<PetscInt>(ours, ours + plex.size()), plex) << "facet " << k;
    }
  }
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
