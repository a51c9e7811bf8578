#include "report/quality_report.hpp"

#include <gtest/gtest.h>

#include "generate/generate.hpp"
#include "generate/serial_view.hpp"
#include "geometry/quality.hpp"

namespace neomesh {
namespace {

TEST(QualityReport, TableAndJsonOfSquareMidpointLevel3) {
  const MeshView view = serial_view(square_midpoint(16));
  const QualitySummary s = summarize(cell_quality(view, view.coords), PETSC_COMM_SELF);
  EXPECT_NE(format_table(s).find("256 quadrilaterals"), std::string::npos);
  const nlohmann::json j = to_json(s);
  EXPECT_EQ(j["cells"]["quadrilateral"], 256);
  EXPECT_EQ(j["inverted"], 0);
  EXPECT_DOUBLE_EQ(j["metrics"]["volume"]["max"].get<double>(), s.volume.max);
}

TEST(QualityReport, VolumeRatioJson) {
  const nlohmann::json j =
      to_json(VolumeRatioStats{.cells = 4, .within = 0.5, .min = 0.25, .median = 1.0, .max = 3.0});
  EXPECT_EQ(j["cells"], 4);
  EXPECT_DOUBLE_EQ(j["fraction_in_0.5_2"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["median"].get<double>(), 1.0);
}

}  // namespace
}  // namespace neomesh
