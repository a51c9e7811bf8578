// The input's point and cell data and its facet and point groups, written back: read -> write ->
// read gives the same arrays (names, components, values, types) and groups in every format that
// has a place for them.
#include <gtest/gtest.h>

#include <exodusII.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <numeric>

#include "core/testing/test_data.hpp"
#include "formats/exodus_file.hpp"
#include "formats/exodus_reader.hpp"
#include "formats/gmsh_reader.hpp"
#include "formats/medit_reader.hpp"
#include "formats/mesh_io.hpp"
#include "formats/vtk_reader.hpp"
#include "formats/vtu_reader.hpp"
#include "generate/generate.hpp"
#include "mesh/gather.hpp"
#include "mesh/mesh_impl.hpp"

namespace neomesh {
namespace {

using testing::data_path;
using testing::scratch_dir;

// A quadrilateral and two triangles (2D), an unused point (6), a line in the facet group 7
// ("left side"), an untagged line and a vertex tagged 9 ("corner"; both skipped); the
// quadrilateral is in the cell group 1 ("solid"), the triangles in 2 (unnamed). Point data:
// "temperature" (Float64) and "velocity" (Float32, 3 components); cell data: "material"
// (Int32) and "volume" (a name of neomesh's own fields).
constexpr const char* kVtu = R"(<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">
<UnstructuredGrid>
<FieldData>
<DataArray type="Int32" Name="left side" NumberOfTuples="2" format="ascii">7 1</DataArray>
<DataArray type="Int32" Name="corner" NumberOfTuples="2" format="ascii">9 0</DataArray>
<DataArray type="Int32" Name="solid" NumberOfTuples="2" format="ascii">1 2</DataArray>
<DataArray type="String" Name="comment" NumberOfTuples="1" format="ascii">104 105 0</DataArray>
</FieldData>
<Piece NumberOfPoints="7" NumberOfCells="6">
<PointData>
<DataArray type="Float64" Name="temperature" format="ascii">0 1.5 3 4.5 6 7.5 9</DataArray>
<DataArray type="Float32" Name="velocity" NumberOfComponents="3" format="ascii">
0 0.1 0.2 1 1.1 1.2 2 2.1 2.2 3 3.1 3.2 4 4.1 4.2 5 5.1 5.2 6 6.1 6.2</DataArray>
</PointData>
<CellData>
<DataArray type="Int32" Name="physical" format="ascii">1 2 2 7 0 9</DataArray>
<DataArray type="Int32" Name="material" format="ascii">10 20 30 -1 -2 -3</DataArray>
<DataArray type="Float64" Name="volume" format="ascii">-1 -2 -3 -4 -5 -6</DataArray>
</CellData>
<Points>
<DataArray type="Float64" NumberOfComponents="3" format="ascii">
0 0 0  1 0 0  1 1 0  0 1 0  2 0 0  2 1 0  5 5 0</DataArray>
</Points>
<Cells>
<DataArray type="Int64" Name="connectivity" format="ascii">0 1 2 3  1 4 5  1 5 2  0 1  4 5  3</DataArray>
<DataArray type="Int64" Name="offsets" format="ascii">4 7 10 12 14 15</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">9 5 5 3 3 1</DataArray>
</Cells>
</Piece>
</UnstructuredGrid>
</VTKFile>
)";

std::filesystem::path input_file(const std::string& test) {
  const auto path = scratch_dir(test) / "in.vtu";
  std::ofstream(path) << kVtu;
  return path;
}

const DataArray* find(const std::vector<DataArray>& arrays, const std::string& name) {
  for (const DataArray& a : arrays)
    if (a.name == name) return &a;
  return nullptr;
}

void expect_same_data(const std::vector<DataArray>& a, const std::vector<DataArray>& b,
                      bool types) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].name, b[k].name);
    EXPECT_EQ(a[k].components, b[k].components) << a[k].name;
    EXPECT_EQ(a[k].values, b[k].values) << a[k].name;
    if (types) {
      EXPECT_EQ(a[k].type, b[k].type) << a[k].name;
    }
  }
}

