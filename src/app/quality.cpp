// `neomesh quality`: the quality summary of a mesh file, as a table and optionally JSON.
#include <memory>
#include <string>

#include <neomesh/mesh.hpp>

#include "app/checks.hpp"
#include "app/subcommand.hpp"
#include "core/atomic_file.hpp"
#include "core/collective_error.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "report/quality_report.hpp"

namespace neomesh::app {

namespace {

struct QualityOptions {
  std::vector<std::string> inputs;  // the mesh, with a FEAT3 mesh's chart files
  std::string json;
  std::string reference;
};

// How far the mesh's boundary is from the reference's (a mesh before smoothing): the largest
// distance of a boundary vertex from the reference's boundary facets, and the relative change
// of the domain's volume.
nlohmann::json compare_boundary(const Mesh& mesh, const std::string& reference_file) {
  const Mesh reference = [&] {
    const Activity reading("reading " + reference_file);
    return Mesh::read(reference_file, MPI_COMM_WORLD, InvertedCells::Keep);
  }();
  if (reference.dim() != mesh.dim())
    fail("--reference {} is {}D, the mesh {}D", reference_file, reference.dim(), mesh.dim());
  const double distance = mesh.max_boundary_distance(reference);
  const double before = reference.volume();
  const double change = (mesh.volume() - before) / before;
  always(
      "boundary against {}: largest distance of a boundary vertex from its boundary {:.3g}, "
      "domain volume change {:+.3g}%\n",
      reference_file, distance, 100 * change);
  return {{"reference", reference_file},
          {"max_distance_from_reference_boundary", distance},
          {"relative_volume_change", change}};
}

void run_quality(const QualityOptions& o) {
  collectively(MPI_COMM_WORLD, [&] {
    check_input_mesh(o.inputs);
    if (!o.reference.empty()) check_input_mesh(o.reference);
    if (!o.json.empty()) check_output_file("--json", o.json, OutputKind::Json);
  });
  // Inverted and degenerate cells are what this command counts, not a reason to refuse.
  const Mesh mesh = [&] {
    const Activity reading("reading " + input_label(o.inputs));
    return Mesh::read(input_paths(o.inputs), MPI_COMM_WORLD, InvertedCells::Keep);
  }();
  const QualitySummary summary = mesh.quality();
  always("{}\n{}", input_label(o.inputs), format_table(summary));
  nlohmann::json json = to_json(summary);
  if (!o.reference.empty()) json["boundary_change"] = compare_boundary(mesh, o.reference);
  if (!o.json.empty())
    on_root(mesh.comm(), [&] {
      AtomicFile file(o.json);
      file.stream() << json.dump(2) << '\n';
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
      "ratio, and the number of inverted and degenerate cells. Of a mesh of second-order\n"
      "(curved) cells these are its straight cells' (on the corners), followed by the curved\n"
      "cells' validity (certified det J > 0) and curved scaled Jacobian.");
  cmd->add_option("mesh", options->inputs, input_mesh_help("mesh file"))->required();
  cmd->add_option("--reference", options->reference,
                  "compare the boundary with this mesh's (e.g. the input of smooth): the largest "
                  "distance of a boundary vertex from its boundary and the domain volume change "
                  "(default: none)");
  cmd->add_option("--json", options->json,
                  "also write the summary as JSON to this file (default: none)")
      ->check(kOutputPath);
  return {cmd, [options] { run_quality(*options); }};
}

}  // namespace neomesh::app
