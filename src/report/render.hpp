// Pictures of meshes: every cell filled with the viridis colour of one value per cell (a quality
// metric, the energy, ...), with a colour bar, written as PNG or SVG. A 2D mesh is drawn as it
// lies; a 3D mesh as its boundary in perspective, shaded, or cut open by a plane; a surface mesh
// (2D cells in space) as its cells in perspective, shaded, either side showing (the side whose
// cells turn clockwise to the eye darker).
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
  // A curved 2D mesh's cells coloured by their curved scaled Jacobian (the least over the cell,
  // geometry/curved_cell.hpp) instead of the values given, which are its corner cells'.
  bool curved_scaled_jacobian = false;
  // The part drawn, {x_min, x_max, y_min, y_max} (a zoom; cells are clipped at its frame);
  // default: the whole mesh. A mesh in the plane only.
  std::optional<std::array<double, 4>> window;
  // In space (3D or surface): where the eye looks from, around the mesh's centre: the azimuth in
  // the x-y plane from the x axis and the elevation above that plane, in degrees.
  double azimuth = -60.0, elevation = 25.0;
  // In space: only the cells whose centre lies on the far side of the plane x_axis = position (seen
  // from the eye), so that the cells inside show in the cut; default: the mesh's middle.
  struct Cut {
    int axis = 0;  // 0, 1, 2: x, y, z
    std::optional<double> position;
  };
  std::optional<Cut> cut;
};

// The values at the ends of the colour bar, which its lowest and highest labels show.
struct ColourBarRange {
  double min = 0, max = 0;
};

// Draws a whole mesh (Mesh::gather's arrays; its cell_fields are not used) coloured by
// `cell_values` (one per cell, by cell number; NaN/±inf drawn in red and counted) to `out`
// (.png or .svg): a 2D mesh's cells, a 3D mesh's boundary faces (of the cells kept by the cut)
// each in its cell's colour, a surface mesh's cells (kept by the cut). Throws Error for arrays that
// do not make a mesh, for options that do not fit its dimension and for files that cannot be
// written; never leaves a partial file.
ColourBarRange render_mesh(const MeshArrays& mesh, std::span<const double> cell_values,
                           const std::filesystem::path& out, const RenderOptions& options = {});

// The same for a whole, possibly distributed mesh at its current coordinates: collective;
// the first process gathers the cells and `cell_values` (one per local cell, in the order of
// Mesh::quality_by_cell()) and draws (the others get an empty range).
ColourBarRange render_mesh(const Mesh& mesh, std::span<const double> cell_values,
                           const std::filesystem::path& out, const RenderOptions& options = {});

}  // namespace neomesh