TEST(VtuData, ReadsTheArraysOfTheVerticesAndCellsKept) {
  const InputMesh mesh = read_vtu(input_file("VtuDataRead"));
  ASSERT_EQ(mesh.num_vertices(), 6);  // the unused point is dropped, with its data
  ASSERT_EQ(mesh.num_cells(), 3);
  ASSERT_EQ(mesh.point_data.size(), 2u);
  EXPECT_EQ(mesh.point_data[0].name, "temperature");
  EXPECT_EQ(mesh.point_data[0].values, (std::vector<double>{0, 1.5, 3, 4.5, 6, 7.5}));
  EXPECT_EQ(mesh.point_data[1].name, "velocity");
  EXPECT_EQ(mesh.point_data[1].components, 3);
  EXPECT_EQ(mesh.point_data[1].type, ValueType::Float32);
  EXPECT_EQ(mesh.point_data[1].values.size(), 18u);
  EXPECT_EQ(mesh.point_data[1].values[17], static_cast<double>(5.2f));
  ASSERT_EQ(mesh.cell_data.size(), 2u);  // not "physical": that is the groups
  EXPECT_EQ(mesh.cell_data[0].name, "material");
  EXPECT_EQ(mesh.cell_data[0].type, ValueType::Int32);
  EXPECT_EQ(mesh.cell_data[0].values, (std::vector<double>{10, 20, 30}));

  ASSERT_EQ(mesh.facets.size(), 1);
  EXPECT_EQ(mesh.facets.tags[0], 7);
  EXPECT_EQ(mesh.facets.vertices, (std::vector<PetscInt>{0, 1}));
  EXPECT_EQ(mesh.points.size(), 0);  // as Gmsh's point elements
  ASSERT_EQ(mesh.groups.size(), 3u);
  const std::vector<std::tuple<int, int, std::string>> expected = {
      {1, 7, "left side"}, {2, 1, "solid"}, {2, 2, ""}};
  for (std::size_t k = 0; k < expected.size(); ++k)
    EXPECT_EQ(std::tuple(mesh.groups[k].dim, mesh.groups[k].tag, mesh.groups[k].name), expected[k]);
}

TEST(VtuData, AGroupFacetOnNoCellIsAnError) {
  std::string text = kVtu;
  text.replace(text.find("0 1  4 5  3"), 11, "0 6  4 5  3");  // the facet to the unused point
  const auto path = scratch_dir("VtuDataOffMesh") / "in.vtu";
  std::ofstream(path) << text;
  EXPECT_THROW(read_vtu(path), Error);
}

// The cells of `mesh` ordered by their centroids: formats that order cells by type (.msh) or
// group (.exo) renumber them.
std::vector<PetscInt> cells_by_position(const PlexMesh& mesh) {
  const GatheredMesh g = gather_mesh(mesh, {});
  std::vector<std::array<double, 3>> centroid(g.mesh.num_cells(), {0, 0, 0});
  for (PetscInt c = 0; c < g.mesh.num_cells(); ++c)
    for (PetscInt i = g.mesh.cell_offsets[c]; i < g.mesh.cell_offsets[c + 1]; ++i)
      for (int d = 0; d < g.mesh.dim; ++d)
        centroid[c][d] += g.mesh.coords[g.mesh.cell_vertices[i] * g.mesh.dim + d];
  std::vector<PetscInt> order(g.mesh.num_cells());
  std::iota(order.begin(), order.end(), PetscInt{0});
  std::sort(order.begin(), order.end(),
            [&](PetscInt a, PetscInt b) { return centroid[a] < centroid[b]; });
  return order;
}

// The arrays and tags per cell in the order `order`.
std::vector<DataArray> reordered(std::vector<DataArray> data, const std::vector<PetscInt>& order) {
  for (DataArray& a : data) {
    std::vector<double> v;
    for (PetscInt c : order)
      v.insert(v.end(), a.values.begin() + c * a.components,
               a.values.begin() + (c + 1) * a.components);
    a.values = std::move(v);
  }
  return data;
}
std::vector<int> reordered(const std::vector<int>& tags, const std::vector<PetscInt>& order) {
  std::vector<int> out;
  for (PetscInt c : order) out.push_back(tags[c]);
  return out;
}

