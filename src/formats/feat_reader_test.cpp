#include "formats/feat_reader.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"
#include "formats/mesh_test_util.hpp"

namespace neomesh {
namespace {

using testing::data_path;

std::string error_reading(const std::string& text) {
  return testing::read_error(text, "in.xml", [](const auto& path) { read_feat(path); });
}

// `text` in a scratch file `name`.
std::filesystem::path scratch_file(const std::string& name, const std::string& text) {
  const auto path = testing::scratch_dir("ReadFeat") / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// A triangle mesh with `charts` and `parts` spliced in (the cell on line 9).
std::string feat_file(const std::string& charts, const std::string& parts,
                      const std::string& cell = "0 1 2") {
  return "<FeatMeshFile version=\"1\">\n" + charts +
         "<Mesh type=\"conformal:simplex:2:2\" size=\"3 3 1\">\n"
         "<Vertices>\n0 0\n1 0\n0 1\n</Vertices>\n"
         "<Topology dim=\"2\">\n" +
         cell + "\n</Topology>\n</Mesh>\n" + parts + "</FeatMeshFile>\n";
}

TEST(ReadFeat, CommentsAttributeOrderAndWhitespaceDoNotMatter) {
  const MeshData mesh = read_feat(data_path("feat_circle_charts.xml"));
  EXPECT_EQ(mesh.dim, 2);
  EXPECT_EQ(mesh.cell_type, CellType::Quadrilateral);
  EXPECT_EQ(mesh.num_vertices(), 8);
  ASSERT_EQ(mesh.num_cells(), 5);
  EXPECT_EQ(std::vector<std::int64_t>(mesh.cells.end() - 4, mesh.cells.end()),
            (std::vector<std::int64_t>{4, 5, 7, 6}));
  EXPECT_EQ(mesh.coords[3], 1.0);  // vertex 1 = (0, 1), a comment after it
  ASSERT_EQ(mesh.boundary_parts.size(), 3u);
  EXPECT_EQ(mesh.boundary_parts[0].name, "outer");
  EXPECT_EQ(mesh.boundary_parts[0].vertices, (std::vector<std::int64_t>{0, 1, 2, 3, 0}));
}

TEST(ReadFeat, KeepsCirclesBezierCurvesAndExtrusionsAsCharts) {
  const MeshData mesh = read_feat(data_path("feat_circle_charts.xml"));
  ASSERT_EQ(mesh.charts.size(), 3u);
  const Chart& circle = mesh.charts[0];
  EXPECT_EQ(circle.name, "outer");
  EXPECT_EQ(circle.kind, Chart::Kind::Circle);
  EXPECT_EQ(circle.radius, 1.0);
  EXPECT_EQ(circle.centre, (std::array<double, 3>{0, 0, 0}));

  // FEAT3's order: "k", the k control points, then the vertex the segment ends at.
  const Chart& bezier = mesh.charts[1];
  EXPECT_EQ(bezier.kind, Chart::Kind::Bezier);
  EXPECT_EQ(bezier.points,
            (std::vector<double>{0.5, 0, 0.5, 0.5, 0, 0.5, -0.5, 0, 0, -0.5, 0.5, 0}));
  EXPECT_EQ(bezier.vertices, (std::vector<std::int64_t>{0, 2, 3, 4, 5}));
  EXPECT_TRUE(mesh.charts[2].extruded);

  EXPECT_EQ(mesh.boundary_parts[0].chart, "outer");
  EXPECT_EQ(mesh.boundary_parts[1].chart, "square");
  EXPECT_EQ(mesh.boundary_parts[2].chart, "far");
}

// FEAT3's parser splits attributes at their quotes; pugixml needs a blank between them.
TEST(ReadFeat, AttributesWithoutBlankBetweenThemAndEmptyChart) {
  const std::string text = feat_file(
      "<Chart name=\"c\"><Circle radius=\"1\"midpoint=\"0 0\"/></Chart>\n",
      "<MeshPart name=\"a\"chart=\"c\"parent=\"root\">\n<Mapping dim=\"0\">\n0\n</Mapping>\n"
      "</MeshPart>\n<MeshPart name=\"b\" chart=\"\">\n</MeshPart>\n");
  const auto path = scratch_file("attributes.xml", text);
  const MeshData mesh = read_feat(path);
  ASSERT_EQ(mesh.boundary_parts.size(), 2u);
  EXPECT_EQ(mesh.boundary_parts[0].name, "a");
  EXPECT_EQ(mesh.boundary_parts[0].chart, "c");
  EXPECT_EQ(mesh.boundary_parts[1].chart, "");  // chart="": no chart
  EXPECT_EQ(mesh.charts[0].radius, 1.0);
}

// A chart in none of the files: the part is read without chart (a notice, no error).
TEST(ReadFeat, PartOnAChartNoFileDefinesHasNoChart) {
  const MeshData mesh = read_feat(data_path("feat_part_on_missing_chart.xml"));
  ASSERT_EQ(mesh.boundary_parts.size(), 1u);
  EXPECT_EQ(mesh.boundary_parts[0].chart, "");
}

// FEAT3's chart files: a <FeatMeshFile> with charts only, given with the mesh in any order.
TEST(ReadFeat, ChartsComeFromTheOtherFilesInAnyOrder) {
  const std::vector<std::filesystem::path> files = {data_path("feat_chart_file_mesh.xml"),
                                                    data_path("feat_chart_file_charts.xml")};
  for (const auto& order : {files, std::vector(files.rbegin(), files.rend())}) {
    const MeshData mesh = read_feat(order);
    ASSERT_EQ(mesh.charts.size(), 1u);
    EXPECT_EQ(mesh.charts[0].name, "hole");
    EXPECT_EQ(mesh.boundary_parts[0].chart, "hole");
  }
  EXPECT_THROW(read_feat(std::vector{files[1]}), Error);            // no mesh
  EXPECT_THROW(read_feat(std::vector{files[0], files[0]}), Error);  // two meshes
}

TEST(ReadFeat, KeepsSpheresAndSurfaceMeshes) {
  const MeshData mesh = read_feat(data_path("feat_sphere_charts.xml"));
  EXPECT_EQ(mesh.cell_type, CellType::Tetrahedron);
  ASSERT_EQ(mesh.charts.size(), 2u);
  EXPECT_EQ(mesh.charts[0].kind, Chart::Kind::Sphere);
  EXPECT_EQ(mesh.charts[0].radius, 2.0);
  EXPECT_EQ(mesh.charts[1].kind, Chart::Kind::SurfaceMesh);
  EXPECT_EQ(mesh.charts[1].points.size(), 12u);
  EXPECT_EQ(mesh.charts[1].triangles, (std::vector<std::int64_t>{0, 1, 2, 2, 1, 3}));
  EXPECT_EQ(mesh.boundary_parts[0].chart, "lid");
  EXPECT_EQ(mesh.boundary_parts[1].chart, "ball");
}

TEST(ReadFeat, MalformedChartsAreOneLineErrorsWithTheLine) {
  const auto circle = [](const std::string& attributes) {
    return "<Chart name=\"c\">\n<Circle " + attributes + "/>\n</Chart>\n";
  };
  struct Case {
    std::string text, expected;
  };
  const Case cases[] = {
      {feat_file("<Chart name=\"c\">\n<Ellipse a=\"1\"/>\n</Chart>\n", ""),
       "in.xml:3: chart 'c' is a <Ellipse>; neomesh reads Circle, Sphere, Bezier, SurfaceMesh"},
      {feat_file(circle("midpoint=\"0 0\""), ""), "in.xml:3: <Circle> has no radius=\"...\""},
      {feat_file(circle("radius=\"nan\" midpoint=\"0 0\""), ""),
       "in.xml:3: <Circle> radius=\"...\" has 'nan', not a finite number"},
      {feat_file(circle("radius=\"1\" midpoint=\"0 inf\""), ""), "not a finite number"},
      {feat_file(circle("radius=\"1\" midpoint=\"0\""), ""),
       "<Circle> midpoint=\"...\" has 1 numbers, expected 2"},
      {feat_file(circle("radius=\"-1\" midpoint=\"0 0\""), ""), "radius=\"...\" must be positive"},
      {feat_file(circle("radius=\"1\" midpoint=\"0 0\"") + circle("radius=\"2\" midpoint=\"0 0\""),
                 ""),
       "in.xml:5: a second chart named 'c'"},
      {feat_file("<Chart name=\"b\">\n<Bezier dim=\"2\" size=\"2\">\n<Points>\n0 0 0\n1 1 1\n"
                 "</Points>\n</Bezier>\n</Chart>\n",
                 ""),
       "in.xml:6: a <Points> line of a Bezier chart is 'k', k control points and the vertex"},
  };
  for (const Case& c : cases) {
    const std::string message = error_reading(c.text);
    EXPECT_NE(message.find(c.expected), std::string::npos) << message << "\n" << c.text;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(ReadFeat, IndicesOutOfRangeAreErrorsNeverWrapped) {
  EXPECT_NE(error_reading(feat_file("", "", "0 1 4294967296"))
                .find("in.xml:9: '4294967296' in <Topology> is not a valid vertex index"),
            std::string::npos);
  EXPECT_NE(error_reading(feat_file("", "", "0 1 -1")).find("'-1' in <Topology> is not a valid"),
            std::string::npos);
  EXPECT_NE(error_reading(feat_file("", "", "0 1 3"))
                .find("in.xml:9: <Topology> refers to vertex 3, but there are 3"),
            std::string::npos);
  EXPECT_NE(error_reading(feat_file("",
                                    "<MeshPart name=\"p\">\n<Mapping dim=\"0\">\n4294967296\n"
                                    "</Mapping>\n</MeshPart>\n"))
                .find("in.xml:14: '4294967296' in <Mapping> is not a valid vertex index"),
            std::string::npos);
}

TEST(ReadFeat, BadXmlIsAnErrorWithTheLine) {
  EXPECT_NE(error_reading("<FeatMeshFile>\n<Mesh>\n<Vertices a=\"1>\n").find("in.xml:3:"),
            std::string::npos)
      << error_reading("<FeatMeshFile>\n<Mesh>\n<Vertices a=\"1>\n");
  EXPECT_NE(error_reading("<FeatMeshFile>\n<Mesh type=\"conformal:hypercube:2:2\" size=\"1\">\n"
                          "<Vertices>\n0 0\n1 2 3\n</Vertices>\n</Mesh>\n</FeatMeshFile>\n")
                .find("in.xml:5: expected 2 numbers per line in <Vertices>, found 3"),
            std::string::npos);
  EXPECT_NE(error_reading("<Other/>").find("expected <FeatMeshFile>, found <Other>"),
            std::string::npos);
}

TEST(ReadFeat, ThousandsOfNestedTagsAndHugeAttributesAreHarmless) {
  std::string deep = "<FeatMeshFile>\n<Info>";
  for (int i = 0; i < 100000; ++i) deep += "<a>";
  for (int i = 0; i < 100000; ++i) deep += "</a>";
  deep += "</Info>\n</FeatMeshFile>\n";
  EXPECT_NE(error_reading(deep).find("no <Mesh> block"), std::string::npos);
  const std::string long_name(100000, 'x');
  // A part on a chart no file defines is read without it (a notice, no error).
  EXPECT_EQ(error_reading(feat_file("", "<MeshPart name=\"" + long_name + "\" chart=\"" +
                                            long_name + "\">\n</MeshPart>\n")),
            "");
}

}  // namespace
}  // namespace neomesh
