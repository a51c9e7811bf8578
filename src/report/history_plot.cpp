#include "report/history_plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include <fmt/format.h>

#include "core/error.hpp"
#include "report/canvas.hpp"

namespace neomesh {

namespace {

constexpr Rgb kInk{0.15, 0.15, 0.15};
constexpr Rgb kGrid{0.89, 0.89, 0.89};
constexpr Rgb kDefectColour{0.12, 0.47, 0.71};
constexpr Rgb kEnergyColour{0.84, 0.37, 0.0};
constexpr int kMinSize = 200, kMaxSize = 20000;
constexpr int kMaxDecadeLabels = 8;  // more would crowd a panel; label every 2nd, 5th, ... decade
constexpr int kMaxIterationTicks = 10;

// One point of a curve: iterate k, value, and whether an antigradient step reached it.
struct Point {
  double k = 0, value = 0;
  bool antigradient = false;
};

std::vector<Point> defect_points(const std::vector<IterationRecord>& history, double initial_defect,
                                 std::optional<double> final_defect) {
  std::vector<Point> points{{0, initial_defect, false}};
  for (std::size_t i = 1; i < history.size(); ++i)
    points.push_back({double(i), history[i].defect, history[i - 1].used_s});
  if (final_defect && !history.empty())
    points.push_back({double(history.size()), *final_defect, history.back().used_s});
  return points;
}

std::vector<Point> energy_points(const std::vector<IterationRecord>& history,
                                 double initial_energy) {
  std::vector<Point> points{{0, initial_energy, false}};
  for (std::size_t i = 0; i < history.size(); ++i)
    points.push_back({double(i + 1), history[i].energy, history[i].used_s});
  return points;
}

// A log10 axis over whole decades from `lo` to `hi`, drawn from pixel `bottom` up to `top`.
// Values outside (≤ 0 in particular) are clamped to its ends.
struct LogAxis {
  int lo = -1, hi = 1, label_step = 1;
  double top = 0, bottom = 0;