// The pieces of a .pvtu join their data: a shared point's from the first piece, the arrays every
// piece has (not "only1").
TEST(VtuData, PiecesJoinTheirArrays) {
  const auto dir = scratch_dir("PvtuData");
  const auto piece = [&](const char* name, const char* points, const char* t, double c,
                         const char* extra) {
    std::ofstream(dir / name) << fmt::format(
        R"(<VTKFile type="UnstructuredGrid"><UnstructuredGrid><Piece NumberOfPoints="3" NumberOfCells="1">
<PointData><DataArray type="Float64" Name="T" format="ascii">{}</DataArray>{}</PointData>
<CellData><DataArray type="Float64" Name="c" format="ascii">{}</DataArray></CellData>
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">{}</DataArray></Points>
<Cells><DataArray type="Int32" Name="connectivity" format="ascii">0 1 2</DataArray>
<DataArray type="Int32" Name="offsets" format="ascii">3</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">5</DataArray></Cells>
</Piece></UnstructuredGrid></VTKFile>
)",
        t, extra, c, points);
  };
  piece("p0.vtu", "0 0 0 1 0 0 1 1 0", "0 1 2", 10, "");
  piece("p1.vtu", "0 0 0 1 1 0 0 1 0", "-5 -6 3", 20,
        R"(<DataArray type="Int32" Name="only1" format="ascii">1 1 1</DataArray>)");
  std::ofstream(dir / "all.pvtu")
      << R"(<VTKFile type="PUnstructuredGrid"><PUnstructuredGrid><Piece Source="p0.vtu"/>)"
         R"(<Piece Source="p1.vtu"/></PUnstructuredGrid></VTKFile>)";
  const InputMesh mesh = read_pvtu(dir / "all.pvtu");
  ASSERT_EQ(mesh.num_vertices(), 4);
  ASSERT_EQ(mesh.point_data.size(), 1u);
  EXPECT_EQ(mesh.point_data[0].values, (std::vector<double>{0, 1, 2, 3}));
  ASSERT_EQ(mesh.cell_data.size(), 1u);
  EXPECT_EQ(mesh.cell_data[0].values, (std::vector<double>{10, 20}));
}

// A UInt64 array may hold values beyond Int64 (ids, hashes): they are data, not an error, and
// written back as the largest UInt64.
TEST(VtuData, UInt64ValuesBeyondInt64AreKept) {
  std::string text = kVtu;
  text.replace(text.find("<DataArray type=\"Float64\" Name=\"temperature\""), 0,
               "<DataArray type=\"UInt64\" Name=\"id\" format=\"binary\">"
               "OAAAAP//////////////////////////////////////////////////////////////////////////"
               "</DataArray>\n");
  const auto dir = scratch_dir("VtuDataUInt64");
  std::ofstream(dir / "in.vtu") << text;
  const InputMesh mesh = read_vtu(dir / "in.vtu");
  ASSERT_EQ(mesh.point_data[0].name, "id");
  EXPECT_EQ(mesh.point_data[0].values[0], 0x1p64);
  write_mesh(load_mesh(dir / "in.vtu"), dir / "out.vtu");
  EXPECT_EQ(read_vtu(dir / "out.vtu").point_data[0].values[5], 0x1p64);  // 2^64 - 1 as double
  write_mesh(load_mesh(dir / "in.vtu"), dir / "out.vtk");
  EXPECT_NE(testing::read_file(dir / "out.vtk").find("18446744073709551615"), std::string::npos);
}

class DataRoundTrip : public ::testing::TestWithParam<const char*> {};

TEST_P(DataRoundTrip, KeepsPointAndCellDataAndGroups) {
  const std::string ext = GetParam();
  PlexMesh in = load_mesh(input_file("DataRoundTrip" + ext.substr(1)));
  const auto out = scratch_dir("DataRoundTripOut" + ext.substr(1)) / ("out" + ext);
  write_mesh(in, out);
  PlexMesh back = load_mesh(out);
  const auto &a = MeshAccess::impl(in), &b = MeshAccess::impl(back);
  // .exo and .msh hold doubles; CGNS 32- and 64-bit integers and reals (an Int8 comes back as
  // Int32).
  const bool typed = ext != ".exo" && ext != ".msh" && ext != ".cgns";
  expect_same_data(a.point_data, b.point_data, typed);
  const auto in_order = cells_by_position(in), back_order = cells_by_position(back);
  expect_same_data(reordered(a.cell_data, in_order), reordered(b.cell_data, back_order), typed);
  EXPECT_EQ(a.facets.vertices, b.facets.vertices);
  if (ext == ".cgns") return;  // CGNS numbers and names the groups its own way (test_cgns.py)
  EXPECT_EQ(a.facets.tags, b.facets.tags);
  EXPECT_EQ(reordered(a.cell_tags, in_order), reordered(b.cell_tags, back_order));
  if (ext == ".exo") return;  // Exodus names unnamed blocks
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (std::size_t k = 0; k < a.groups.size(); ++k) {
    EXPECT_EQ(a.groups[k].dim, b.groups[k].dim);
    EXPECT_EQ(a.groups[k].tag, b.groups[k].tag);
    EXPECT_EQ(a.groups[k].name, b.groups[k].name);
  }
}

