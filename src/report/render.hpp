// Pictures of 2D meshes: every cell filled with the viridis colour of one value per cell
// (a quality metric, the energy, ...), with a colour bar, written as PNG or SVG.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include <neomesh/mesh.hpp>

namespace neomesh {

struct RenderOptions {
  int width = 1200;  // of the whole picture; the height follows the mesh's aspect ratio
  std::string title;
  std::string field_name;  // shown above the colour bar
  bool log_scale = false;  // colour by log10 of the value (values ≤ 0 get the lowest colour)
  std::optional<double> min, max;  // colour range; default: the range of the finite values
  bool draw_edges = true;          // skipped anyway when cells are too small to show them
  // What non-finite values mean, for the legend ("3 inverted").
  std::string invalid_label = "inverted";
  // The part drawn, {x_min, x_max, y_min, y_max} (a zoom; cells are clipped at its frame);
  // default: the whole mesh.
  std::optional<std::array<double, 4>> window;
};

// Draws a whole 2D mesh (Mesh::gather's arrays; its cell_fields are not used) coloured by
// `cell_values` (one per cell, by cell number; NaN/±inf drawn in red and counted) to `out`
// (.png or .svg). Throws Error for 3D meshes, for arrays that do not make a mesh and for files
// that cannot be written; never leaves a partial file.
void render_mesh(const MeshArrays& mesh, std::span<const double> cell_values,
                 const std::filesystem::path& out, const RenderOptions& options = {});

// The same for a whole, possibly distributed mesh at its current coordinates: collective;
// the first process gathers the cells and `cell_values` (one per local cell, in the order of
// Mesh::quality_by_cell()) and draws.
void render_mesh(const Mesh& mesh, std::span<const double> cell_values,
                 const std::filesystem::path& out, const RenderOptions& options = {});

}  // namespace neomesh
