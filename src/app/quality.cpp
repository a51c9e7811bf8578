// `neomesh quality`: the quality summary of a mesh file, as a table and optionally JSON.
#include <memory>
#include <string>

#include "app/checks.hpp"
#include "app/subcommand.hpp"
#include "core/atomic_file.hpp"
#include "core/log.hpp"
#include "geometry/quality.hpp"
#include "mesh/collective_error.hpp"
#include "mesh/mesh.hpp"
#include "mesh/mesh_io.hpp"

namespace neomesh::app {

namespace {

struct QualityOptions {
  std::string input;
  std::string json;
};

void run_quality(const QualityOptions& o) {
  collectively(PETSC_COMM_WORLD, [&] {
    check_readable_format(o.input);
    if (!o.json.empty()) check_output_file("--json", o.json, OutputKind::Json);
  });
  // Inverted and degenerate cells are what this command counts, not a reason to refuse.
  const Mesh mesh = [&] {
    const Activity reading("reading " + o.input);
    return Mesh::load(o.input, PETSC_COMM_WORLD, InvertedCells::Keep);
  }();
  const MeshView& view = mesh.view();
  const QualitySummary summary = summarize(cell_quality(view, view.coords), mesh.comm());
  always("{}\n{}", o.input, format_table(summary));
  if (!o.json.empty())
    on_root(mesh.comm(), [&] {
      AtomicFile file(o.json);
      file.stream() << to_json(summary).dump(2) << '\n';
      file.commit();
    });
}

}  // namespace

Subcommand add_quality(CLI::App& app) {
  auto options = std::make_shared<QualityOptions>();
  CLI::App* cmd = app.add_subcommand(
      "quality",
      "Print the quality of a mesh: cells by type, min/mean/max of the cell volume, det J at "
      "corners and Gauss points, scaled Jacobian (1 = ideal, <= 0 = inverted), angles and edge "
      "ratio, and the number of inverted and degenerate cells.");
  cmd->add_option("mesh", options->input, "mesh file (.msh or .xml)")->required();
  cmd->add_option("--json", options->json,
                  "also write the summary as JSON to this file (default: none)")
      ->check(kOutputPath);
  return {cmd, [options] { run_quality(*options); }};
}

}  // namespace neomesh::app
