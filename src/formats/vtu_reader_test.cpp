#include "formats/vtu_reader.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"
#include "formats/mesh_test_util.hpp"
#include "formats/vtk_reader.hpp"

namespace neomesh {
namespace {

using testing::data_path;

std::string error_reading(const std::string& text, const std::string& name = "in.vtu") {
  return testing::read_error(text, name, [&](const auto& path) {
    if (name.ends_with(".pvtu"))
      read_pvtu(path);
    else
      read_vtu(path);
  });
}

::testing::AssertionResult has(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' lacks '" << part << "'";
}

// An ASCII .vtu of one piece: its points (3 numbers each) and cells.
std::string ascii_vtu(const std::string& points, int num_points, const std::string& connectivity,
                      const std::string& offsets, const std::string& types, int num_cells,
                      const std::string& extra = "") {
  return fmt::format(
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n"
      "<UnstructuredGrid>\n<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n{}"
      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">{}"
      "</DataArray></Points>\n<Cells>\n"
      "<DataArray Name=\"connectivity\" type=\"Int32\" format=\"ascii\">{}</DataArray>\n"
      "<DataArray Name=\"offsets\" type=\"Int32\" format=\"ascii\">{}</DataArray>\n"
      "<DataArray Name=\"types\" type=\"UInt8\" format=\"ascii\">{}</DataArray>\n"
      "</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n",
      num_points, num_cells, extra, points, connectivity, offsets, types);
}
const std::string kTriangle = "0 0 0 1 0 0 0 1 0";

// Every vtu_mixed_3d_*.vtu (tests/data/make_vtu.py) is vtk_mixed_3d.vtk's mesh, with the cell
// data "physical" 7 on the hexahedron, wedge and tetrahedron, 8 on the pyramid.
TEST(ReadVtu, ReadsEveryEncodingAsTheLegacyFileOfTheSameMesh) {
  const InputMesh legacy = read_vtk(data_path("vtk_mixed_3d.vtk"));
  for (const char* name :
       {"vtu_mixed_3d_ascii.vtu", "vtu_mixed_3d_binary.vtu", "vtu_mixed_3d_binary_zlib.vtu",
        "vtu_mixed_3d_raw.vtu", "vtu_mixed_3d_raw_zlib_bigendian.vtu", "vtu_mixed_3d_base64.vtu",
        "vtu_mixed_3d_base64_zlib.vtu"}) {
    SCOPED_TRACE(name);
    const InputMesh mesh = read_vtu(data_path(name));
    ASSERT_EQ(mesh.dim, 3);
    EXPECT_EQ(mesh.cell_types, legacy.cell_types);
    EXPECT_EQ(mesh.cell_vertices, legacy.cell_vertices);
    EXPECT_EQ(mesh.coords, legacy.coords);
    EXPECT_EQ(mesh.element_tag, legacy.element_tag);
    EXPECT_EQ(mesh.cell_tags, (std::vector<int>{7, 7, 8, 7}));
    ASSERT_EQ(mesh.groups.size(), 2u);
    EXPECT_EQ(mesh.groups[0].dim, 3);
    EXPECT_EQ(mesh.groups[1].tag, 8);
  }
}

TEST(ReadPvtu, JoinsThePiecesWhereTheirPointsCoincideOrByGlobalIds) {
  for (const char* name : {"vtu_square_pieces.pvtu", "vtu_square_pieces_ids.pvtu"}) {
    SCOPED_TRACE(name);
    const InputMesh mesh = read_pvtu(data_path(name));
    ASSERT_EQ(mesh.dim, 2);
    EXPECT_EQ(mesh.num_cells(), 4);
    // 8 points in the files, 6 in the square: the edge x = 0.5 is shared.
    ASSERT_EQ(mesh.num_vertices(), 6);
    EXPECT_EQ(mesh.cell_vertices[6], 1);  // piece 1's first point is piece 0's second
  }
}

TEST(ReadVtu, KeepsCoincidingPointsOfOnePieceApartAndSkipsDuplicateGhostCells) {
  const auto path = testing::scratch_dir("ReadVtu") / "ghost.vtu";
  const std::string ghost =
      "<CellData><DataArray Name=\"vtkGhostType\" type=\"UInt8\" format=\"ascii\">0 1"
      "</DataArray></CellData>\n";
  std::ofstream(path) << ascii_vtu(kTriangle + " " + kTriangle, 6, "0 1 2 3 4 5", "3 6", "5 5", 2,
                                   ghost);
  const InputMesh mesh = read_vtu(path);
  EXPECT_EQ(mesh.num_cells(), 1);
  EXPECT_EQ(mesh.num_vertices(), 3);
  std::ofstream(path) << ascii_vtu(kTriangle + " " + kTriangle, 6, "0 1 2 3 4 5", "3 6", "5 5", 2);
  EXPECT_EQ(read_vtu(path).num_vertices(), 6);
}

TEST(ReadVtu, NamesTheFileAndTheArrayOfAnError) {
  EXPECT_TRUE(has(error_reading("<VTKFile type=\"UnstructuredGrid\"><Unstructured"),
                  "in.vtu:1: not a valid VTK XML file ("));
  EXPECT_TRUE(has(error_reading(ascii_vtu(kTriangle, 3, "0 1 3", "3", "5", 1)),
                  "in.vtu: not a valid VTK XML file (a cell of piece 0 refers to point 3, which "
                  "is out of range (0..2))"));
  EXPECT_TRUE(has(error_reading(ascii_vtu(kTriangle, 3, "0 1 2", "3", "9", 1)),
                  "cell 0 (0-based) of piece 0 is a quadrilateral of 3 points"));
  EXPECT_TRUE(has(error_reading(ascii_vtu("0 0 0 1 0 0 0 1", 3, "0 1 2", "3", "5", 1)),
                  "the points of piece 0 holds 8 values, expected 9"));
  EXPECT_TRUE(has(error_reading(ascii_vtu(kTriangle, 3, "0 1 2.5", "3", "5", 1)),
                  "the connectivity of piece 0: '2.5' is not an integer"));
  EXPECT_TRUE(has(error_reading(ascii_vtu(kTriangle, 3, "0 1 2", "3", "99", 1)),
                  "unknown VTK cell type 99"));
  EXPECT_TRUE(has(error_reading(ascii_vtu("0 0 0 1 nan 0 0 1 0", 3, "0 1 2", "3", "5", 1)),
                  "point 1 (0-based) of piece 0 has the coordinate nan"));
  const std::string binary =
      "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece NumberOfPoints=\"1\" "
      "NumberOfCells=\"0\"><Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" "
      "format=\"binary\">";
  // 24 bytes announced (base64 "GAAAAA=="), 21 given.
  EXPECT_TRUE(has(error_reading(binary + "GAAAAA==" + std::string(28, 'A') +
                                "</DataArray></Points></Piece></UnstructuredGrid></VTKFile>"),
                  "the points of piece 0: the data end early"));
  EXPECT_TRUE(has(error_reading(binary + "GAAAAA==AAAA</DataArray></Points></Piece>"
                                         "</UnstructuredGrid></VTKFile>"),
                  "the points of piece 0: it announces 24 bytes, more than the file holds"));
  EXPECT_TRUE(has(error_reading(binary + "GAAA*AAA</DataArray></Points></Piece>"
                                         "</UnstructuredGrid></VTKFile>"),
                  "'*' is not a base64 character"));
  EXPECT_TRUE(has(error_reading(binary + "////////</DataArray></Points></Piece>"
                                         "</UnstructuredGrid></VTKFile>"),
                  "it announces 4294967295 bytes, more than the file holds"));
}

TEST(ReadVtu, RefusesWhatNeomeshDoesNotReadInOneLine) {
  EXPECT_TRUE(has(error_reading("<VTKFile type=\"ImageData\"><ImageData/></VTKFile>"),
                  "in.vtu: is a structured grid (ImageData); neomesh reads unstructured grids"));
  EXPECT_TRUE(has(error_reading("<VTKFile type=\"PolyData\"><PolyData/></VTKFile>"),
                  "in.vtu: is VTK polydata"));
  EXPECT_TRUE(has(error_reading("<VTKFile type=\"UnstructuredGrid\" "
                                "compressor=\"vtkLZ4DataCompressor\"/>"),
                  "in.vtu: is compressed with vtkLZ4DataCompressor; neomesh reads"));
  EXPECT_TRUE(has(error_reading(ascii_vtu(kTriangle, 3, "0 1 2 0 1 2 0", "7", "34", 1)),
                  "in.vtu: cell 0 (0-based) is a biquadratic triangle of 7 points; of the "
                  "second-order cells neomesh reads triangles (6 points)"));
  EXPECT_TRUE(has(error_reading(ascii_vtu(kTriangle, 3, "0 1 2", "3", "42", 1)),
                  "in.vtu: cell 0 (0-based) is a polyhedron; neomesh supports"));
  EXPECT_TRUE(has(error_reading(ascii_vtu(kTriangle, 3, "0 1 1 2", "2 4", "3 3", 2)),
                  "in.vtu: has no 2D or 3D cells (only 1D elements)"));
  EXPECT_TRUE(has(error_reading("<VTKFile type=\"PUnstructuredGrid\"><PUnstructuredGrid>"
                                "<Piece Source=\"missing.vtu\"/></PUnstructuredGrid></VTKFile>",
                                "in.pvtu"),
                  "missing.vtu: no such file"));
}

}  // namespace
}  // namespace neomesh