  double y(double v) const {
    const double d = v > 0 ? std::clamp(std::log10(v), double(lo), double(hi)) : lo;
    return bottom - (d - lo) / (hi - lo) * (bottom - top);
  }
  static bool off_scale(double v) { return v <= 0 || std::isinf(v); }
};

LogAxis log_axis(std::span<const Point> points, double top, double bottom) {
  double min = std::numeric_limits<double>::infinity(), max = 0;
  for (const Point& p : points)
    if (p.value > 0 && std::isfinite(p.value))
      min = std::min(min, p.value), max = std::max(max, p.value);
  LogAxis axis;
  axis.top = top, axis.bottom = bottom;
  if (max == 0) return axis;  // nothing positive: an arbitrary axis around 1
  axis.lo = static_cast<int>(std::floor(std::log10(min)));
  axis.hi = static_cast<int>(std::ceil(std::log10(max)));
  if (axis.hi == axis.lo) --axis.lo, ++axis.hi;
  axis.label_step = std::max(1, (axis.hi - axis.lo + kMaxDecadeLabels - 1) / kMaxDecadeLabels);
  // Both ends on labelled decades (floor/ceil towards −∞/+∞ for negative exponents too).
  const int s = axis.label_step;
  axis.lo = static_cast<int>(std::floor(double(axis.lo) / s)) * s;
  axis.hi = static_cast<int>(std::ceil(double(axis.hi) / s)) * s;
  return axis;
}

// Iterates 0..n along x, ticks every 1, 2, 5, 10, ... iterations.
struct IterationAxis {
  int n = 1, step = 1;
  double left = 0, right = 0;
  double x(double k) const {
    const double pad = 0.02 * (right - left);
    return left + pad + k / n * (right - left - 2 * pad);
  }
};

IterationAxis iteration_axis(int n, double left, double right) {
  IterationAxis axis{std::max(n, 1), 1, left, right};
  for (int scale = 1;; scale *= 10)
    for (int m : {1, 2, 5})
      if (axis.n / (m * scale) <= kMaxIterationTicks) {
        axis.step = m * scale;
        return axis;
      }
}

// "10" with a raised exponent, right-aligned at x.
void draw_power_of_ten(cairo_t* cr, int exponent, double x, double y, double font) {
  const std::string e =
      exponent < 0 ? fmt::format("\u2212{}", -exponent) : fmt::format("{}", exponent);
  const double small = 0.72 * font;
  const double e_width = text_width(e, small);
  draw_text(cr, "10", x - e_width - 0.05 * font, y, font, Anchor::Right);
  draw_text(cr, e, x - e_width, y - 0.45 * font, small);
}

void draw_marker(cairo_t* cr, double x, double y, double r, const Rgb& colour, bool hollow,
                 bool off_scale_low, bool off_scale_high) {
  if (off_scale_low || off_scale_high) {  // a triangle pointing off the axis
    const double dir = off_scale_low ? 1 : -1;
    cairo_move_to(cr, x - 1.2 * r, y - dir * 1.1 * r);
    cairo_line_to(cr, x + 1.2 * r, y - dir * 1.1 * r);
    cairo_line_to(cr, x, y + dir * 0.9 * r);
    cairo_close_path(cr);
  } else {
    cairo_new_sub_path(cr);
    cairo_arc(cr, x, y, r, 0, 2 * M_PI);
  }
  set_colour(cr, hollow ? Rgb{1, 1, 1} : colour);
  cairo_fill_preserve(cr);
  set_colour(cr, colour);
  cairo_set_line_width(cr, 0.35 * r);
  cairo_stroke(cr);
}

struct Panel {
  std::vector<Point> points;
  Rgb colour;
  std::string label;
};

void draw_panel(cairo_t* cr, const Panel& panel, const LogAxis& y, const IterationAxis& x,
                double font) {
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  // Grid: every labelled decade and every iteration tick.
  set_colour(cr, kGrid);
  cairo_set_line_width(cr, 1.0);
  for (int d = y.lo; d <= y.hi; d += y.label_step) {
    cairo_move_to(cr, x.left, y.y(std::pow(10.0, d)));
    cairo_line_to(cr, x.right, y.y(std::pow(10.0, d)));
  }
  for (int k = 0; k <= x.n; k += x.step) {
    cairo_move_to(cr, x.x(k), y.top);
    cairo_line_to(cr, x.x(k), y.bottom);
  }
  cairo_stroke(cr);

  // Frame, then decade ticks: long and labelled, or short between labels.
  set_colour(cr, kInk);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, x.left, y.top, x.right - x.left, y.bottom - y.top);
  cairo_stroke(cr);
  const double tick = 0.4 * font;
  for (int d = y.lo; d <= y.hi; ++d) {
    const bool labelled = (d - y.lo) % y.label_step == 0;
    const double py = y.y(std::pow(10.0, d));
    cairo_move_to(cr, x.left - (labelled ? tick : 0.5 * tick), py);
    cairo_line_to(cr, x.left, py);
    cairo_stroke(cr);
    if (labelled) draw_power_of_ten(cr, d, x.left - 1.6 * tick, py, font);
  }
  for (int k = 0; k <= x.n; k += x.step) {
    cairo_move_to(cr, x.x(k), y.bottom);
    cairo_line_to(cr, x.x(k), y.bottom + tick);
  }
  cairo_stroke(cr);
  draw_vertical_text(cr, panel.label, x.left - 5.2 * font, 0.5 * (y.top + y.bottom), font);

  // The curve through every point (NaN ones skipped), then the markers on top.
  set_colour(cr, panel.colour);
  cairo_set_line_width(cr, 1.6);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const Point& p : panel.points)
    if (!std::isnan(p.value)) cairo_line_to(cr, x.x(p.k), y.y(p.value));
  cairo_stroke(cr);
  const double r = std::min(0.3 * font, std::max(1.0, 0.45 * (x.x(1) - x.x(0))));
  for (const Point& p : panel.points)
    if (!std::isnan(p.value))
      draw_marker(cr, x.x(p.k), y.y(p.value), r, panel.colour, p.antigradient, p.value <= 0,
                  std::isinf(p.value));
}

