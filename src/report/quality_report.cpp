#include "report/quality_report.hpp"

#include <fmt/format.h>

#include "mesh/cell_type.hpp"

namespace neomesh {

namespace {

// The curved cells' lines below the straight cells' table.
std::string format_curved(const CurvedQualitySummary& c) {
  std::string out = "curved cells:";
  for (const auto& [type, count] : c.cells_by_type) out += fmt::format(" {} {}", count, type);
  out += fmt::format(
      "\nnot certified valid: {} (invalid {}, undecided {})\n"
      "curved scaled Jacobian (least over each cell, sampled): min {:.6g}, mean {:.6g}, max "
      "{:.6g}; certified lower bound {:.6g}\n",
      c.not_valid, c.invalid, c.undecided, c.scaled_jacobian.min, c.scaled_jacobian.mean,
      c.scaled_jacobian.max, c.scaled_jacobian_lower_bound);
  return out;
}

nlohmann::json curved_json(const CurvedQualitySummary& c) {
  nlohmann::json cells = nlohmann::json::object();
  for (const auto& [type, count] : c.cells_by_type) cells[type] = count;
  const MetricStats& q = c.scaled_jacobian;
  return {{"cells", cells},
          {"not_certified_valid", c.not_valid},
          {"invalid", c.invalid},
          {"undecided", c.undecided},
          {"scaled_jacobian", {{"min", q.min}, {"mean", q.mean}, {"max", q.max}}},
          {"scaled_jacobian_lower_bound", c.scaled_jacobian_lower_bound}};
}

}  // namespace

std::string format_table(const QualitySummary& s) {
  std::string out = fmt::format("cells: {}", s.cells);
  for (int t = 0; t < kNumCellTypes; ++t)
    if (s.cells_by_type[t] > 0)
      out += fmt::format(", {} {}", s.cells_by_type[t], plural_name(static_cast<CellType>(t)));
  out += fmt::format("\n{:<18}{:>14}{:>14}{:>14}\n", "metric", "min", "mean", "max");
  for (const auto& [metric, stats] : s.metrics())
    out += fmt::format("{:<18}{:>14.6g}{:>14.6g}{:>14.6g}\n", metric, stats.min, stats.mean,
                       stats.max);
  out += fmt::format("inverted cells: {}, degenerate cells: {}\n", s.inverted, s.degenerate);
  if (s.curved) out += format_curved(*s.curved);
  return out;
}

nlohmann::json to_json(const QualitySummary& s) {
  nlohmann::json cells = {{"total", s.cells}};
  for (int t = 0; t < kNumCellTypes; ++t)
    if (s.cells_by_type[t] > 0)
      cells[std::string(name(static_cast<CellType>(t)))] = s.cells_by_type[t];
  nlohmann::json metrics = nlohmann::json::object();
  for (const auto& [metric, stats] : s.metrics())
    metrics[std::string(metric)] = {{"min", stats.min}, {"mean", stats.mean}, {"max", stats.max}};
  nlohmann::json json = {{"cells", cells},
                         {"metrics", metrics},
                         {"inverted", s.inverted},
                         {"degenerate", s.degenerate}};
  if (s.curved) json["curved"] = curved_json(*s.curved);
  return json;
}

nlohmann::json to_json(const VolumeRatioStats& s) {
  return {{"cells", s.cells},
          {"fraction_in_0.5_2", s.within},
          {"min", s.min},
          {"median", s.median},
          {"max", s.max}};
}

}  // namespace neomesh
