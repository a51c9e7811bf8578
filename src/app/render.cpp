// `neomesh render`: a picture of a mesh (a 2D mesh as it lies, a 3D mesh's boundary or a surface
// mesh's cells in perspective, or cut open) coloured by a quality metric, the energy or the
// volume ratio Q of its cells.
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <neomesh/mesh.hpp>
#include <neomesh/optimizer.hpp>
#include <neomesh/options.hpp>

#include "app/checks.hpp"
#include "app/subcommand.hpp"
#include "core/collective_error.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "report/render.hpp"

namespace neomesh::app {

namespace {

struct RenderCommandOptions {
  std::vector<std::string> inputs;  // the mesh, with a FEAT3 mesh's chart files
  std::string output, field = "scaled_jacobian", sizes{name(SmoothOptions().sizes)}, title;
  int width = 1200;
  std::vector<double> range, window, view;
  std::string cut;
  bool log_scale = false;
};

// "x", "y", "z", or with the plane's position "x=0.5".
RenderOptions::Cut parse_cut(const std::string& text) {
  const std::string axis = text.substr(0, text.find('='));
  if (axis != "x" && axis != "y" && axis != "z")
    fail("--cut takes x, y or z, optionally with the plane's position (x=0.5); got '{}'", text);
  RenderOptions::Cut cut{.axis = axis[0] - 'x', .position = std::nullopt};
  if (text.size() > 1) {
    const std::string at = text.substr(2);
    std::size_t used = 0;
    double value = std::numeric_limits<double>::quiet_NaN();
    try {
      value = std::stod(at, &used);
    } catch (const std::exception&) {
    }
    if (text[1] != '=' || used != at.size() || !std::isfinite(value))
      fail("--cut takes x, y or z, optionally with the plane's position (x=0.5); got '{}'", text);
    cut.position = value;
  }
  return cut;
}

struct FieldInfo {
  const char* option;  // --field value
  const char* legend;  // shown above the colour bar
};

constexpr std::array<FieldInfo, 8> kFields = {{
    {"scaled_jacobian", "scaled Jacobian"},
    {"min_angle", "min angle (deg)"},
    {"max_angle", "max angle (deg)"},
    {"edge_ratio", "edge ratio"},
    {"inverse_mean_ratio", "inverse mean ratio"},
    {"volume", "cell volume"},
    {"energy", "energy of the cell"},
    {"Q", "Q = volume / desired"},
}};

const FieldInfo& field_info(const std::string& option) {
  for (const FieldInfo& f : kFields)
    if (option == f.option) return f;
  fail("unknown field '{}'", option);  // CLI11 checks the choices first
}

// The values of the field named `name` (none on a process without cells).
std::vector<double> values_of(const std::vector<Field>& fields, const std::string& name) {
  for (const Field& f : fields)
    if (f.name == name) return f.values;
  return {};
}

// Energy and Q compare each cell with its optimal cell, whose volume --sizes decides: the
// energy's own defaults (3 Gauss points per direction), boundary vertices fixed.
std::vector<double> energy_field(Mesh& mesh, const RenderCommandOptions& o) {
  SmoothOptions options;
  options.energy = EnergyOptions{};
  options.boundary = BoundaryOptions{BoundaryMode::Fixed};
  options.sizes = parse_size_mode(o.sizes);
  options.targets = TargetMode::Ideal;
  Optimizer optimizer(mesh);
  optimizer.evaluate(options);
  return values_of(optimizer.cell_fields(), o.field == "energy" ? "energy" : "Q");
}

std::vector<double> field_values(Mesh& mesh, const RenderCommandOptions& o) {
  const std::vector<Field> quality = mesh.quality_by_cell();
  std::vector<double> values =
      o.field == "energy" || o.field == "Q" ? energy_field(mesh, o) : values_of(quality, o.field);
  // Inverted cells stand out in red whatever the field (render counts non-finite values).
  const std::vector<double> inverted = values_of(quality, "inverted");
  for (std::size_t c = 0; c < values.size(); ++c)
    if (inverted[c] != 0) values[c] = std::numeric_limits<double>::quiet_NaN();
  return values;
}

void run_render(const RenderCommandOptions& o) {
  if (!o.range.empty() && o.range.size() != 2)
    fail("--range takes MIN,MAX (got {} numbers)", o.range.size());
  check_finite("--range", o.range);
  if (!o.window.empty() && o.window.size() != 4)
    fail("--window takes XMIN,XMAX,YMIN,YMAX (got {} numbers)", o.window.size());
  check_finite("--window", o.window);
  if (!o.view.empty() && o.view.size() != 2)
    fail("--view takes AZIMUTH,ELEVATION in degrees (got {} numbers)", o.view.size());
  check_finite("--view", o.view);
  const std::optional<RenderOptions::Cut> cut =
      o.cut.empty() ? std::nullopt : std::optional(parse_cut(o.cut));
  // Fail before the (possibly long) load.
  collectively(MPI_COMM_WORLD, [&] {
    check_output_file("-o/--output", o.output, OutputKind::Picture);
    check_input_mesh(o.inputs);
  });
  // Inverted cells are drawn in red and counted, not refused.
  Mesh mesh = [&] {
    const Activity reading("reading " + input_label(o.inputs));
    return Mesh::read(input_paths(o.inputs), MPI_COMM_WORLD, InvertedCells::Keep);
  }();

  RenderOptions options;
  options.width = o.width;
  std::string files;
  for (const std::string& input : o.inputs)
    files += (files.empty() ? "" : " + ") + std::filesystem::path(input).filename().string();
  options.title = o.title.empty() ? files : o.title;
  options.field_name = field_info(o.field).legend;
  options.log_scale = o.log_scale;
  if (!o.range.empty()) options.min = o.range[0], options.max = o.range[1];
  if (!o.window.empty()) options.window = {o.window[0], o.window[1], o.window[2], o.window[3]};
  if (!o.view.empty()) options.azimuth = o.view[0], options.elevation = o.view[1];
  options.cut = cut;
  options.curved_scaled_jacobian = o.field == "scaled_jacobian";
  render_mesh(mesh, field_values(mesh, o), o.output, options);
  say("wrote {}: {} of {} cells\n", o.output, o.field, mesh.num_cells());
}

}  // namespace

Subcommand add_render(CLI::App& app) {
  auto options = std::make_shared<RenderCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Draw a mesh as a .png or .svg picture. Every cell is coloured by a quality metric,\n"
      "its energy or its volume ratio Q, with a colour bar; inverted cells are drawn in red\n"
      "and counted. A 3D mesh is drawn as its boundary in perspective, shaded, a surface\n"
      "mesh as its cells (their back side darker); --cut opens it to show the cells inside.\n"
      "A curved 2D mesh is drawn with its edges curved, cells not certified valid in red,\n"
      "its scaled Jacobian the least over each curved cell.");
  cmd->add_option("mesh", options->inputs, input_mesh_help("mesh file"))->required();
  cmd->add_option("-o,--output", options->output, "picture file (.png or .svg)")->required();
  std::vector<std::string> fields;
  for (const FieldInfo& f : kFields) fields.emplace_back(f.option);
  cmd->add_option("--field", options->field,
                  "what colours the cells: a quality metric (see `neomesh quality`), the "
                  "Neo-Hookean energy of the cell, or Q = volume / desired volume")
      ->check(CLI::IsMember(fields))
      ->capture_default_str();
  cmd->add_option("--sizes", options->sizes,
                  "desired cell volumes for energy and Q, as in `neomesh smooth`: uniform (mesh "
                  "volume / cells), input (each cell's own volume) or smoothed")
      ->check(CLI::IsMember(choice_names<SizeMode>()))
      ->capture_default_str();
  cmd->add_option("--title", options->title, "title above the mesh (default: the file name)");
  cmd->add_option("--width", options->width, "picture width in pixels (PNG) or points (SVG)")
      ->capture_default_str();
  cmd->add_option("--range", options->range,
                  "colour range MIN,MAX (default: the range of the values); values outside get "
                  "the end colours")
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--window", options->window,
                  "draw only XMIN,XMAX,YMIN,YMAX (a zoom, e.g. into a boundary layer; default: "
                  "the whole mesh)")
      ->delimiter(',')
      ->expected(4);
  cmd->add_option("--view", options->view,
                  "3D and surface meshes: where the eye looks from, AZIMUTH,ELEVATION in degrees "
                  "(azimuth in the "
                  "x-y plane from the x axis; default: -60,25)")
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--cut", options->cut,
                  "3D and surface meshes: draw only the cells behind a plane normal to x, y or z, "
                  "at the mesh's "
                  "middle or where given (x=0.5), to show the cells inside");
  cmd->add_flag("--log", options->log_scale,
                "colour by the logarithm of the value (default: linear)");
  return {cmd, [options] { run_render(*options); }};
}

}  // namespace neomesh::app
