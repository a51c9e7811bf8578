// `neomesh generate`: writes one of the thesis' test meshes (docs/cases.md).
#include <memory>
#include <optional>
#include <string>

#include <neomesh/generate.hpp>
#include <neomesh/mesh.hpp>

#include "app/checks.hpp"
#include "app/subcommand.hpp"
#include "core/collective_error.hpp"
#include "core/error.hpp"
#include "core/log.hpp"

namespace neomesh::app {

namespace {

struct GenerateCommandOptions {
  std::string name;
  std::optional<int> level, cells;
  double rotate_degrees = 0.0;
  unsigned seed = 1;
  double amplitude = 0.2;
  double jitter = 0.0;
  std::string output;
};

const GeneratedCase& find_case(const std::string& name) {
  for (const GeneratedCase& c : generated_cases())
    if (name == c.name) return c;
  fail("unknown mesh case '{}'", name);  // CLI11 checks the choices first
}

// The generator's size argument from --level or --cells. The thesis' levels: t for the moved
// midpoint cases (2^(t+1) cells per direction), L for lattices (2^L), refinements otherwise.
int size_of(const GeneratedCase& c, const GenerateCommandOptions& o) {
  if (o.level.has_value() == o.cells.has_value())
    fail("generate {}: give exactly one of --level and --cells", c.name);
  if (o.cells) {
    if (c.size == GeneratedSize::Refinements)
      fail("generate {}: --cells does not apply to a refined mesh; use --level (refinements)",
           c.name);
    // Checked here, on every rank, because only rank 0 runs the generator.
    if (*o.cells < 1 || (c.size == GeneratedSize::EvenCells && *o.cells % 2 != 0))
      fail("generate {}: --cells must be {} (got {})", c.name,
           c.size == GeneratedSize::EvenCells ? "even and >= 2" : ">= 1", *o.cells);
    return *o.cells;
  }
  const int level = *o.level;
  const int max_level = c.size == GeneratedSize::Refinements ? 12 : 14;
  if (level < 0 || level > max_level)
    fail("generate {}: --level must be in 0..{} (got {})", c.name, max_level, level);
  switch (c.size) {
    case GeneratedSize::EvenCells:
      return 1 << (level + 1);
    case GeneratedSize::Cells:
      return 1 << level;
    case GeneratedSize::Refinements:
      return level;
  }
  return level;
}

// The library's check of the options, told with the command line's flags.
void check_generate_options(const GenerateOptions& g) {
  try {
    g.validate();
  } catch (const OptionError& e) {
    if (e.field() == "rotate_degrees") throw Error("--rotate " + e.requirement());
    if (e.requirement().starts_with("must"))  // a value out of range
      throw Error(fmt::format("generate: --{} {}", e.field(), e.requirement()));
    throw Error(fmt::format("generate {}: --{} {}", g.name, e.field(), e.requirement()));
  }
}

void run_generate(const GenerateCommandOptions& o) {
  const GeneratedCase& c = find_case(o.name);
  const GenerateOptions options{.name = o.name,
                                .size = size_of(c, o),
                                .amplitude = o.amplitude,
                                .seed = o.seed,
                                .jitter = o.jitter,
                                .rotate_degrees = o.rotate_degrees};
  check_generate_options(options);
  collectively(MPI_COMM_WORLD,
               [&] { check_output_file("-o/--output", o.output, OutputKind::Mesh); });
  // A large --jitter folds cells over: such meshes are written as they are, to be untangled.
  const Mesh mesh = Mesh::generate(options, MPI_COMM_WORLD);
  mesh.write_mesh_only(o.output);
  say("wrote {}: {} {}, {} vertices\n", o.output, mesh.num_cells(), plural_name(c.type),
      mesh.num_vertices());
  const QualitySummary quality = mesh.quality();
  if (quality.inverted > 0)
    say("{} of them are inverted (neomesh smooth untangles them)\n", quality.inverted);
}

}  // namespace

Subcommand add_generate(CLI::App& app) {
  auto options = std::make_shared<GenerateCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "generate",
      "Write one of the thesis' test meshes (docs/cases.md) to a .msh or .vtu file.\n"
      "Meaning of --level per case:\n"
      "  square-midpoint, cube-midpoint: thesis level t = 2^(t+1) cells per direction\n"
      "    (level 3 = 16x16 quads, Table 5.1; 3D level 3 = 16^3 hexes)\n"
      "  square-random, box-quad, box-tri, box-hex, box-tet, box-wedge, box-pyramid,\n"
      "    annulus-quad, annulus-tri, annulus-hex, annulus-tet: level L = 2^L cells per\n"
      "    direction (box-tri: 2 triangles per square; box-tet: 6 tets, box-wedge: 2 wedges,\n"
      "    box-pyramid: 6 pyramids per cube; annulus: the quarter annulus 1 <= r <= 2, in 3D\n"
      "    extruded to 0 <= z <= 1, split likewise)\n"
      "  transition, circle-quad, triangle-equilateral, triangle-curved: level = number of\n"
      "    uniform refinements of the coarse mesh (5, 5, 1 and 8 cells), 4x cells each\n"
      "--cells N gives the cells per direction directly (not for refined cases).");
  std::vector<std::string> names;
  for (const GeneratedCase& c : generated_cases()) names.emplace_back(c.name);
  cmd->add_option("case", options->name, "the mesh to generate")
      ->required()
      ->check(CLI::IsMember(names));
  auto* level = cmd->add_option("--level", options->level,
                                "size level, meaning per case above (give --level or --cells)");
  auto* cells = cmd->add_option("--cells", options->cells,
                                "cells per direction (instead of --level; not for refined cases)");
  level->excludes(cells);
  cmd->add_option("--rotate", options->rotate_degrees,
                  "rotate counter-clockwise about the origin (2D) / the z axis (3D), degrees")
      ->capture_default_str();
  cmd->add_option("--seed", options->seed,
                  "random seed (square-random, triangle-equilateral, --jitter)")
      ->capture_default_str();
  cmd->add_option("--amplitude", options->amplitude,
                  "square-random: largest displacement per coordinate, in cell widths, < 0.25")
      ->capture_default_str();
  cmd->add_option("--jitter", options->jitter,
                  "box and annulus cases: displace interior vertices by up to this many cell "
                  "widths per coordinate, at random, < 1 (from 0.25 on, cells may fold over: a "
                  "tangled mesh)")
      ->capture_default_str();
  cmd->add_option("-o,--output", options->output, fmt::format("output file ({})", kMeshOutputs))
      ->required();
  return {cmd, [options] { run_generate(*options); }};
}

}  // namespace neomesh::app