#ifdef NEOMESH_HAS_CGNS
INSTANTIATE_TEST_SUITE_P(Formats, DataRoundTrip,
                         ::testing::Values(".vtu", ".vtk", ".exo", ".msh", ".cgns"),
#else
INSTANTIATE_TEST_SUITE_P(Formats, DataRoundTrip, ::testing::Values(".vtu", ".vtk", ".exo", ".msh"),
#endif
                         [](const auto& info) { return std::string(info.param).substr(1); });

// A .msh's boundary groups survive .vtu and .vtk with their names.
class FacetGroupsInVtk : public ::testing::TestWithParam<const char*> {};

TEST_P(FacetGroupsInVtk, SurviveWithTheirNames) {
  PlexMesh in = load_mesh(data_path("mixed_tri_quad_v41.msh"));
  const auto out = scratch_dir("FacetGroupsInVtk") / (std::string("out") + GetParam());
  write_mesh(in, out);
  PlexMesh back = load_mesh(out);
  const auto &a = MeshAccess::impl(in), &b = MeshAccess::impl(back);
  ASSERT_GT(a.facets.size(), 0);
  EXPECT_EQ(a.facets.vertices, b.facets.vertices);
  EXPECT_EQ(a.facets.tags, b.facets.tags);
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (std::size_t k = 0; k < a.groups.size(); ++k) {
    EXPECT_EQ(a.groups[k].dim, b.groups[k].dim);
    EXPECT_EQ(a.groups[k].tag, b.groups[k].tag);
    EXPECT_EQ(a.groups[k].name, b.groups[k].name);
  }
  ASSERT_EQ(in.view().parts.size(), back.view().parts.size());
  for (std::size_t p = 0; p < in.view().parts.size(); ++p)
    EXPECT_EQ(in.view().parts[p].name, back.view().parts[p].name);
}

INSTANTIATE_TEST_SUITE_P(Formats, FacetGroupsInVtk, ::testing::Values(".vtu", ".vtk"),
                         [](const auto& info) { return std::string(info.param).substr(1); });

// The input's "volume" keeps its name; neomesh's is written as "neomesh_volume", and replaces
// an input array of that name (its own field of an earlier run).
TEST(DataNames, TheInputKeepsItsNamesAndNeomeshsFieldsArePrefixed) {
  for (const char* ext : {".vtu", ".vtk"}) {
    PlexMesh in = load_mesh(input_file("DataNames"));
    MeshFields fields;
    fields.cell.push_back({"volume", std::vector<double>(3, 42.0), 1});
    fields.cell.push_back({"other", std::vector<double>(3, 7.0), 1});
    const auto dir = scratch_dir("DataNamesOut");
    write_mesh(in, dir / (std::string("once") + ext), fields);
    PlexMesh once = load_mesh(dir / (std::string("once") + ext));
    const auto& data = MeshAccess::impl(once).cell_data;
    ASSERT_TRUE(find(data, "volume")) << ext;
    EXPECT_EQ(find(data, "volume")->values, (std::vector<double>{-1, -2, -3})) << ext;
    ASSERT_TRUE(find(data, "neomesh_volume")) << ext;
    EXPECT_EQ(find(data, "neomesh_volume")->values, (std::vector<double>(3, 42.0))) << ext;
    ASSERT_TRUE(find(data, "other")) << ext;

    fields.cell[0].values.assign(3, 43.0);
    write_mesh(once, dir / (std::string("twice") + ext), fields);
    PlexMesh twice = load_mesh(dir / (std::string("twice") + ext));
    const auto& again = MeshAccess::impl(twice).cell_data;
    EXPECT_EQ(again.size(), data.size() + 1) << ext;  // + "neomesh_other"
    EXPECT_EQ(find(again, "volume")->values, (std::vector<double>{-1, -2, -3})) << ext;
    EXPECT_EQ(find(again, "neomesh_volume")->values, (std::vector<double>(3, 43.0))) << ext;
  }
}

TEST(VtkData, ReadsAttributesAndFieldArraysWithTheirNamesDecoded) {
  const auto path = scratch_dir("VtkData") / "in.vtk";
  std::ofstream(path) << "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n"
                         "FIELD FieldData 1\nthe%20wall 1 2 int\n3 1\n"
                         "POINTS 4 float\n0 0 0 1 0 0 1 1 0 0 1 0\n"
                         "CELLS 3 11\n3 0 1 2\n3 0 2 3\n2 0 1\nCELL_TYPES 3\n5 5 3\n"
                         "CELL_DATA 3\nSCALARS physical int 1\nLOOKUP_TABLE default\n0 0 3\n"
                         "SCALARS id%25 short\nLOOKUP_TABLE default\n4 5 6\n"
                         "POINT_DATA 4\nVECTORS flow double\n0 0 0 1 1 1 2 2 2 3 3 3\n"
                         "FIELD FieldData 2\nT 1 4 float\n0.5 1.5 2.5 3.5\n"
                         "skipped 1 3 float\n1 2 3\n";
  const InputMesh mesh = read_vtk(path);
  ASSERT_EQ(mesh.cell_data.size(), 1u);
  EXPECT_EQ(mesh.cell_data[0].name, "id%");
  EXPECT_EQ(mesh.cell_data[0].type, ValueType::Int16);
  EXPECT_EQ(mesh.cell_data[0].values, (std::vector<double>{4, 5}));
  ASSERT_EQ(mesh.point_data.size(), 2u);
  EXPECT_EQ(mesh.point_data[0].name, "flow");
  EXPECT_EQ(mesh.point_data[0].components, 3);
  EXPECT_EQ(mesh.point_data[1].name, "T");
  EXPECT_EQ(mesh.point_data[1].values, (std::vector<double>{0.5, 1.5, 2.5, 3.5}));
  ASSERT_EQ(mesh.facets.size(), 1);
  ASSERT_EQ(mesh.groups.size(), 1u);
  EXPECT_EQ(mesh.groups[0].name, "the wall");
}

// $NodeData and $ElementData by node and element tag (not file order): the last section of a
// name wins, nodes without a value get NaN, data of the line elements are dropped.
TEST(GmshData, ReadsNodeAndElementDataByTag) {
  const auto path = scratch_dir("GmshData") / "in.msh";
  std::ofstream(path) << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
                         "$Nodes\n4\n10 0 0 0\n20 1 0 0\n30 1 1 0\n40 0 1 0\n$EndNodes\n"
                         "$Elements\n3\n7 2 2 1 1 10 20 30\n5 2 2 1 1 10 30 40\n"
                         "9 1 2 2 2 10 20\n$EndElements\n"
                         "$NodeData\n1\n\"T\"\n1\n0\n3\n0\n1\n4\n10 1\n20 2\n30 3\n40 4\n"
                         "$EndNodeData\n"
                         "$NodeData\n1\n\"T\"\n1\n1\n3\n1\n1\n3\n40 8\n10 5\n20 6\n"
                         "$EndNodeData\n"
                         "$ElementData\n1\n\"the u\"\n1\n0\n3\n0\n2\n3\n5 0.5 1.5\n9 9 9\n"
                         "7 2.5 3.5\n$EndElementData\n";
  const InputMesh mesh = read_gmsh(path);
  ASSERT_EQ(mesh.point_data.size(), 1u);
  EXPECT_EQ(mesh.point_data[0].name, "T");
  ASSERT_EQ(mesh.point_data[0].values.size(), 4u);
  EXPECT_EQ(mesh.point_data[0].values[0], 5);
  EXPECT_EQ(mesh.point_data[0].values[1], 6);
  EXPECT_TRUE(std::isnan(mesh.point_data[0].values[2]));  // not in the last time step
  EXPECT_EQ(mesh.point_data[0].values[3], 8);
  ASSERT_EQ(mesh.cell_data.size(), 1u);
  EXPECT_EQ(mesh.cell_data[0].name, "the u");
  EXPECT_EQ(mesh.cell_data[0].components, 2);
  EXPECT_EQ(mesh.cell_data[0].values, (std::vector<double>{2.5, 3.5, 0.5, 1.5}));
}

// The same file in binary (2.2: int tags and double values after each section's integer
// tags) reads as its ASCII twin above.
TEST(GmshData, ReadsBinaryDataAsItsAsciiTwin) {
  std::string bytes;
  auto put = [&](const auto... values) {
    (bytes.append(reinterpret_cast<const char*>(&values), sizeof(values)), ...);
  };
  auto data = [&](const char* head, std::initializer_list<std::array<double, 3>> entries,
                  int components, const char* end) {
    bytes += head;
    for (const auto& e : entries) {
      put(static_cast<int>(e[0]));
      for (int j = 0; j < components; ++j) put(e[1 + j]);
    }
    bytes += end;
  };
  bytes = "$MeshFormat\n2.2 1 8\n";
  put(1);
  bytes += "\n$EndMeshFormat\n$Nodes\n4\n";
  put(10, 0.0, 0.0, 0.0, 20, 1.0, 0.0, 0.0, 30, 1.0, 1.0, 0.0, 40, 0.0, 1.0, 0.0);
  bytes += "\n$EndNodes\n$Elements\n3\n";
  put(2, 2, 2, 7, 1, 1, 10, 20, 30, 5, 1, 1, 10, 30, 40, 1, 1, 2, 9, 2, 2, 10, 20);
  bytes += "\n$EndElements\n";
  data("$NodeData\n1\n\"T\"\n1\n0\n3\n0\n1\n4\n", {{10, 1}, {20, 2}, {30, 3}, {40, 4}}, 1,
       "\n$EndNodeData\n");
  data("$NodeData\n1\n\"T\"\n1\n1\n3\n1\n1\n3\n", {{40, 8}, {10, 5}, {20, 6}}, 1,
       "\n$EndNodeData\n");
  data("$ElementData\n1\n\"the u\"\n1\n0\n3\n0\n2\n3\n", {{5, .5, 1.5}, {9, 9, 9}, {7, 2.5, 3.5}},
       2, "\n$EndElementData\n");
  const auto path = scratch_dir("GmshDataBinary") / "in.msh";
  std::ofstream(path, std::ios::binary) << bytes;
  const InputMesh mesh = read_gmsh(path);
  ASSERT_EQ(mesh.point_data.size(), 1u);
  const std::vector<double>& t = mesh.point_data[0].values;
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t[0], 5);
  EXPECT_EQ(t[1], 6);
  EXPECT_TRUE(std::isnan(t[2]));
  EXPECT_EQ(t[3], 8);
  ASSERT_EQ(mesh.cell_data.size(), 1u);
  EXPECT_EQ(mesh.cell_data[0].name, "the u");
  EXPECT_EQ(mesh.cell_data[0].values, (std::vector<double>{2.5, 3.5, 0.5, 1.5}));
  // A data section cut short is an error naming it.
  std::ofstream(path, std::ios::binary) << bytes.substr(0, bytes.size() - 30);
  EXPECT_THROW(read_gmsh(path), Error);
}

