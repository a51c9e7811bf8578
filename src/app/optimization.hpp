// One optimization run as `smooth` and `adapt` share it, around the library's Optimizer
// (include/neomesh/optimizer.hpp): read the mesh, print what the Optimizer tells while it runs
// (the problem, the iteration table, the untangling phases), then write the result with its
// per-cell fields, the JSON report, the history plot and the pictures.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <neomesh/mesh.hpp>
#include <neomesh/optimizer.hpp>

namespace neomesh::app {

// Throws Error unless `output` has a writable format and differs from `input` (or `force`).
// Collective (every rank throws).
void check_output_path(const std::vector<std::string>& inputs, const std::filesystem::path& output,
                       bool force);

// What a run writes besides the mesh, shared by smooth and adapt: the JSON report, the
// history plot, the iteration table or progress lines, and pictures of a 2D run coloured by
// one of the output's cell fields (Q and the energy need the run's desired volumes, which a
// mesh file does not keep, so the run draws them itself).
struct RunOutputs {
  std::string report, history_plot;           // empty: none
  std::string picture_before, picture_after;  // .png or .svg; empty: none
  std::string picture_field;
  bool progress_lines = false;  // instead of the iteration table
};
void add_run_output_options(CLI::App& cmd, RunOutputs& outputs, const std::string& picture_field);
// Throws Error for an unwritable or unknown-format path, before the run costs any time.
// Collective (every rank throws).
void check_run_outputs(const RunOutputs& outputs);

// The options a run prints and reports.
struct RunSettings {
  EnergyOptions energy;
  SolverOptions solver;
  BoundaryOptions boundary;
};

class OptimizationRun {
 public:
  // `inputs`: the mesh file, with the chart files of a FEAT3 mesh (any order).
  OptimizationRun(const std::vector<std::string>& inputs, InvertedCells inverted);
  ~OptimizationRun();

  Mesh& mesh();
  Optimizer& optimizer();

  // What the run prints while the Optimizer works: the problem, the untangling phases, the
  // iteration table (or progress lines with `progress_only`), the updates of the desired
  // volumes, and with --verbose the linear solves. `before_run` runs once the problem is set
  // up (the desired volumes are known), before the first iteration: the picture of the input.
  Observer observer(const RunSettings& settings, bool progress_only,
                    std::function<void()> before_run = {});

  // Draws the mesh at its current coordinates coloured by `field` (an output cell field).
  void draw(const std::filesystem::path& path, const std::string& field,
            const std::string& title) const;
  // Writes `output` with the optimizer's fields and facet groups (one step of a time series).
  void snapshot(const std::filesystem::path& output) const;
  // Prints the outcome and the quality before and after, writes `output` with per-cell fields,
  // and the optional JSON report (with `extra` merged in: the options, to_json(SmoothOptions)
  // or to_json(AdaptOptions), and what the task adds), history plot and picture.
  void finish(const Result& result, const RunSettings& settings,
              const std::filesystem::path& output, const RunOutputs& outputs,
              const nlohmann::json& extra = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace neomesh::app
