// `neomesh convert IN -o OUT`: read a mesh, check it, write it in another format (or the
// same one, normalized: Gmsh 4.1 ASCII with the input's physical groups).
#include <filesystem>
#include <memory>
#include <string>

#include <neomesh/mesh.hpp>

#include "app/checks.hpp"
#include "app/subcommand.hpp"
#include "core/collective_error.hpp"
#include "core/error.hpp"
#include "core/log.hpp"

namespace neomesh::app {

namespace {

struct ConvertOptions {
  std::vector<std::string> inputs;  // the mesh, with a FEAT3 mesh's chart files
  std::string output;
  bool force = false;
};

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  return std::filesystem::weakly_canonical(a, ec) == std::filesystem::weakly_canonical(b, ec);
}

void run_convert(const ConvertOptions& o) {
  collectively(MPI_COMM_WORLD, [&] {
    check_input_mesh(o.inputs);
    check_output_file("-o/--output", o.output, OutputKind::Mesh);
    for (const std::string& input : o.inputs)
      if (!o.force && same_file(input, o.output))
        fail("{}: output is the input file; choose another -o or pass --force", o.output);
  });
  say("reading {} ...\n", input_label(o.inputs));
  const Mesh mesh = [&] {
    const Activity reading("reading " + input_label(o.inputs));
    return Mesh::read(input_paths(o.inputs));
  }();
  const Activity writing("writing " + o.output);
  mesh.write_mesh_only(o.output);
  say("wrote {}: {} cells, {} vertices\n", o.output, mesh.num_cells(), mesh.num_vertices());
}

}  // namespace

Subcommand add_convert(CLI::App& app) {
  auto options = std::make_shared<ConvertOptions>();
  CLI::App* cmd = app.add_subcommand(
      "convert",
      "Convert a mesh to .vtu (ParaView), .msh, .mesh, .exo or .cgns. Reads Gmsh .msh 2.2/4.1,\n"
      "FEAT3 .xml, VTK .vtk/.vtu/.pvtu, Medit .mesh, Exodus II .exo/.e/.ex2 or CGNS .cgns,\n"
      "checks it (no inverted or degenerate cells) and writes VTU, Gmsh 4.1, Medit, Exodus II\n"
      "or CGNS (keeping physical groups).");
  cmd->add_option("input", options->inputs, input_mesh_help("input mesh"))->required();
  cmd->add_option("-o,--output", options->output, fmt::format("output mesh ({})", kMeshOutputs))
      ->required();
  cmd->add_flag("--force", options->force,
                "allow the output to overwrite the input (default: off)");
  return {cmd, [options] { run_convert(*options); }};
}

}  // namespace neomesh::app
