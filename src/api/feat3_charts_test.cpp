// FEAT3 meshes smoothed as FEAT3 reads them: vertices off their charts projected onto them,
// chart files given with the mesh, exact Bezier charts, one patch per sphere.
#include <neomesh/mesh.hpp>
#include <neomesh/optimizer.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include <neomesh/error.hpp>

#include "boundary/shape.hpp"
#include "core/testing/test_data.hpp"
#include "formats/feat_reader.hpp"

namespace neomesh {
namespace {

using testing::data_path;

// The FEAT3 meshes of the shared corpus (../shared/corpus from the repository root).
std::filesystem::path corpus(const std::string& name) {
  return data_path("../../../shared/corpus/feat3") / name;
}
#define SKIP_WITHOUT_CORPUS()               \
  if (!std::filesystem::exists(corpus(""))) \
  GTEST_SKIP() << "no corpus at " << corpus("").string() << ": test skipped"

const std::vector<std::filesystem::path> kCircleFiles = {data_path("feat_chart_file_charts.xml"),
                                                         data_path("feat_chart_file_mesh.xml")};

TEST(Feat3Charts, SmoothMovesAVertexOffItsCircleOntoIt) {
  Mesh mesh = Mesh::read(kCircleFiles, MPI_COMM_WORLD);
  Optimizer optimizer(mesh);
  const Result result = optimizer.smooth();
  EXPECT_EQ(result.problem.boundary.moved_onto_charts, 1);  // (0, 1.02); the others are on
  EXPECT_NEAR(result.problem.boundary.max_move_onto_charts, 0.02, 1e-15);
  const std::vector<double> x = mesh.coordinates();
  const std::vector<std::int64_t> numbers = mesh.vertex_numbers();
  for (std::size_t i = 0; i < numbers.size(); ++i) {
    if (numbers[i] < 4) {
      EXPECT_NEAR(std::hypot(x[2 * i], x[2 * i + 1]), 1.0, 1e-12) << numbers[i];
    }
  }
  EXPECT_EQ(result.quality_after.inverted, 0);
}

// quality and convert take the file as it is: no projection, no chart check.
TEST(Feat3Charts, ReadingAloneLeavesTheVertexWhereItIs) {
  const Mesh mesh = Mesh::read(kCircleFiles, MPI_COMM_WORLD);
  const std::vector<double> x = mesh.coordinates();
  const std::vector<std::int64_t> numbers = mesh.vertex_numbers();
  for (std::size_t i = 0; i < numbers.size(); ++i) {
    if (numbers[i] == 1) {
      EXPECT_EQ(x[2 * i + 1], 1.02);
    }
  }
}

TEST(Feat3Charts, AChartFarFromItsPartIsRefusedWithTheDistance) {
  const auto dir = testing::scratch_dir("Feat3Charts");
  std::ofstream(dir / "far.xml") << "<FeatMeshFile version=\"1\"><Chart name=\"hole\">"
                                    "<Circle radius=\"1\" midpoint=\"20 0\"/></Chart>"
                                    "</FeatMeshFile>\n";
  Mesh mesh = Mesh::read({data_path("feat_chart_file_mesh.xml"), dir / "far.xml"}, MPI_COMM_WORLD);
  Optimizer optimizer(mesh);
  try {
    optimizer.smooth();
    ADD_FAILURE() << "a chart 19 away accepted";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("chart 'hole' of part 'outer'"), std::string::npos) << message;
    EXPECT_NE(message.find("times the local mesh size"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// Exact Bezier charts: after smoothing, every boundary vertex is on its screw's curve to
// round-off (a sampled polyline left vertices 0.00184 off).
TEST(Feat3Charts, RotorVerticesStayOnTheirBezierChartsExactly) {
  SKIP_WITHOUT_CORPUS();
  const std::vector<std::filesystem::path> files = {
      corpus("screws_2d_mesh_quad_smaller_360_1.xml"),
      corpus("screws_2d_chart_bezier_24_28_smaller.xml")};
  Mesh mesh = Mesh::read(files, MPI_COMM_WORLD);
  Optimizer optimizer(mesh);
  const Result result = optimizer.smooth();
  EXPECT_GT(result.quality_after.scaled_jacobian.min, result.quality_before.scaled_jacobian.min);
  const MeshData data = read_feat(files);
  std::vector<std::unique_ptr<Surface>> charts;
  for (const Chart& c : data.charts) {
    std::vector<Point> controls;
    for (std::size_t i = 0; i + 1 < c.points.size(); i += 2)
      controls.emplace_back(c.points[i], c.points[i + 1], 0.0);
    charts.push_back(make_bezier(controls, std::vector<int>(c.vertices.begin(), c.vertices.end())));
  }
  const std::vector<double> x = mesh.coordinates();
  const std::vector<std::int64_t> numbers = mesh.vertex_numbers();
  int checked = 0;
  for (const VertexSet& part : data.boundary_parts) {
    if (part.chart.empty()) continue;
    const Surface& chart = *charts[part.chart == data.charts[0].name ? 0 : 1];
    for (std::int64_t v : part.vertices) {
      const auto at = std::lower_bound(numbers.begin(), numbers.end(), v) - numbers.begin();
      const Point p(x[2 * at], x[2 * at + 1], 0.0);
      EXPECT_LT((chart.closest_point(p) - p).norm(), 1e-12) << "vertex " << v;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

// The 6 faces of the coarse sphere meet at large angles, but a sphere has no ridges: one
// patch, and smoothing ends (it hung assembling 12 ridges between the sphere and itself).
TEST(Feat3Charts, SphereIsOnePatch) {
  SKIP_WITHOUT_CORPUS();
  Mesh mesh = Mesh::read(corpus("unit_sphere_hexa_32.xml"), MPI_COMM_WORLD);
  Optimizer optimizer(mesh);
  const Result result = optimizer.smooth();
  EXPECT_EQ(result.problem.boundary.patches, 1);
  EXPECT_EQ(result.problem.boundary.ridges, 0);
  // Ended by converging, not by the iteration limit (a hang is ctest's timeout).
  EXPECT_LT(result.history.size(), 30u);
  EXPECT_EQ(result.quality_after.inverted, 0);
}

}  // namespace
}  // namespace neomesh
