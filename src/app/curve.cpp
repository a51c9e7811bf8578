// `neomesh curve IN -o OUT --order 2 [--shape PART=SPEC]`: raise a straight mesh to second
// order, put its boundary on the exact geometry, untangle and optimize the nodes inside with the
// curved cells' energy (the boundary's held where they were put), and write it only if every
// curved cell is certified valid.
#include <memory>
#include <string>
#include <vector>

#include <neomesh/curve.hpp>
#include <neomesh/mesh.hpp>
#include <neomesh/optimizer.hpp>

#include "app/checks.hpp"
#include "app/method_options.hpp"
#include "app/subcommand.hpp"
#include "core/collective_error.hpp"
#include "core/error.hpp"
#include "core/log.hpp"

namespace neomesh::app {

namespace {

struct CurveCommand {
  std::vector<std::string> inputs;  // the mesh, with a FEAT3 mesh's chart files
  std::string output;
  int order = 2;
  std::vector<std::string> shapes;  // PART=SPEC
};

// The curved cells must all be certified valid (det J > 0 everywhere) for the mesh to be
// written; otherwise one line says how many are not, and nothing is written.
void require_certified_valid(const Mesh& mesh) {
  const QualitySummary quality = mesh.quality();
  const CurvedQualitySummary& curved = *quality.curved;
  if (curved.not_valid > 0)
    fail(
        "{} of {} cells are not certified valid once the boundary nodes are on the geometry "
        "and the nodes inside optimized (least curved scaled Jacobian {:.3g}); nothing written",
        curved.not_valid, quality.cells, curved.scaled_jacobian.min);
  say("all {} cells certified valid; curved scaled Jacobian min {:.4g}, mean {:.4g}\n",
      quality.cells, curved.scaled_jacobian.min, curved.scaled_jacobian.mean);
}

void run_curve(const CurveCommand& o) {
  collectively(MPI_COMM_WORLD, [&] {
    check_input_mesh(o.inputs);
    check_output_file("-o/--output", o.output, OutputKind::Mesh);
  });
  CurveOptions options;
  options.order = o.order;
  options.shapes = parse_shapes(o.shapes);
  say("reading {} ...\n", input_label(o.inputs));
  CurveSummary placed;
  Mesh mesh = [&] {
    const Activity reading("reading and raising " + input_label(o.inputs));
    return curve_mesh(input_paths(o.inputs), options, &placed);
  }();
  say("raised {} cells to order 2; on the geometry: {} boundary vertices (moved up to {:.3g}) "
      "and {} boundary nodes (off it by at most {:.3g}); {} boundary nodes of parts without a "
      "shape or chart left straight\n",
      mesh.num_cells(), placed.vertices_on_geometry, placed.max_vertex_move,
      placed.nodes_on_geometry, placed.max_off_geometry, placed.nodes_straight);
  {
    // Smoothing a curved mesh with the library's defaults: the boundary vertices and nodes slide
    // on the shapes and charts they were put on (parts without one on their straight facets),
    // the cells folded behind a bent boundary are untangled first, and the certificate judges
    // the optimum (docs/method.md §12, "The solver").
    const Activity optimizing("untangling and optimizing the nodes inside");
    SmoothOptions smooth;
    smooth.boundary.mode = BoundaryMode::Fixed;
    Optimizer optimizer(mesh);
    const Result result = optimizer.smooth(smooth);
    if (result.curved)
      say("nodes inside optimized: least curved scaled Jacobian {:.4g} -> {:.4g}{}\n",
          result.curved->min_scaled_jacobian_before, result.curved->min_scaled_jacobian_optimum,
          result.curved->input_returned ? " (not better: the placed mesh is kept)" : "");
  }
  require_certified_valid(mesh);
  const Activity writing("writing " + o.output);
  mesh.write_mesh_only(o.output);
  say("wrote {}: {} cells, {} vertices\n", o.output, mesh.num_cells(), mesh.num_vertices());
}

}  // namespace

Subcommand add_curve(CLI::App& app) {
  auto options = std::make_shared<CurveCommand>();
  CLI::App* cmd = app.add_subcommand(
      "curve",
      "Raise a straight mesh of triangles, quadrilaterals, tetrahedra or hexahedra to second\n"
      "order (triangle6, quadrilateral9, tetrahedron10, hexahedron27) and put its boundary\n"
      "vertices and nodes on the exact geometry of their parts (--shape, FEAT3 charts; parts\n"
      "without either stay straight), then untangles and optimizes every node inside with the\n"
      "curved cells' energy. Writes the curved mesh only if every cell is certified valid\n"
      "(det J > 0 everywhere); otherwise says how many are not and writes nothing.");
  cmd->add_option("input", options->inputs, input_mesh_help("input mesh"))->required();
  cmd->add_option("-o,--output", options->output, fmt::format("output mesh ({})", kMeshOutputs))
      ->required();
  cmd->add_option("--order", options->order, "the order to raise to: 2 (default: 2)");
  cmd->add_option("--shape", options->shapes,
                  "boundary part PART (physical group or FEAT3 mesh part) lies exactly on a "
                  "shape: PART=circle:cx,cy,r | line:px,py,nx,ny | sphere:cx,cy,cz,r | "
                  "plane:px,py,pz,nx,ny,nz | cylinder:px,py,pz,ax,ay,az,r | levelset:EXPR "
                  "(repeatable; default: FEAT3 charts, else straight)");
  return {cmd, [options] { run_curve(*options); }};
}

}  // namespace neomesh::app