// A name .msh cannot hold (a quote, a line break) is written readable; .vtu keeps it.
TEST(GmshData, NamesStayOnOneLine) {
  std::string text = kVtu;
  text.replace(text.find("\"temperature\""), 13, "\"te&quot;mp&#10;x\"");
  const auto dir = scratch_dir("GmshDataNames");
  std::ofstream(dir / "in.vtu") << text;
  PlexMesh mesh = load_mesh(dir / "in.vtu");
  ASSERT_EQ(MeshAccess::impl(mesh).point_data[0].name, "te\"mp\nx");
  write_mesh(mesh, dir / "out.msh");
  const InputMesh back = read_gmsh(dir / "out.msh");
  ASSERT_EQ(back.point_data.size(), 2u);
  EXPECT_EQ(back.point_data[0].name, "te'mp x");
  write_mesh(mesh, dir / "out.vtu");  // XML keeps it as it is
  EXPECT_EQ(read_vtu(dir / "out.vtu").point_data[0].name, "te\"mp\nx");
}

// Medit's vertex references are the point data "medit:ref": .mesh -> .vtu -> .mesh keeps them.
TEST(MeditData, VertexReferencesSurviveOtherFormats) {
  const auto dir = scratch_dir("MeditData");
  std::ofstream(dir / "in.mesh") << "MeshVersionFormatted 2\nDimension 2\nVertices\n5\n"
                                    "0 0 3\n1 0 0\n1 1 -4\n0 1 7\n9 9 8\n"
                                    "Triangles\n2\n1 2 3 1\n1 3 4 1\nEnd\n";
  const InputMesh in = read_medit(dir / "in.mesh");
  ASSERT_EQ(in.point_data.size(), 1u);
  EXPECT_EQ(in.point_data[0].name, "medit:ref");
  EXPECT_EQ(in.point_data[0].values, (std::vector<double>{3, 0, -4, 7}));  // not the unused one
  PlexMesh mesh = load_mesh(dir / "in.mesh");
  write_mesh(mesh, dir / "mid.vtu");
  write_mesh(load_mesh(dir / "mid.vtu"), dir / "again.mesh");
  const InputMesh again = read_medit(dir / "again.mesh");
  ASSERT_EQ(again.point_data.size(), 1u);
  EXPECT_EQ(again.point_data[0].values, in.point_data[0].values);
  // All 0: no data.
  write_mesh(PlexMesh::from_data(box(CellType::Triangle, 2), "box"), dir / "box.mesh");
  EXPECT_TRUE(read_medit(dir / "box.mesh").point_data.empty());
}

