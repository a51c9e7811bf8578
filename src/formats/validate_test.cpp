// Every bad input ends in one neomesh::Error whose message names the file (and the cell).
#include "mesh/validate.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"
#include "formats/mesh_io.hpp"
#include "formats/mesh_test_util.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh {
namespace {

using testing::data_path;

// The message of the Error that loading `path` throws ("" if it loads).
std::string load_error(const std::filesystem::path& path) {
  try {
    load_mesh(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

struct BadInput {
  const char* file;
  const char* reason;  // a part of the message
};

class RejectsBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(RejectsBadInput, WithOneLineNamingTheFile) {
  const auto path = data_path(GetParam().file);
  const std::string message = load_error(path);
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find(GetParam().reason), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    Files, RejectsBadInput,
    ::testing::Values(
        BadInput{"no_such_file.msh", "no such file"}, BadInput{"geo", "is a directory"},
        BadInput{"geo/square_tri.geo", "unknown mesh format"},
        BadInput{"bad_empty.msh", "the file is empty"},
        BadInput{"bad_garbage.msh", "not a valid Gmsh mesh file"},
        BadInput{"bad_truncated.msh", "not a valid Gmsh mesh file"},
        BadInput{"bad_nan.msh", "vertex 5 (0-based) has a non-finite coordinate"},
        BadInput{
            "bad_inverted.msh",
            "cell 0 (0-based; element 13 of the file), a triangle, is inverted (it folds over"},
        BadInput{"bad_repeated_vertex.msh", "cell 0 (0-based) has a repeated vertex"},
        BadInput{"bad_element_type.msh", "has elements of Gmsh type 92"},
        BadInput{"bad_lines_only.msh", "no 2D or 3D cells"},
        BadInput{"bad_mixed_dim.msh", "2D and 3D cells mixed"},
        BadInput{"bad_feat_truncated.xml", "unexpected end of file"},
        BadInput{"bad_feat_inverted.xml", "cell 2 (0-based), a quadrilateral, is inverted"}),
    [](const auto& info) {
      std::string name = info.param.file;
      std::replace_if(
          name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
      return name;
    });

// A second-order mesh is read (smooth refuses it later, in the API: tests/cli).
TEST(Validate, ASecondOrderMeshIsReadAsACurvedMesh) {
  EXPECT_TRUE(load_mesh(data_path("bad_second_order.msh")).curved());
  EXPECT_FALSE(load_mesh(data_path("square_quad_v41.msh")).curved());
}

TEST(Validate, FlagsDegenerateTriangle) {
  InputMesh mesh;
  mesh.coords = {0, 0, 1, 0, 2, 0};
  const PetscInt cell[3] = {0, 1, 2};
  mesh.add_cell(CellType::Triangle, cell, 0);
  EXPECT_NE(find_defect(mesh).find("degenerate"), std::string::npos) << find_defect(mesh);
}

TEST(Validate, TensorOrderUnitCubeIsPositive) {
  double x[24];
  for (int i = 0; i < 8; ++i)
    for (int d = 0; d < 3; ++d) x[3 * i + d] = (i >> d) & 1;
  EXPECT_DOUBLE_EQ(min_scaled_corner_jacobian(CellType::Hexahedron, x), 1.0);
  std::swap(x[0], x[3]);  // vertices 0 and 1 exchange their x: inverted
  EXPECT_LT(min_scaled_corner_jacobian(CellType::Hexahedron, x), 0.0);
}

// A unit cube (or square) in tensor order, mirrored in x when `mirrored`.
InputMesh unit_cell(CellType type, bool mirrored) {
  InputMesh mesh;
  mesh.dim = dimension(type);
  PetscInt cell[8];
  for (int i = 0; i < num_vertices(type); ++i) {
    for (int d = 0; d < mesh.dim; ++d) mesh.coords.push_back((i >> d) & 1);
    if (mirrored) mesh.coords[i * mesh.dim] = 1 - mesh.coords[i * mesh.dim];
    cell[i] = i;
  }
  mesh.add_cell(type, cell, 0);
  return mesh;
}

TEST(Validate, MirroredCellsAreReorientedNotInverted) {
  for (CellType type : {CellType::Quadrilateral, CellType::Hexahedron}) {
    InputMesh mesh = unit_cell(type, true);
    EXPECT_EQ(orient_mirrored_cells(mesh), std::vector<PetscInt>{0});
    EXPECT_EQ(find_defect(mesh), "");
    EXPECT_EQ(find_fold(mesh, {0}), "");
    double x[24];
    for (int i = 0; i < num_vertices(type); ++i)
      std::copy_n(mesh.coords.data() + mesh.cell_vertices[i] * mesh.dim, mesh.dim,
                  x + i * mesh.dim);
    EXPECT_DOUBLE_EQ(min_scaled_corner_jacobian(type, x), 1.0) << name(type);
    InputMesh positive = unit_cell(type, false);
    EXPECT_TRUE(orient_mirrored_cells(positive).empty());
  }
}

// One cell of `type` at `coords` (canonical order).
InputMesh one_cell(CellType type, std::vector<double> coords) {
  InputMesh mesh;
  mesh.dim = 3;
  mesh.coords = std::move(coords);
  PetscInt cell[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  mesh.add_cell(type, cell, 0);
  return mesh;
}

// A wedge listed with its triangles clockwise and a pyramid with its apex below the base are
// mirrored, and reoriented; a pyramid with a base corner pulled inside (a dart) is inverted.
TEST(Validate, MirroredWedgesAndPyramidsAreReorientedFoldedOnesInverted) {
  InputMesh wedge =
      one_cell(CellType::Wedge, {0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 1, 1, 1, 0, 1});
  EXPECT_EQ(orient_mirrored_cells(wedge), std::vector<PetscInt>{0});
  EXPECT_EQ(find_defect(wedge), "");
  InputMesh below = one_cell(CellType::Pyramid, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0.5, 0.5, -1});
  EXPECT_EQ(orient_mirrored_cells(below), std::vector<PetscInt>{0});
  EXPECT_EQ(find_defect(below), "");
  InputMesh dart =
      one_cell(CellType::Pyramid, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.4, 0.4, 0, 0.5, 0.5, 1});
  EXPECT_TRUE(orient_mirrored_cells(dart).empty());
  EXPECT_NE(find_defect(dart).find("a pyramid, is inverted"), std::string::npos)
      << find_defect(dart);
}

TEST(Validate, AMirroredTriangleAmongOthersLoads) {
  // square_tri_v22.msh with element 13 listed clockwise.
  PlexMesh mesh = load_mesh(data_path("square_tri_v22_mirrored_cell.msh"));
  EXPECT_EQ(mesh.global_num_cells(), 26);
  EXPECT_GT(testing::min_view_jacobian(mesh.view()), 0.0);
}

TEST(Validate, AMirroredFeatRingAndHexMeshLoadPositive) {
  for (const char* file : {"feat_ring_quad_mirrored.xml", "feat_cube_hex_jitter_mirrored.xml"}) {
    PlexMesh mesh = load_mesh(data_path(file));
    EXPECT_GT(testing::min_view_jacobian(mesh.view()), 0.0) << file;
  }
}

}  // namespace
}  // namespace neomesh
