#include "report/quality_report.hpp"

#include <fmt/format.h>

#include "mesh/cell_type.hpp"

namespace neomesh {

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
  return {{"cells", cells},
          {"metrics", metrics},
          {"inverted", s.inverted},
          {"degenerate", s.degenerate}};
}

nlohmann::json to_json(const VolumeRatioStats& s) {
  return {{"cells", s.cells},
          {"fraction_in_0.5_2", s.within},
          {"min", s.min},
          {"median", s.median},
          {"max", s.max}};
}

}  // namespace neomesh
