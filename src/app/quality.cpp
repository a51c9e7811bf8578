// `neomesh quality`: the quality summary of a mesh file, as a table and optionally JSON.
#include <memory>
#include <string>

#include "app/subcommand.hpp"
#include "core/atomic_file.hpp"
#include "core/log.hpp"
#include "geometry/quality.hpp"
#include "mesh/mesh.hpp"
#include "mesh/mesh_io.hpp"

namespace neomesh::app {

namespace {

struct QualityOptions {
  std::string input;
  std::string json;
};

void run_quality(const QualityOptions& o) {
  check_readable_format(o.input);
  const Mesh mesh = Mesh::load(o.input);
  const MeshView& view = mesh.view();
  const QualitySummary summary = summarize(cell_quality(view, view.coords), mesh.comm());
  always("{}\n{}", o.input, format_table(summary));
  if (!o.json.empty() && is_root_rank()) {
    AtomicFile file(o.json);
    file.stream() << to_json(summary).dump(2) << '\n';
    file.commit();
  }
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
                  "also write the summary as JSON to this file (default: none)");
  return {cmd, [options] { run_quality(*options); }};
}

}  // namespace neomesh::app