// An Exodus file written through the library as other programs write it: two blocks, two time
// steps (times 1 and 2), an element variable that only the second block has (truth table), a
// global variable "energy" (100 times the step).
std::filesystem::path two_steps() {
  const auto path = scratch_dir("ExodusVariables") / "in.exo";
  {
    ExodusFile file(path, ExodusFile::Mode::Create, path.string());
    ex_init_params init{};
    init.num_dim = 2;
    init.num_nodes = 5;
    init.num_elem = 2;
    init.num_elem_blk = 2;
    file.check(ex_put_init_ext(file.id(), &init), "init");
    const double x[] = {0, 1, 1, 0, 2}, y[] = {0, 0, 1, 1, 0};
    file.check(ex_put_coord(file.id(), x, y, nullptr), "coord");
    const std::int64_t quad[] = {1, 2, 3, 4}, tri[] = {2, 5, 3};
    file.check(ex_put_block(file.id(), EX_ELEM_BLOCK, 10, "QUAD4", 1, 4, 0, 0, 0), "block");
    file.check(ex_put_conn(file.id(), EX_ELEM_BLOCK, 10, quad, nullptr, nullptr), "conn");
    file.check(ex_put_block(file.id(), EX_ELEM_BLOCK, 20, "TRI3", 1, 3, 0, 0, 0), "block");
    file.check(ex_put_conn(file.id(), EX_ELEM_BLOCK, 20, tri, nullptr, nullptr), "conn");
    char p[] = "p", u[] = "u_x", v[] = "u_y";
    char* nodal[] = {p};
    char* element[] = {u, v};
    file.check(ex_put_variable_param(file.id(), EX_NODAL, 1), "vars");
    file.check(ex_put_variable_names(file.id(), EX_NODAL, 1, nodal), "names");
    file.check(ex_put_variable_param(file.id(), EX_ELEM_BLOCK, 2), "vars");
    file.check(ex_put_variable_names(file.id(), EX_ELEM_BLOCK, 2, element), "names");
    int truth[] = {0, 0, 1, 1};  // block 10: none; block 20: both
    file.check(ex_put_truth_table(file.id(), EX_ELEM_BLOCK, 2, 2, truth), "truth");
    char energy[] = "energy";
    char* global[] = {energy};
    file.check(ex_put_variable_param(file.id(), EX_GLOBAL, 1), "vars");
    file.check(ex_put_variable_names(file.id(), EX_GLOBAL, 1, global), "names");
    for (int step = 1; step <= 2; ++step) {
      const double time = step, e = 100.0 * step;
      file.check(ex_put_time(file.id(), step, &time), "time");
      file.check(ex_put_var(file.id(), step, EX_GLOBAL, 1, 0, 1, &e), "var");
      const double nodes[] = {step * 1.0, step * 2.0, step * 3.0, step * 4.0, step * 5.0};
      file.check(ex_put_var(file.id(), step, EX_NODAL, 1, 1, 5, nodes), "var");
      const double ux = 10.0 * step, uy = -ux;
      file.check(ex_put_var(file.id(), step, EX_ELEM_BLOCK, 1, 20, 1, &ux), "var");
      file.check(ex_put_var(file.id(), step, EX_ELEM_BLOCK, 2, 20, 1, &uy), "var");
    }
    file.close();
  }
  return path;
}

