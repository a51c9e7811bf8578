#include "formats/vtk_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"
#include "formats/mesh_test_util.hpp"

namespace neomesh {
namespace {

using testing::data_path;

std::string error_reading(const std::string& text) {
  return testing::read_error(text, "in.vtk", [](const auto& path) { read_vtk(path); });
}

// True if `text` contains `part`, with the text in the failure message.
::testing::AssertionResult has(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' lacks '" << part << "'";
}

const std::string kHead = "# vtk DataFile Version 3.0\ntitle\nASCII\nDATASET UNSTRUCTURED_GRID\n";
const std::string kTrianglePoints = "POINTS 3 float\n0 0 0 1 0 0 0 1 0\n";

// The mesh of vtk_mixed_3d*.vtk (tests/data, written by tests/data/README.md's script): a
// hexahedron, a wedge, a pyramid and a tetrahedron among a vertex and a line cell, an unused
// point between the wedge and the pyramid.
void expect_mixed_3d(const InputMesh& mesh, const std::string& name) {
  SCOPED_TRACE(name);
  ASSERT_EQ(mesh.dim, 3);
  EXPECT_EQ(mesh.cell_types, (std::vector<CellType>{CellType::Hexahedron, CellType::Wedge,
                                                    CellType::Pyramid, CellType::Tetrahedron}));
  // Canonical orders: tensor order for the hexahedron and the pyramid's base; the wedge's
  // triangles counter-clockwise seen from its top (VTK lists them clockwise).
  EXPECT_EQ(mesh.cell_vertices,
            (std::vector<PetscInt>{0,  1,  3,  2,  4,  5,  7,  6,  8,  10, 9, 11,
                                   13, 12, 14, 15, 17, 16, 18, 19, 20, 21, 22}));
  ASSERT_EQ(mesh.num_vertices(), 23);  // the unused point and the vertex cell's are dropped
  EXPECT_EQ(mesh.coords[3 * 14], 4.0);
  EXPECT_EQ(mesh.coords[3 * 18 + 2], 1.0);  // the apex
  EXPECT_EQ(mesh.cell_tags, std::vector<int>(4, 0));
  EXPECT_TRUE(mesh.groups.empty());
  // The vertex and the line are not cells: messages name cells by their place in the file.
  EXPECT_EQ(mesh.element_tag, (std::vector<std::int64_t>{0, 2, 4, 5}));
}

TEST(ReadVtk, ReadsEachCellTypeAndSkipsPointAndCellData) {
  expect_mixed_3d(read_vtk(data_path("vtk_mixed_3d.vtk")), "vtk_mixed_3d.vtk");
}

TEST(ReadVtk, AsciiBinaryAndTheVersion51LayoutAgree) {
  const InputMesh ascii = read_vtk(data_path("vtk_mixed_3d.vtk"));
  for (const char* other :
       {"vtk_mixed_3d_bin.vtk", "vtk_mixed_3d_v51.vtk", "vtk_mixed_3d_v51_bin.vtk"}) {
    const InputMesh mesh = read_vtk(data_path(other));
    expect_mixed_3d(mesh, other);
    EXPECT_EQ(mesh.coords, ascii.coords) << other;
  }
}

TEST(ReadVtk, ReadsPolygonsOfPolydataAsTrianglesAndQuadrilaterals) {
  const InputMesh mesh = read_vtk(data_path("vtk_square_polydata.vtk"));
  ASSERT_EQ(mesh.dim, 2);
  EXPECT_EQ(mesh.cell_types, (std::vector<CellType>{CellType::Triangle, CellType::Triangle,
                                                    CellType::Quadrilateral}));
  // The quadrilateral 1 2 5 4 (counter-clockwise) in tensor order.
  EXPECT_EQ(std::vector<PetscInt>(mesh.cell_vertices.begin() + 6, mesh.cell_vertices.end()),
            (std::vector<PetscInt>{1, 2, 4, 5}));
  EXPECT_EQ(mesh.plane, nullptr);
  EXPECT_EQ(mesh.coords.size(), 12u);
}

TEST(ReadVtk, KeepsTheTiltedPlaneOfA2DMesh) {
  const InputMesh mesh = read_vtk(data_path("vtk_tilted_tri.vtk"));
  ASSERT_EQ(mesh.dim, 2);
  ASSERT_NE(mesh.plane, nullptr);
  const std::vector<double> xyz = mesh.plane->to_space(mesh.coords);
  ASSERT_EQ(xyz.size(), 18u);
  EXPECT_DOUBLE_EQ(xyz[3 * 4 + 1], 0.8);  // (u, v) = (1, 1) comes back where it was
  EXPECT_DOUBLE_EQ(xyz[3 * 4 + 2], 1 - 0.6);
  // In-plane lengths are those in space: the edge from point 0 to point 3 is 1 long.
  EXPECT_NEAR(std::hypot(mesh.coords[6] - mesh.coords[0], mesh.coords[7] - mesh.coords[1]), 1.0,
              1e-12);
}

TEST(ReadVtk, NamesTheLineOfAnAsciiError) {
  EXPECT_TRUE(has(error_reading(kHead + "POINTS 3 float\n0 0 0\n1 0 0\n"),
                  "in.vtk:5: not a valid VTK file (truncated: the file ends inside POINTS, which "
                  "announces 3 × 3 values)"));
  EXPECT_TRUE(has(error_reading(kHead + "POINTS 2 float\n0 0 0\n1 nan 0\n"),
                  "in.vtk:7: not a valid VTK file (point 1 (0-based) has the coordinate nan)"));
  EXPECT_TRUE(has(error_reading(kHead + kTrianglePoints + "CELLS 1 4\n3 0 1 3\nCELL_TYPES 1\n5\n"),
                  "in.vtk:8: not a valid VTK file (cell 0 (0-based) refers to point 3, which is "
                  "out of range (0..2))"));
  EXPECT_TRUE(has(error_reading(kHead + kTrianglePoints + "CELLS 1 5\n3 0 1 2\nCELL_TYPES 1\n5\n"),
                  "CELLS announces 5 numbers and lists 4"));
  EXPECT_TRUE(has(error_reading(kHead + kTrianglePoints + "CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n9\n"),
                  "in.vtk:10: not a valid VTK file (cell 0 (0-based) is a quadrilateral of 3 "
                  "points (a quadrilateral has 4))"));
  EXPECT_TRUE(has(error_reading(kHead + kTrianglePoints + "CELLS 2 4\n3 0 1 2\n"),
                  "in.vtk:9: not a valid VTK file (truncated: the file ends inside CELLS)"));
  EXPECT_TRUE(has(error_reading(kHead + kTrianglePoints + "CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n99\n"),
                  "unknown VTK cell type 99"));
  EXPECT_TRUE(has(error_reading(kHead + kTrianglePoints + "CELLS 1 4\n3 0 1 2\n"),
                  "it has CELLS but no CELL_TYPES"));
  EXPECT_TRUE(has(error_reading("# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n"
                                "POINTS 1 float\n0 0 0\nPOINT_DATA 1\nSCALARS s float 1\n"
                                "LOOKUP_TABLE default\n"),
                  "truncated: the file ends inside SCALARS"));
  EXPECT_TRUE(has(error_reading("solid x\nfacet\n"),
                  "in.vtk:1: not a valid VTK file (it does "
                  "not start with '# vtk DataFile Version')"));
}

// The cell scalars "physical" (neomesh's .vtk output) are the cells' groups; a count other than
// the cells' or a value that is not a group number is an error naming the line.
TEST(ReadVtk, ReadsThePhysicalGroupsOfCells) {
  const std::string cells = "CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n";
  const std::string path = ::testing::TempDir() + "groups.vtk";
  std::ofstream(path) << kHead + kTrianglePoints + cells +
                             "CELL_DATA 1\nSCALARS physical int 1\nLOOKUP_TABLE default\n7\n";
  const InputMesh mesh = read_vtk(path);
  EXPECT_EQ(mesh.cell_tags, (std::vector<int>{7}));
  ASSERT_EQ(mesh.groups.size(), 1u);
  EXPECT_EQ(mesh.groups[0].tag, 7);
  EXPECT_TRUE(has(error_reading(kHead + kTrianglePoints + cells +
                                "CELL_DATA 2\nSCALARS physical int 1\nLOOKUP_TABLE default\n7 8\n"),
                  "it gives physical groups of 2 cells, but has 1 cells"));
  EXPECT_TRUE(has(error_reading(kHead + kTrianglePoints + cells +
                                "CELL_DATA 1\nSCALARS physical float 1\nLOOKUP_TABLE default\n"
                                "2.5\n"),
                  "a cell's physical group is 2.5"));
}

TEST(ReadVtk, NamesTheByteOffsetOfABinaryError) {
  const std::string head = "# vtk DataFile Version 3.0\nt\nBINARY\nDATASET UNSTRUCTURED_GRID\n";
  const std::string points = "POINTS 1 double\n" + std::string(24, '\0') + "\n";
  EXPECT_TRUE(has(error_reading(head + "POINTS 2 double\n" + std::string(24, '\0')),
                  "in.vtk: byte 62: not a valid VTK file (truncated"));
  // Cell 0 of 3 points: 0, 0, and 1 << 24, far outside the one point.
  const std::string cells = std::string("\0\0\0\3\0\0\0\0\0\0\0\0\1\0\0\0", 16);
  EXPECT_TRUE(has(error_reading(head + points + "CELLS 1 4\n" + cells),
                  "refers to point 16777216, which is out of range (0..0)"));
}

TEST(ReadVtk, AQuadraticTriangleIsACurvedMeshOfThreeVerticesAndThreeNodes) {
  const std::string path = ::testing::TempDir() + "tri6.vtk";
  std::ofstream(path) << kHead << "POINTS 6 float\n0 0 0 1 0 0 0 1 0 .5 -.1 0 .5 .5 0 0 .5 0\n"
                      << "CELLS 1 7\n6 0 1 2 3 4 5\nCELL_TYPES 1\n22\n";
  const InputMesh mesh = read_vtk(path);
  ASSERT_TRUE(mesh.curved());
  EXPECT_EQ(mesh.num_vertices(), 3);
  EXPECT_EQ(mesh.high_order.num_nodes(), 3);
  EXPECT_EQ(mesh.high_order.types, std::vector{CurvedType::Triangle6});
  PetscInt points[kMaxCurvedNodes];
  ASSERT_EQ(curved_cell_points(mesh, 0, points), 6);
  EXPECT_EQ(std::vector(points, points + 6), (std::vector<PetscInt>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(mesh.high_order.xyz[1], -0.1);
}

TEST(ReadVtk, RefusesWhatNeomeshDoesNotOptimizeInOneLine) {
  const std::string six = "POINTS 6 float\n0 0 0 1 0 0 0 1 0 .5 0 0 .5 .5 0 0 .5 0\n";
  EXPECT_TRUE(has(error_reading(kHead + six + "CELLS 1 7\n6 0 1 2 3 4 5\nCELL_TYPES 1\n30\n"),
                  "in.vtk: cell 0 (0-based) is a quadratic-linear quadrilateral of 6 points; of "
                  "the second-order cells neomesh reads"));
  EXPECT_TRUE(
      has(error_reading(kHead + six + "CELLS 2 11\n6 0 1 2 3 4 5\n3 0 1 2\nCELL_TYPES 2\n22 5\n"),
          "in.vtk: mixes first-order cells (cell 1) and second-order ones (cell 0)"));
  EXPECT_TRUE(has(error_reading(kHead + six + "CELLS 1 6\n5 0 1 4 2 5\nCELL_TYPES 1\n7\n"),
                  "in.vtk: cell 0 (0-based) is a polygon of 5 vertices"));
  EXPECT_TRUE(has(error_reading("# vtk DataFile Version 2.0\nt\nASCII\nDATASET POLYDATA\n" + six +
                                "POLYGONS 1 7\n6 0 3 1 4 2 5\n"),
                  "in.vtk: cell 0 (0-based) is a polygon of 6 vertices"));
  EXPECT_TRUE(has(error_reading("# vtk DataFile Version 2.0\nt\nASCII\nDATASET STRUCTURED_POINTS\n"
                                "DIMENSIONS 2 2 2\n"),
                  "in.vtk: is a structured grid; neomesh reads unstructured grids"));
  EXPECT_TRUE(
      has(error_reading(kHead + kTrianglePoints + "CELLS 2 5\n2 0 1\n1 2\nCELL_TYPES 2\n3 1\n"),
          "in.vtk: has no 2D or 3D cells (only 1D elements)"));
  EXPECT_TRUE(has(error_reading(kHead + kTrianglePoints + "CELLS 1 4\n3 0 1 1\nCELL_TYPES 1\n5\n"),
                  "in.vtk: cell 0 (0-based) has a repeated vertex"));
  for (const std::string& message :
       {error_reading(kHead + six + "CELLS 1 7\n6 0 1 2 3 4 5\nCELL_TYPES 1\n22\n"),
        error_reading(kHead + "POINTS x float\n")})
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(ReadVtk, TakesTheFirstCellTypesWhenTheFileListsMore) {
  // MOAB wrote one type per point; VTK's own reader takes the first ones.
  const auto path = testing::scratch_dir("ReadVtk") / "more_types.vtk";
  std::ofstream(path) << kHead + kTrianglePoints + "CELLS 1 4\n3 0 1 2\nCELL_TYPES 3\n5 5 5\n";
  EXPECT_EQ(read_vtk(path).num_cells(), 1);
}

}  // namespace
}  // namespace neomesh
