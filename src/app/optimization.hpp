// One optimization run as `smooth` and `adapt` share it: read and check the mesh, build the
// functional with fixed or sliding boundary vertices, print the iteration table while the method
// runs, then check, write and report the result. The commands differ only in how they choose the
// desired volumes and drive the quasi-Newton method.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/method_options.hpp"
#include "energy/functional.hpp"
#include "geometry/quality.hpp"
#include "mesh/mesh.hpp"
#include "mesh/mesh_io.hpp"
#include "solver/quasi_newton.hpp"

namespace neomesh::app {

// Throws Error unless `output` has a writable format and differs from `input` (or `force`).
// Collective (every rank throws).
void check_output_path(const std::filesystem::path& input, const std::filesystem::path& output,
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
// Once the mesh is read, before the run: throws Error if `outputs` asks for a picture of a
// mesh of dimension `dim` that cannot be drawn (3D).
void check_run_outputs(const RunOutputs& outputs, int dim);

class OptimizationRun {
 public:
  // With InvertedCells::Keep, a mesh with inverted cells is read as it is, for untangle().
  OptimizationRun(const std::filesystem::path& input, MethodOptions& method,
                  InvertedCells inverted = InvertedCells::Refuse);
  ~OptimizationRun();

  const MeshView& view() const;
  const DofMap& dofs() const;
  Vec x() const;  // the coordinates being optimized
  // Volume of each local cell of the input mesh (MeshView order).
  const std::vector<double>& input_volumes() const;
  double mesh_volume() const;

  // (Re)sets the desired cell volumes (absolute, summing to mesh_volume()).
  void set_desired_volumes(std::vector<double> volumes);
  const Functional& functional() const;
  // Rebuilds the functional with `extra` vertices sliding besides the boundary's (an
  // interface fitted to a level set; none: the boundary's alone), keeping the desired volumes.
  const Functional& constrain(SlidingVertices extra);
  // Fields and facet groups every later output carries besides the run's own.
  void set_extra_outputs(MeshFields extra);
  Vec cell_size() const;  // local cell size per dof, for the practical criterion

  void print_problem() const;
  // Draws the mesh at its current coordinates coloured by `field` (an output cell field).
  void draw(const std::filesystem::path& path, const std::string& field,
            const std::string& title) const;
  // Observer for minimize(): the iteration table (or progress lines with `progress_only`).
  std::function<void(const IterationRecord&)> table_printer(bool progress_only) const;
  // If cells are inverted at x(), untangles them (solver/untangle.hpp), printing its table;
  // returns the report's "untangling" record (empty if nothing was inverted). Throws Error
  // naming the cells that stay inverted. Needs the desired volumes.
  nlohmann::json untangle(bool progress_only);

  // Moves the mesh to x(), checks it has no inverted cell and writes `output` with per-cell
  // fields (one step of a time series); returns its quality.
  QualitySummary snapshot(const std::filesystem::path& output);
  // Moves the mesh to x(), checks it has no inverted cell, writes `output` with per-cell
  // fields, and the optional JSON report (with `extra` merged in), history plot and picture.
  void finish(const QuasiNewtonResult& result, const std::filesystem::path& output,
              const RunOutputs& outputs, const nlohmann::json& extra = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace neomesh::app