// The last step is the point and cell data; the first block's cells get NaN.
TEST(ExodusVariables, TheLastStepIsReadAndAMissingBlockGetsNaN) {
  const InputMesh mesh = read_exodus(two_steps());
  ASSERT_EQ(mesh.point_data.size(), 1u);
  EXPECT_EQ(mesh.point_data[0].values, (std::vector<double>{2, 4, 6, 8, 10}));
  ASSERT_EQ(mesh.cell_data.size(), 1u);
  EXPECT_EQ(mesh.cell_data[0].name, "u");
  ASSERT_EQ(mesh.cell_data[0].values.size(), 4u);
  EXPECT_TRUE(std::isnan(mesh.cell_data[0].values[0]));
  EXPECT_TRUE(std::isnan(mesh.cell_data[0].values[1]));
  EXPECT_EQ(mesh.cell_data[0].values[2], 20);
  EXPECT_EQ(mesh.cell_data[0].values[3], -20);
}

// Every step, with its time and global variables, is read and written back by .exo.
TEST(ExodusVariables, EveryTimeStepAndTheGlobalVariablesAreKeptByExodus) {
  const auto check = [](const InputMesh& mesh) {
    const TimeSteps& steps = mesh.steps;
    EXPECT_EQ(steps.times, (std::vector<double>{1, 2}));
    EXPECT_EQ(steps.global_names, (std::vector<std::string>{"energy"}));
    EXPECT_EQ(steps.globals, (std::vector<std::vector<double>>{{100}, {200}}));
    ASSERT_EQ(steps.point_data.size(), 1u);
    ASSERT_EQ(steps.point_data[0].size(), 1u);
    EXPECT_EQ(steps.point_data[0][0].values, (std::vector<double>{1, 2, 3, 4, 5}));
    ASSERT_EQ(steps.cell_data.size(), 1u);
    ASSERT_EQ(steps.cell_data[0].size(), 1u);
    const std::vector<double>& u = steps.cell_data[0][0].values;
    ASSERT_EQ(u.size(), 4u);
    EXPECT_TRUE(std::isnan(u[0]));
    EXPECT_EQ(u[2], 10);
    EXPECT_EQ(u[3], -10);
  };
  const auto in = two_steps();
  check(read_exodus(in));
  const auto out = scratch_dir("ExodusSteps") / "out.exo";
  write_mesh(load_mesh(in), out);
  const InputMesh back = read_exodus(out);
  check(back);
  EXPECT_EQ(back.point_data[0].values, (std::vector<double>{2, 4, 6, 8, 10}));
}

