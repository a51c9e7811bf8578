#include "report/history_plot.hpp"

#include <cmath>

#include <cairo.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"

namespace neomesh {
namespace {

// A run like the thesis' tables: two antigradient steps, then quasi-Newton steps with a
// superlinearly falling defect, F reaching round-off and finally exactly 0.
std::vector<IterationRecord> converging_run() {
  std::vector<IterationRecord> history;
  double defect = 3.2, energy = 1.4;
  for (int k = 1; k <= 12; ++k) {
    IterationRecord rec;
    rec.k = k;
    rec.defect = defect;
    rec.used_s = k <= 2;
    energy = k == 12 ? 0.0 : energy * std::pow(10.0, -0.3 * k);
    rec.energy = energy;
    history.push_back(rec);
    defect *= std::pow(10.0, -0.15 * k);
  }
  return history;
}

double non_white_fraction(cairo_surface_t* s) {
  cairo_surface_flush(s);
  const int width = cairo_image_surface_get_width(s), height = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  long count = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      count +=
          (reinterpret_cast<const std::uint32_t*>(data + y * stride)[x] & 0xffffff) != 0xffffff;
  return static_cast<double>(count) / (width * height);
}

TEST(PlotHistory, ConvergingRunToPng) {
  const auto dir = testing::scratch_dir("history_png");
  const auto history = converging_run();
  HistoryPlotOptions options;
  options.width = 900, options.height = 600;
  options.title = "square, 16 x 16 quads";
  options.final_defect = 1e-11;
  plot_history(history, 2.1, 3.2, dir / "history.png", options);

  cairo_surface_t* png = cairo_image_surface_create_from_png((dir / "history.png").c_str());
  ASSERT_EQ(cairo_surface_status(png), CAIRO_STATUS_SUCCESS);
  EXPECT_EQ(cairo_image_surface_get_width(png), 900);
  EXPECT_EQ(cairo_image_surface_get_height(png), 600);
  EXPECT_GT(non_white_fraction(png), 0.02);  // axes, grid, text and two curves
  cairo_surface_destroy(png);
}

TEST(PlotHistory, LongStallingRunToPng) {
  const auto dir = testing::scratch_dir("history_long");
  std::vector<IterationRecord> history(150);
  for (int i = 0; i < 150; ++i) {
    history[i].k = i + 1;
    history[i].defect = 1e-3 / (1 + i) + 1e-9;
    history[i].energy = 1e-2 / (1 + i * i) + 1e-31;
    history[i].used_s = i % 17 == 0;
  }
  plot_history(history, 0.5, 1e-2, dir / "long.png");
  cairo_surface_t* png = cairo_image_surface_create_from_png((dir / "long.png").c_str());
  ASSERT_EQ(cairo_surface_status(png), CAIRO_STATUS_SUCCESS);
  EXPECT_EQ(cairo_image_surface_get_width(png), HistoryPlotOptions{}.width);
  EXPECT_GT(non_white_fraction(png), 0.02);
  cairo_surface_destroy(png);
}

TEST(PlotHistory, NoIterationsAndNonPositiveValuesToSvg) {
  const auto dir = testing::scratch_dir("history_svg");
  plot_history({}, 0.0, 0.0, dir / "empty.svg");
  EXPECT_TRUE(std::filesystem::exists(dir / "empty.svg"));
}

TEST(PlotHistory, UnknownExtensionFails) {
  const auto dir = testing::scratch_dir("history_errors");
  EXPECT_THROW(plot_history(converging_run(), 1.0, 1.0, dir / "history.pdf"), Error);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace
}  // namespace neomesh
