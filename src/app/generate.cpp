// `neomesh generate`: writes one of the thesis' test meshes (docs/cases.md).
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "app/checks.hpp"
#include "app/subcommand.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "geometry/quality.hpp"
#include "mesh/collective_error.hpp"
#include "mesh/generate.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh::app {

namespace {

// How --level maps to the size argument of a generator.
enum class Levels {
  MovedMidpoint,  // thesis level t: 2^(t+1) cells per direction
  Lattice,        // level L: 2^L cells per direction
  Refinements,    // level = number of uniform refinements of the coarse mesh
};

struct GenerateOptions {
  std::string name;
  std::optional<int> level, cells;
  double rotate_degrees = 0.0;
  unsigned seed = 1;
  double amplitude = 0.2;
  double jitter = 0.0;
  std::string output;
};

struct Case {
  const char* name;
  Levels levels;
  std::function<MeshData(int size, const GenerateOptions&)> make;
};

const std::array<Case, 13>& cases() {
  static const std::array<Case, 13> all = {{
      {"square-midpoint", Levels::MovedMidpoint, [](int n, auto&) { return square_midpoint(n); }},
      {"cube-midpoint", Levels::MovedMidpoint, [](int n, auto&) { return cube_midpoint(n); }},
      {"square-random", Levels::Lattice,
       [](int n, const GenerateOptions& o) { return square_random(n, o.amplitude, o.seed); }},
      {"transition", Levels::Refinements, [](int r, auto&) { return transition(r); }},
      {"circle-quad", Levels::Refinements, [](int r, auto&) { return circle_quad(r); }},
      {"triangle-equilateral", Levels::Refinements,
       [](int r, const GenerateOptions& o) { return triangle_equilateral(r, o.seed); }},
      {"triangle-curved", Levels::Refinements, [](int r, auto&) { return triangle_curved(r); }},
      {"box-quad", Levels::Lattice, [](int n, auto&) { return box(CellType::Quadrilateral, n); }},
      {"box-tri", Levels::Lattice, [](int n, auto&) { return box(CellType::Triangle, n); }},
      {"box-hex", Levels::Lattice, [](int n, auto&) { return box(CellType::Hexahedron, n); }},
      {"box-tet", Levels::Lattice, [](int n, auto&) { return box(CellType::Tetrahedron, n); }},
      {"box-wedge", Levels::Lattice, [](int n, auto&) { return box(CellType::Wedge, n); }},
      {"box-pyramid", Levels::Lattice, [](int n, auto&) { return box(CellType::Pyramid, n); }},
  }};
  return all;
}

const Case& find_case(const std::string& name) {
  for (const Case& c : cases())
    if (name == c.name) return c;
  fail("unknown mesh case '{}'", name);  // CLI11 checks the choices first
}

// The generator's size argument from --level or --cells.
int size_of(const Case& c, const GenerateOptions& o) {
  if (o.level.has_value() == o.cells.has_value())
    fail("generate {}: give exactly one of --level and --cells", c.name);
  if (o.cells) {
    if (c.levels == Levels::Refinements)
      fail("generate {}: --cells does not apply to a refined mesh; use --level (refinements)",
           c.name);
    // Checked here, on every rank, because only rank 0 runs the generator.
    if (*o.cells < 1 || (c.levels == Levels::MovedMidpoint && *o.cells % 2 != 0))
      fail("generate {}: --cells must be {} (got {})", c.name,
           c.levels == Levels::MovedMidpoint ? "even and >= 2" : ">= 1", *o.cells);
    return *o.cells;
  }
  const int level = *o.level;
  const int max_level = c.levels == Levels::Refinements ? 12 : 14;
  if (level < 0 || level > max_level)
    fail("generate {}: --level must be in 0..{} (got {})", c.name, max_level, level);
  switch (c.levels) {
    case Levels::MovedMidpoint:
      return 1 << (level + 1);
    case Levels::Lattice:
      return 1 << level;
    case Levels::Refinements:
      return level;
  }
  return level;
}

void run_generate(const GenerateOptions& o) {
  const Case& c = find_case(o.name);
  const int size = size_of(c, o);
  check_option("--rotate", o.rotate_degrees, true, "in degrees");
  if (!(o.amplitude >= 0.0 && o.amplitude < 0.25))
    fail("generate: --amplitude must be in [0, 0.25) (got {})", o.amplitude);
  const bool is_box = std::string_view(c.name).starts_with("box-");
  if (o.jitter != 0.0 && !is_box) fail("generate {}: --jitter applies to the box cases", c.name);
  if (!(o.jitter >= 0.0 && o.jitter < 1.0))
    fail("generate: --jitter must be in [0, 1) (got {})", o.jitter);
  collectively(PETSC_COMM_WORLD,
               [&] { check_output_file("-o/--output", o.output, OutputKind::Mesh); });
  // The mesh is built on rank 0; PlexMesh::from_data distributes it.
  MeshData data;
  if (is_root_rank()) {
    data = c.make(size, o);
    if (o.jitter > 0.0) jitter(data, 2.0 / size, o.jitter, o.seed);  // boxes are [-1,1]^d
    if (o.rotate_degrees != 0.0) rotate(data, o.rotate_degrees);
  }
  const CellType type = data.cell_type;
  // A large --jitter folds cells over: such meshes are written as they are, to be untangled.
  const PlexMesh mesh = PlexMesh::from_data(data, c.name, PETSC_COMM_WORLD, InvertedCells::Keep);
  write_mesh(mesh, o.output);
  say("wrote {}: {} {}, {} vertices\n", o.output, mesh.global_num_cells(), plural_name(type),
      mesh.global_num_vertices());
  const QualitySummary quality =
      summarize(cell_quality(mesh.view(), mesh.view().coords), mesh.comm());
  if (quality.inverted > 0)
    say("{} of them are inverted (neomesh smooth untangles them)\n", quality.inverted);
}

}  // namespace

Subcommand add_generate(CLI::App& app) {
  auto options = std::make_shared<GenerateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "generate",
      "Write one of the thesis' test meshes (docs/cases.md) to a .msh or .vtu file.\n"
      "Meaning of --level per case:\n"
      "  square-midpoint, cube-midpoint: thesis level t = 2^(t+1) cells per direction\n"
      "    (level 3 = 16x16 quads, Table 5.1; 3D level 3 = 16^3 hexes)\n"
      "  square-random, box-quad, box-tri, box-hex, box-tet, box-wedge, box-pyramid: level\n"
      "    L = 2^L cells per direction (box-tri: 2 triangles per square; box-tet: 6 tets,\n"
      "    box-wedge: 2 wedges, box-pyramid: 6 pyramids per cube)\n"
      "  transition, circle-quad, triangle-equilateral, triangle-curved: level = number of\n"
      "    uniform refinements of the coarse mesh (5, 5, 1 and 8 cells), 4x cells each\n"
      "--cells N gives the cells per direction directly (not for refined cases).");
  std::vector<std::string> names;
  for (const Case& c : cases()) names.emplace_back(c.name);
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
                  "box cases: displace interior vertices by up to this many cell widths per "
                  "coordinate, at random, < 1 (from 0.25 on, cells may fold over: a tangled mesh)")
      ->capture_default_str();
  cmd->add_option("-o,--output", options->output, "output file (.msh or .vtu)")->required();
  return {cmd, [options] { run_generate(*options); }};
}

}  // namespace neomesh::app