TEST(ExodusVariables, VectorsAreWrittenByComponentAndJoinedAgain) {
  const DataArray v{"u", 3, ValueType::Float64, {1, 2, 3, 4, 5, 6}};
  EXPECT_EQ(exodus_variable_names(v), (std::vector<std::string>{"u_x", "u_y", "u_z"}));
  EXPECT_EQ(exodus_variable_names({"p", 1, ValueType::Float64, {}}),
            (std::vector<std::string>{"p"}));
  EXPECT_EQ(exodus_variable_names({"t", 4, ValueType::Float64, {}}),
            (std::vector<std::string>{"t_1", "t_2", "t_3", "t_4"}));
  const std::vector<DataArray> scalars = {{"p", 1, ValueType::Float64, {7, 8}},
                                          {"u_x", 1, ValueType::Float64, {1, 4}},
                                          {"u_y", 1, ValueType::Float64, {2, 5}},
                                          {"u_z", 1, ValueType::Float64, {3, 6}},
                                          {"w_x", 1, ValueType::Float64, {0, 0}}};
  const std::vector<DataArray> joined = join_exodus_variables(scalars);
  ASSERT_EQ(joined.size(), 3u);
  EXPECT_EQ(joined[0].name, "p");
  EXPECT_EQ(joined[1].name, "u");
  EXPECT_EQ(joined[1].components, 3);
  EXPECT_EQ(joined[1].values, v.values);
  EXPECT_EQ(joined[2].name, "w_x");  // alone: a scalar
}

}  // namespace
}  // namespace neomesh