void draw_iteration_labels(cairo_t* cr, const IterationAxis& x, double bottom, double font) {
  set_colour(cr, kInk);
  for (int k = 0; k <= x.n; k += x.step)
    draw_text(cr, fmt::format("{}", k), x.x(k), bottom + 1.3 * font, font, Anchor::Center);
  draw_text(cr, "iterate k (0: input mesh)", 0.5 * (x.left + x.right), bottom + 3.0 * font, font,
            Anchor::Center);
}

// Which marker means what, in the top-right corner of the upper panel.
void draw_legend(cairo_t* cr, double right, double top, double font, bool any_off_scale) {
  struct Entry {
    const char* text;
    bool hollow, off_scale;
  };
  std::vector<Entry> entries = {{"quasi-Newton step", false, false},
                                {"antigradient step (\u2212s)", true, false}};
  if (any_off_scale) entries.push_back({"off scale (\u2264 0)", false, true});
  double width = 0;
  for (const Entry& e : entries) width = std::max(width, text_width(e.text, font));
  const double line = 1.6 * font, pad = 0.7 * font;
  const double box_w = width + 2.2 * font + 2 * pad, box_h = entries.size() * line + pad;
  const double left = right - box_w - 0.8 * font, y0 = top + 0.8 * font;
  cairo_rectangle(cr, left, y0, box_w, box_h);
  set_colour(cr, {1, 1, 1}, 0.9);
  cairo_fill_preserve(cr);
  set_colour(cr, {0.75, 0.75, 0.75});
  cairo_set_line_width(cr, 0.8);
  cairo_stroke(cr);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const double y = y0 + pad / 2 + (i + 0.5) * line;
    draw_marker(cr, left + pad + 0.5 * font, y, 0.32 * font, kInk, entries[i].hollow,
                entries[i].off_scale, false);
    set_colour(cr, kInk);
    draw_text(cr, entries[i].text, left + pad + 1.6 * font, y, font);
  }
}

}  // namespace

void plot_history(const std::vector<IterationRecord>& history, double initial_energy,
                  double initial_defect, const std::filesystem::path& out,
                  const HistoryPlotOptions& options) {
  const int W = options.width, H = options.height;
  if (std::min(W, H) < kMinSize || std::max(W, H) > kMaxSize)
    fail("history plot size {}x{} is outside {}..{}", W, H, kMinSize, kMaxSize);
  const Panel defect{defect_points(history, initial_defect, options.final_defect), kDefectColour,
                     "Newton defect \u2016g\u2016"};
  const Panel energy{energy_points(history, initial_energy), kEnergyColour, "energy F"};

  const double font = std::max(10.0, 0.014 * W), title_font = 1.3 * font;
  const double left = 0.03 * W + 6.4 * font, right = W - 0.03 * W;
  const double top = 0.03 * H + 0.8 * font + (options.title.empty() ? 0 : 2.4 * title_font);
  const double bottom = H - 0.03 * H - 3.6 * font, gap = 2.0 * font;
  const double panel_height = 0.5 * (bottom - top - gap);
  const IterationAxis x = iteration_axis(static_cast<int>(history.size()), left, right);
  const LogAxis defect_axis = log_axis(defect.points, top, top + panel_height);
  const LogAxis energy_axis = log_axis(energy.points, bottom - panel_height, bottom);

  Canvas canvas(out, W, H);
  cairo_t* cr = canvas.cr();
  if (!options.title.empty()) {
    set_colour(cr, kInk);
    draw_text(cr, options.title, left, 0.03 * H + 0.6 * title_font, title_font, Anchor::Left, true);
  }
  draw_panel(cr, defect, defect_axis, x, font);
  draw_panel(cr, energy, energy_axis, x, font);
  draw_iteration_labels(cr, x, bottom, font);
  bool any_off_scale = false;
  for (const Panel* p : {&defect, &energy})
    for (const Point& point : p->points) any_off_scale |= LogAxis::off_scale(point.value);
  draw_legend(cr, right, top, 0.9 * font, any_off_scale);
  canvas.finish();
}

}  // namespace neomesh
