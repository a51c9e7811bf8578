#include "mesh/plex_mesh.hpp"

#include <gtest/gtest.h>

#include <numeric>

#include "core/testing/test_data.hpp"
#include "formats/mesh_io.hpp"
#include "formats/mesh_test_util.hpp"
#include "generate/generate.hpp"

namespace neomesh {
namespace {

using testing::data_path;
using testing::min_view_jacobian;

struct Expected {
  const char* file;
  int dim;
  CellType type;
  PetscInt cells, vertices;
};

class LoadGmsh : public ::testing::TestWithParam<Expected> {};

TEST_P(LoadGmsh, GivesCountsAndPositiveOrientation) {
  const Expected e = GetParam();
  PlexMesh mesh = load_mesh(data_path(e.file));
  const MeshView& view = mesh.view();
  EXPECT_EQ(mesh.dim(), e.dim);
  EXPECT_EQ(mesh.global_num_cells(), e.cells);
  EXPECT_EQ(mesh.global_num_vertices(), e.vertices);
  ASSERT_EQ(view.blocks.size(), 1u);
  EXPECT_EQ(view.blocks[0].type, e.type);
  EXPECT_EQ(view.num_cells, e.cells);
  EXPECT_EQ(view.num_vertices, e.vertices);
  EXPECT_GT(min_view_jacobian(view), 0.0);
  std::vector<PetscInt> expected(e.cells);
  std::iota(expected.begin(), expected.end(), PetscInt{0});
  EXPECT_EQ(view.global_cell, expected);  // serial: input order
}

INSTANTIATE_TEST_SUITE_P(
    AllFormats, LoadGmsh,
    ::testing::Values(Expected{"square_tri_v22.msh", 2, CellType::Triangle, 26, 20},
                      Expected{"square_tri_v22_bin.msh", 2, CellType::Triangle, 26, 20},
                      Expected{"square_tri_v41.msh", 2, CellType::Triangle, 26, 20},
                      Expected{"square_tri_v41_bin.msh", 2, CellType::Triangle, 26, 20},
                      Expected{"square_quad_v22.msh", 2, CellType::Quadrilateral, 21, 30},
                      Expected{"square_quad_v41.msh", 2, CellType::Quadrilateral, 21, 30},
                      Expected{"square_quad_v41_bin.msh", 2, CellType::Quadrilateral, 21, 30},
                      Expected{"cube_tet_v41.msh", 3, CellType::Tetrahedron, 1125, 339},
                      Expected{"cube_tet_v22_bin.msh", 3, CellType::Tetrahedron, 1125, 339},
                      Expected{"cube_hex_v41.msh", 3, CellType::Hexahedron, 8, 27},
                      Expected{"cube_hex_v22.msh", 3, CellType::Hexahedron, 8, 27},
                      Expected{"feat_square_quad.xml", 2, CellType::Quadrilateral, 4, 9},
                      Expected{"feat_square_tri.xml", 2, CellType::Triangle, 2, 4},
                      Expected{"feat_cube_hex.xml", 3, CellType::Hexahedron, 1, 8},
                      Expected{"feat_cube_tet.xml", 3, CellType::Tetrahedron, 1, 4}),
    [](const auto& info) {
      std::string name = info.param.file;
      std::replace_if(
          name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
      return name;
    });

TEST(LoadGmsh, KeepsNamedBoundaryParts) {
  PlexMesh mesh = load_mesh(data_path("square_quad_v41.msh"));
  const MeshView& view = mesh.view();
  ASSERT_EQ(view.parts.size(), 4u);
  EXPECT_EQ(view.parts[0].name, "bottom");
  EXPECT_EQ(view.parts[0].tag, 1);
  EXPECT_EQ(view.parts[3].name, "left");
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    const double x = view.coords[2 * v], y = view.coords[2 * v + 1];
    const bool on_side = x == 0 || x == 1 || y == 0 || y == 1;
    EXPECT_EQ(view.on_boundary[v], on_side);
    EXPECT_EQ(view.boundary_part[v] >= 0, on_side);
    const bool corner = (x == 0 || x == 1) && (y == 0 || y == 1);
    EXPECT_EQ(view.part_count[v], corner ? 2 : on_side ? 1 : 0);
    if (on_side && !corner) {
      const std::string& part = view.parts[view.boundary_part[v]].name;
      EXPECT_EQ(part, y == 0 ? "bottom" : x == 1 ? "right" : y == 1 ? "top" : "left");
    }
  }
}

TEST(LoadGmsh, MixedTrianglesAndQuadsGiveTwoBlocks) {
  PlexMesh mesh = load_mesh(data_path("mixed_tri_quad_v41.msh"));
  const MeshView& view = mesh.view();
  ASSERT_EQ(view.blocks.size(), 2u);
  EXPECT_EQ(view.blocks[0].type, CellType::Triangle);
  EXPECT_EQ(view.blocks[1].type, CellType::Quadrilateral);
  EXPECT_EQ(view.blocks[1].size(), 4);
  EXPECT_EQ(view.blocks[1].first_cell, view.blocks[0].size());
  EXPECT_EQ(view.num_cells, 18);
  EXPECT_GT(min_view_jacobian(view), 0.0);
}

TEST(LoadFeat, BoundaryPartsAreNamedVertexSets) {
  PlexMesh mesh = load_mesh(data_path("feat_square_quad.xml"));
  const MeshView& view = mesh.view();
  ASSERT_EQ(view.parts.size(), 4u);
  EXPECT_EQ(view.parts[0].name, "bnd:bottom");
  EXPECT_EQ(view.parts[3].name, "bnd:left");
  // FEAT's order is canonical: cell 0 is the lower-left quad as given in the file.
  const PetscInt* cell = view.blocks[0].cell(0);
  const double expected[4][2] = {{0, 0}, {0.5, 0}, {0, 0.5}, {0.5, 0.5}};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(view.coords[2 * cell[i]], expected[i][0]);
    EXPECT_EQ(view.coords[2 * cell[i] + 1], expected[i][1]);
  }
  for (PetscInt v = 0; v < view.num_vertices; ++v)
    EXPECT_EQ(view.on_boundary[v], !(view.coords[2 * v] == 0.5 && view.coords[2 * v + 1] == 0.5));
}

TEST(FromData, GeneratedCubeIsPositiveWithSixParts) {
  PlexMesh mesh = PlexMesh::from_data(cube_midpoint(4), "cube_midpoint");
  const MeshView& view = mesh.view();
  EXPECT_EQ(mesh.global_num_cells(), 64);
  EXPECT_EQ(view.parts.size(), 6u);
  EXPECT_GT(min_view_jacobian(view), 0.0);
}

TEST(Coordinates, RoundTripThroughGlobalVector) {
  PlexMesh mesh = load_mesh(data_path("square_tri_v41.msh"));
  OwnedVec x = mesh.coordinates();
  {
    VecWriteView values(x);
    for (PetscInt i = 0; i < values.size(); ++i) values[i] *= 2.0;
  }
  const std::vector<double> before = mesh.view().coords;
  mesh.set_coordinates(x);
  for (std::size_t i = 0; i < before.size(); ++i)
    EXPECT_DOUBLE_EQ(mesh.view().coords[i], 2.0 * before[i]);
  Vec plex;
  NM_PETSC(DMGetCoordinatesLocal(mesh.dm(), &plex));
  VecReadView stored(plex);
  for (std::size_t i = 0; i < before.size(); ++i) EXPECT_DOUBLE_EQ(stored[i], 2.0 * before[i]);
}

}  // namespace
}  // namespace neomesh
