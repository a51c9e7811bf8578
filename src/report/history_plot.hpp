// A picture of a run's convergence: the Newton defect ‖g‖ and the energy F of every iterate
// on log scales, one panel each, marking the iterates that an antigradient step (−s)
// reached. PNG or SVG by the file's extension.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <neomesh/result.hpp>

namespace neomesh {

struct HistoryPlotOptions {
  int width = 1000, height = 700;
  std::string title;
  // ‖g‖ at the last iterate (Result::final_defect); the records only hold the
  // defect at the start of each iteration, so without it the defect curve ends one short.
  std::optional<double> final_defect;
};

// Iterate 0 is the input mesh (initial_energy, initial_defect); iterate k ≥ 1 is the one
// after history[k-1], with F = history[k-1].energy and ‖g‖ = history[k].defect. Values
// ≤ 0 (F can be exactly 0) are drawn on the lower edge of their axis.
void plot_history(const std::vector<IterationRecord>& history, double initial_energy,
                  double initial_defect, const std::filesystem::path& out,
                  const HistoryPlotOptions& options = {});

}  // namespace neomesh
