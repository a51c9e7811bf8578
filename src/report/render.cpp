#include "report/render.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Dense>

#include <fmt/format.h>

#include "core/collective_error.hpp"
#include "core/error.hpp"
#include "geometry/curved_quality.hpp"
#include "mesh/cell_type.hpp"
#include "mesh/gather.hpp"
#include "mesh/input_mesh.hpp"
#include "mesh/plex_mesh.hpp"
#include "report/canvas.hpp"

namespace neomesh {

namespace {

constexpr Rgb kInvalidColour{0.85, 0.11, 0.11};  // red: absent from viridis
constexpr Rgb kInk{0.15, 0.15, 0.15};            // text, outlines and edges
constexpr Rgb kMutedInk{0.45, 0.45, 0.45};
constexpr int kMinWidth = 200, kMaxWidth = 20000;
// Edges of cells smaller than this (mean size in pixels) would only darken the picture.
constexpr double kMinCellPixelsForEdges = 2.0;
// Colour-bar ticks: their length and the gap to their label, in font sizes.
constexpr double kTickLength = 0.35, kTickLabelGap = 0.6;

// Maps a value to its position t ∈ [0, 1] on the colour bar (in log10 units for log scale).
struct ColourScale {
  double lo = 0, hi = 1;
  bool log = false;

  double position(double v) const {
    const double u = !log ? v : v > 0 ? std::log10(v) : -std::numeric_limits<double>::infinity();
    return (u - lo) / (hi - lo);
  }
  double value_at(double t) const {
    const double u = lo + t * (hi - lo);
    return log ? std::pow(10.0, u) : u;
  }
};

ColourScale colour_scale(std::span<const double> values, const RenderOptions& o) {
  if (o.min && o.max && !(*o.min < *o.max))
    fail("colour range {},{} is empty: the minimum must be below the maximum", *o.min, *o.max);
  if (o.log_scale && ((o.min && *o.min <= 0) || (o.max && *o.max <= 0)))
    fail("a log-scale colour range must be positive (got {},{})", o.min.value_or(1),
         o.max.value_or(1));
  ColourScale s;
  s.log = o.log_scale;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : values)
    if (std::isfinite(v) && (!s.log || v > 0)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (lo > hi) lo = hi = s.log ? 1.0 : 0.0;  // no drawable value at all
  lo = o.min.value_or(lo);
  hi = o.max.value_or(hi);
  s.lo = s.log ? std::log10(lo) : lo;
  s.hi = s.log ? std::log10(hi) : hi;
  // A constant field (or a one-sided range beyond the data) still needs a bar to read.
  if (!(s.hi - s.lo > 1e-12 * std::max(1.0, std::abs(s.lo)))) {
    const double pad = s.log ? 0.5 : s.lo != 0 ? 0.05 * std::abs(s.lo) : 1.0;
    if (o.min && !o.max)
      s.hi = s.lo + 2 * pad;
    else if (o.max && !o.min)
      s.lo = s.hi - 2 * pad;
    else
      s.lo -= pad, s.hi += pad;
  }
  return s;
}

std::string tick_label(double v) {
  const double a = std::abs(v);
  if (a == 0 || (a >= 1e-3 && a < 1e5)) return fmt::format("{:.3g}", v);
  return fmt::format("{:.2e}", v);
}

// The texts beside the colour bar; known before the layout, which makes room for them.
struct Legend {
  std::string name;
  std::array<std::string, 3> tick_labels;  // at the bottom, middle and top of the bar
  std::string invalid;                     // "2 inverted", or empty
  std::string count;                       // "16 cells"
};

Legend legend(const ColourScale& scale, const RenderOptions& o, std::span<const double> values) {
  Legend g;
  g.name = o.field_name + (o.log_scale ? " (log scale)" : "");
  for (int i = 0; i < 3; ++i) g.tick_labels[i] = tick_label(scale.value_at(i / 2.0));
  const auto invalid =
      std::count_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); });
  if (invalid > 0) g.invalid = fmt::format("{} {}", invalid, o.invalid_label);
  g.count = fmt::format("{} cells", values.size());
  return g;
}

// Where everything goes, in picture units.
struct Layout {
  int width = 0, height = 0;
  double margin = 0, font = 0, title_font = 0, title_y = 0;
  double scale = 0, x0 = 0, y0 = 0;  // a point (x, y) goes to (x0 + scale x, y0 − scale y)
  double legend_x = 0, legend_top = 0, bar_width = 0, bar_height = 0;
  std::array<double, 4> frame{};  // the part drawn: left, top, width, height

  double px(double x) const { return x0 + scale * x; }
  double py(double y) const { return y0 - scale * y; }
};

Layout layout(std::span<const double> coords, const RenderOptions& o, const Legend& g) {
  if (o.width < kMinWidth || o.width > kMaxWidth)
    fail("picture width {} is outside {}..{}", o.width, kMinWidth, kMaxWidth);
  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  for (std::size_t i = 0; i + 1 < coords.size(); i += 2) {
    xmin = std::min(xmin, coords[i]), xmax = std::max(xmax, coords[i]);
    ymin = std::min(ymin, coords[i + 1]), ymax = std::max(ymax, coords[i + 1]);
  }
  if (o.window) {
    const auto& [x0, x1, y0, y1] = *o.window;
    if (!(x0 < x1 && y0 < y1) || !std::isfinite(x1 - x0) || !std::isfinite(y1 - y0))
      fail("render window {},{},{},{} is empty (give x_min < x_max, y_min < y_max)", x0, x1, y0,
           y1);
    xmin = x0, xmax = x1, ymin = y0, ymax = y1;
  }
  // A degenerate extent (all vertices on a line) gets the other one, so that scale is finite.
  double w = xmax - xmin, h = ymax - ymin;
  if (!(w > 0)) w = h > 0 ? h : 1.0;
  if (!(h > 0)) h = w;

  Layout l;
  l.width = o.width;
  const double W = o.width;
  l.margin = 0.035 * W;
  l.font = std::max(10.0, 0.013 * W);
  l.title_font = 1.35 * l.font;
  const double title_height = o.title.empty() ? 0.0 : 2.6 * l.title_font;
  l.bar_width = 0.022 * W;
  double labels = 0;
  for (const std::string& label : g.tick_labels)
    labels = std::max(labels, text_width(label, l.font));
  const double legend_width = 0.035 * W + std::max({text_width(g.name, l.font, true),
                                                    l.bar_width + kTickLength * l.font + labels,
                                                    1.5 * l.font + text_width(g.invalid, l.font)});
  const double map_width = std::max(W - 2 * l.margin - legend_width, 0.3 * W);
  // Very flat or very tall meshes get a frame of bounded height, the mesh centred in it.
  const double map_height = std::clamp(map_width * h / w, 0.3 * W, 1.2 * W);
  const double top = l.margin + title_height;
  l.height = static_cast<int>(std::ceil(top + map_height + l.margin));
  l.title_y = l.margin + 0.5 * l.title_font;

  l.scale = std::min(map_width / w, map_height / h);
  l.x0 = l.margin + 0.5 * (map_width - l.scale * w) - l.scale * xmin;
  l.y0 = top + 0.5 * (map_height + l.scale * h) + l.scale * ymin;
  l.frame = {l.px(xmin), l.py(ymax), l.scale * w, l.scale * h};

  l.legend_x = l.margin + map_width + 0.035 * W;
  l.legend_top = top + 2.4 * l.font;
  l.bar_height = std::min(map_height - 6.0 * l.font, 0.5 * W);
  return l;
}

// A cell of the picture: its vertices (Gmsh order, which is the outline's for triangles and
// quadrilaterals) in the coordinates.
struct Outline {
  std::span<const std::int64_t> vertices;
  std::size_t cell;    // its number, for its value
  double shade = 1.0;  // its colour's brightness (3D: how squarely it faces the light)
};

// Cell c's outline is vertices[first[c], first[c + 1]); the cells in the order they are drawn:
// triangles first, then quadrilaterals, each by number.
std::vector<Outline> in_drawing_order(std::span<const CellType> types,
                                      std::span<const std::int64_t> vertices,
                                      std::span<const std::size_t> first) {
  std::vector<Outline> out;
  out.reserve(types.size());
  for (CellType type : {CellType::Triangle, CellType::Quadrilateral})
    for (std::size_t c = 0; c < types.size(); ++c)
      if (types[c] == type) out.push_back({vertices.subspan(first[c], first[c + 1] - first[c]), c});
  return out;
}

// The cells of a mesh of triangles and quadrilaterals, in drawing order (in_drawing_order).
// Throws Error unless the arrays make a mesh of triangles and quadrilaterals (in the plane or,
// a surface mesh, in space).
std::vector<Outline> outlines(const MeshArrays& mesh) {
  std::vector<std::size_t> first(mesh.types.size() + 1, 0);
  for (std::size_t c = 0; c < mesh.types.size(); ++c) {
    if (mesh.types[c] != CellType::Triangle && mesh.types[c] != CellType::Quadrilateral)
      fail("render: cell {} is a {}, not a triangle or quadrilateral", c,
           facts(mesh.types[c]).name);
    first[c + 1] = first[c] + num_vertices(mesh.types[c]);
  }
  const auto vertex_count =
      static_cast<std::int64_t>(mesh.coordinates.size() / mesh.coordinate_dim);
  if (first.back() != mesh.cells.size())
    fail("render: {} vertex numbers for {} cells that have {}", mesh.cells.size(),
         mesh.types.size(), first.back());
  for (std::int64_t v : mesh.cells)
    if (v < 0 || v >= vertex_count)
      fail("render: a cell names vertex {}, but there are {} vertices", v, vertex_count);
  return in_drawing_order(mesh.types, mesh.cells, first);
}

void trace_cell(cairo_t* cr, const Layout& l, std::span<const double> coords, const Outline& cell) {
  for (std::size_t i = 0; i < cell.vertices.size(); ++i) {
    const std::int64_t vertex = cell.vertices[i];
    const double x = l.px(coords[2 * vertex]), y = l.py(coords[2 * vertex + 1]);
    i == 0 ? cairo_move_to(cr, x, y) : cairo_line_to(cr, x, y);
  }
  cairo_close_path(cr);
}

// Mean cell size on the picture: the square root of the mean |area| in picture units².
double mean_cell_pixels(std::span<const Outline> cells, const Layout& l,
                        std::span<const double> coords) {
  double area = 0;
  for (const Outline& cell : cells) {
    const std::size_t n = cell.vertices.size();
    double twice = 0;  // shoelace formula along the outline
    for (std::size_t i = 0; i < n; ++i) {
      const std::int64_t a = cell.vertices[i], b = cell.vertices[(i + 1) % n];
      twice += coords[2 * a] * coords[2 * b + 1] - coords[2 * b] * coords[2 * a + 1];
    }
    area += 0.5 * std::abs(twice);
  }
  return l.scale * std::sqrt(area / static_cast<double>(std::max<std::size_t>(cells.size(), 1)));
}

// The cells with a vertex inside the frame, or whose bounding box overlaps it.
std::vector<Outline> inside(std::span<const Outline> cells, const Layout& l,
                            std::span<const double> coords) {
  std::vector<Outline> out;
  const auto& [left, top, width, height] = l.frame;
  for (const Outline& cell : cells) {
    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    for (std::int64_t v : cell.vertices) {
      const double x = l.px(coords[2 * v]), y = l.py(coords[2 * v + 1]);
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    if (x1 >= left && x0 <= left + width && y1 >= top && y0 <= top + height) out.push_back(cell);
  }
  return out;
}

void draw_cells(cairo_t* cr, std::span<const Outline> cells, const Layout& l,
                std::span<const double> coords, std::span<const double> values,
                const ColourScale& scale) {
  // Stroking each cell in its own colour closes the hairline seams that antialiasing
  // leaves between neighbouring fills.
  cairo_set_line_width(cr, 0.6);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  // Invalid (inverted) cells last: an inverted cell overlaps its neighbours, which would
  // otherwise cover it.
  for (const bool invalid : {false, true})
    for (const Outline& cell : cells) {
      const double v = values[cell.cell];
      if (std::isfinite(v) == invalid) continue;
      set_colour(cr, invalid ? kInvalidColour : viridis(scale.position(v)));
      trace_cell(cr, l, coords, cell);
      cairo_fill_preserve(cr);
      cairo_stroke(cr);
    }
}

// All edges as one path, so that an edge shared by two cells is not darkened twice.
void draw_edges(cairo_t* cr, std::span<const Outline> cells, const Layout& l,
                std::span<const double> coords, double cell_pixels) {
  const double width = std::clamp(0.03 * cell_pixels, 0.3, 1.2);
  const double alpha = std::clamp(cell_pixels / 30, 0.1, 0.7);  // fading out as cells shrink
  for (const Outline& cell : cells) trace_cell(cr, l, coords, cell);
  set_colour(cr, kInk, alpha);
  cairo_set_line_width(cr, width);
  cairo_stroke(cr);
}

// A mesh in space seen from the eye, far to near: a 3D mesh's visible boundary faces of the
// cells drawn, or a surface mesh's cells drawn, both sides.
struct Projection {
  std::vector<double> coords;          // 2 per vertex: where it lands on the picture plane
  std::vector<std::int64_t> vertices;  // the faces' vertices (3D: outward, counter-clockwise seen)
  std::vector<Outline> faces;          // far to near, spans into `vertices`
};

// The side of a surface cell turned away from the light's side of the picture is drawn this
// much darker, so that the inside of an open surface reads as such.
constexpr double kBackSideShade = 0.7;

using Vector3 = Eigen::Vector3d;

Vector3 vertex(const MeshArrays& mesh, std::int64_t v) {
  return {mesh.coordinates[3 * v], mesh.coordinates[3 * v + 1], mesh.coordinates[3 * v + 2]};
}

// The faces that one cell drawn has and no other (the cut's faces among them), each with the
// outward order of its cell's facet (cell_type.hpp). Throws Error unless the arrays make a 3D
// mesh of volume cells.
struct Face {
  std::array<std::int64_t, 4> key;  // its vertices sorted, -1 padded
  std::array<std::int64_t, 4> vertices;
  int size;
  std::size_t cell;
};
std::vector<Face> boundary_faces(const MeshArrays& mesh, std::span<const std::uint8_t> drawn) {
  const auto vertex_count = static_cast<std::int64_t>(mesh.coordinates.size() / 3);
  std::vector<Face> faces;
  std::size_t first = 0;
  for (std::size_t c = 0; c < mesh.types.size(); ++c) {
    const CellFacts& f = facts(mesh.types[c]);
    if (f.dim != 3)
      fail("render: cell {} is a {} in a 3D mesh; only volume cells are drawn", c, f.name);
    if (first + f.vertices > mesh.cells.size())
      fail("render: {} vertex numbers are too few for {} cells", mesh.cells.size(),
           mesh.types.size());
    std::array<std::int64_t, 8> canonical{};  // Gmsh position i holds canonical gmsh_order[i]
    for (int i = 0; i < f.vertices; ++i) {
      const std::int64_t v = mesh.cells[first + i];
      if (v < 0 || v >= vertex_count)
        fail("render: a cell names vertex {}, but there are {} vertices", v, vertex_count);
      canonical[f.gmsh_order[i]] = v;
    }
    first += f.vertices;
    if (!drawn[c]) continue;
    for (int k = 0; k < f.num_facets; ++k) {
      Face face{.key = {-1, -1, -1, -1}, .vertices = {}, .size = f.facets[k].size, .cell = c};
      for (int i = 0; i < face.size; ++i)
        face.key[i] = face.vertices[i] = canonical[f.facets[k].vertices[i]];
      sort_facet_key(face.key, face.size);
      faces.push_back(face);
    }
  }
  if (first != mesh.cells.size())
    fail("render: {} vertex numbers for {} cells that have {}", mesh.cells.size(),
         mesh.types.size(), first);
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) {
    return a.key < b.key || (a.key == b.key && a.cell < b.cell);
  });
  std::vector<Face> single;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j == i + 1) single.push_back(faces[i]);
    i = j;
  }
  return single;
}

// A surface mesh's cells drawn (those the cut keeps), as faces. Throws Error unless the arrays
// make a mesh of triangles and quadrilaterals.
std::vector<Face> surface_faces(const MeshArrays& mesh, std::span<const std::uint8_t> drawn) {
  std::vector<Face> faces;
  for (const Outline& cell : outlines(mesh)) {
    if (!drawn[cell.cell]) continue;
    Face face{.key = {}, .vertices = {-1, -1, -1, -1}, .size = 0, .cell = cell.cell};
    face.size = static_cast<int>(cell.vertices.size());
    std::copy(cell.vertices.begin(), cell.vertices.end(), face.vertices.begin());
    faces.push_back(face);
  }
  return faces;
}

Projection project(const MeshArrays& mesh, const RenderOptions& o) {
  if (mesh.coordinates.size() % 3 != 0)
    fail("render: a mesh in space needs 3 coordinates per vertex");
  const auto vertex_count = static_cast<std::int64_t>(mesh.coordinates.size() / 3);
  Vector3 lo = Vector3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::int64_t v = 0; v < vertex_count; ++v)
    lo = lo.cwiseMin(vertex(mesh, v)), hi = hi.cwiseMax(vertex(mesh, v));
  if (vertex_count == 0) lo = hi = Vector3::Zero();
  const Vector3 centre = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * (hi - lo).norm(), 1e-300);

  // The camera: the eye on the unit vector e from the centre, far enough that the mesh fills
  // a 30° cone; r and u span the picture plane (right, up).
  const double az = o.azimuth * std::numbers::pi / 180, el = o.elevation * std::numbers::pi / 180;
  const Vector3 e(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  const Vector3 eye = centre + radius / std::tan(std::numbers::pi / 12) * e;
  Vector3 r = Vector3::UnitZ().cross(e);
  if (r.norm() < 1e-6) r = Vector3::UnitY().cross(e);  // looking straight down or up
  r.normalize();
  const Vector3 u = e.cross(r);
  const Vector3 light = (e + 0.4 * u - 0.3 * r).normalized();

  // The cells drawn: all, or those on the cut's far side.
  std::vector<std::uint8_t> drawn(mesh.types.size(), 1);
  if (o.cut) {
    const int a = o.cut->axis;
    const double at = o.cut->position.value_or(centre[a]);
    const double side = e[a] >= 0 ? 1.0 : -1.0;
    std::size_t first = 0;
    for (std::size_t c = 0; c < mesh.types.size(); ++c) {
      const int n = num_vertices(mesh.types[c]);
      double mean = 0;
      for (int i = 0; i < n && first + i < mesh.cells.size(); ++i) {
        const std::int64_t v = std::clamp<std::int64_t>(
            mesh.cells[first + i], 0, std::max<std::int64_t>(vertex_count - 1, 0));
        mean += vertex_count > 0 ? mesh.coordinates[3 * v + a] / n : 0.0;
      }
      drawn[c] = side * (mean - at) <= 0;
      first += n;
    }
  }

  Projection p;
  p.coords.resize(2 * vertex_count);
  for (std::int64_t v = 0; v < vertex_count; ++v) {
    const Vector3 q = vertex(mesh, v) - eye;
    const double depth = std::max(-q.dot(e), 1e-12 * radius);
    p.coords[2 * v] = q.dot(r) / depth;
    p.coords[2 * v + 1] = q.dot(u) / depth;
  }
  struct Visible {
    double depth, shade;
    std::size_t first, size, cell;
  };
  std::vector<Visible> visible;
  const bool surface = mesh.dim == 2;
  for (const Face& f : surface ? surface_faces(mesh, drawn) : boundary_faces(mesh, drawn)) {
    Vector3 normal = Vector3::Zero(), mid = Vector3::Zero();  // Newell's normal
    for (int i = 0; i < f.size; ++i) {
      const Vector3 a = vertex(mesh, f.vertices[i]), b = vertex(mesh, f.vertices[(i + 1) % f.size]);
      normal += a.cross(b);
      mid += a / f.size;
    }
    // A volume's faces turned away are hidden behind the ones turned towards the eye. A
    // surface's cells show either side (an open surface's inside shows through its opening),
    // the nearer ones drawn over the farther ones.
    const bool back = !(normal.dot(eye - mid) > 0);
    if (back && !surface) continue;
    if (back) normal = -normal;
    const double shade = (back ? kBackSideShade : 1.0) *
                         (0.45 + 0.55 * std::max(0.0, normal.normalized().dot(light)));
    visible.push_back({(eye - mid).dot(e), shade, p.vertices.size(), std::size_t(f.size), f.cell});
    p.vertices.insert(p.vertices.end(), f.vertices.begin(), f.vertices.begin() + f.size);
  }
  std::stable_sort(visible.begin(), visible.end(),
                   [](const Visible& a, const Visible& b) { return a.depth > b.depth; });
  for (const Visible& v : visible)
    p.faces.push_back(
        {std::span<const std::int64_t>(p.vertices).subspan(v.first, v.size), v.cell, v.shade});
  return p;
}

Rgb shaded(Rgb c, double shade) {
  return {c.r * shade, c.g * shade, c.b * shade};
}

// Far to near, each face filled and then outlined, so that nearer faces cover both.
void draw_faces(cairo_t* cr, std::span<const Outline> faces, const Layout& l,
                std::span<const double> coords, std::span<const double> values,
                const ColourScale& scale, double face_pixels, bool edges) {
  const double width = std::clamp(0.03 * face_pixels, 0.3, 1.2);
  const double alpha = std::clamp(face_pixels / 30, 0.1, 0.7);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const Outline& face : faces) {
    const double v = values[face.cell];
    const Rgb colour =
        shaded(std::isfinite(v) ? viridis(scale.position(v)) : kInvalidColour, face.shade);
    set_colour(cr, colour);
    trace_cell(cr, l, coords, face);
    cairo_fill_preserve(cr);
    cairo_set_line_width(cr, 0.6);
    cairo_stroke_preserve(cr);  // closes the seams antialiasing leaves between fills
    if (edges) {
      set_colour(cr, kInk, alpha);
      cairo_set_line_width(cr, width);
      cairo_stroke_preserve(cr);
    }
    cairo_new_path(cr);
  }
}

void draw_colour_bar(cairo_t* cr, const Layout& l, const Legend& g) {
  const double x = l.legend_x, top = l.legend_top, bottom = top + l.bar_height;
  set_colour(cr, kInk);
  draw_text(cr, g.name, x, top - 1.5 * l.font, l.font, Anchor::Left, true);

  cairo_pattern_t* gradient = cairo_pattern_create_linear(0, bottom, 0, top);
  for (const ColormapStop& stop : viridis_stops())
    cairo_pattern_add_color_stop_rgb(gradient, stop.t, stop.colour.r, stop.colour.g, stop.colour.b);
  cairo_rectangle(cr, x, top, l.bar_width, l.bar_height);
  cairo_set_source(cr, gradient);
  cairo_fill_preserve(cr);
  cairo_pattern_destroy(gradient);
  set_colour(cr, kInk);
  cairo_set_line_width(cr, 0.8);
  cairo_stroke(cr);

  const double right = x + l.bar_width;
  for (int i = 0; i < 3; ++i) {
    const double y = bottom - 0.5 * i * l.bar_height;
    cairo_move_to(cr, right, y);
    cairo_line_to(cr, right + kTickLength * l.font, y);
    cairo_stroke(cr);
    draw_text(cr, g.tick_labels[i], right + (kTickLength + kTickLabelGap) * l.font, y, l.font);
  }

  double y = bottom + 2.0 * l.font;
  if (!g.invalid.empty()) {
    set_colour(cr, kInvalidColour);
    cairo_rectangle(cr, x, y - 0.5 * l.font, l.font, l.font);
    cairo_fill(cr);
    set_colour(cr, kInk);
    draw_text(cr, g.invalid, x + 1.5 * l.font, y, l.font);
    y += 1.8 * l.font;
  }
  set_colour(cr, kMutedInk);
  draw_text(cr, g.count, x, y, 0.85 * l.font);
}

ColourBarRange draw_picture(std::span<const Outline> cells, std::span<const double> coords,
                            const Projection* projection, std::span<const double> cell_values,
                            const std::filesystem::path& out, const RenderOptions& options) {
  const bool in_space = projection != nullptr;
  picture_format(out);  // an unknown extension fails before any work
  const ColourScale scale = colour_scale(cell_values, options);
  const Legend g = legend(scale, options, cell_values);
  // Framed: what is drawn (a cut shows part of a 3D mesh).
  std::vector<double> framed;
  if (in_space)
    for (std::int64_t v : projection->vertices)
      framed.insert(framed.end(), {coords[2 * v], coords[2 * v + 1]});
  const Layout l = layout(in_space ? std::span<const double>(framed) : coords, options, g);

  Canvas canvas(out, l.width, l.height);
  cairo_t* cr = canvas.cr();
  if (!options.title.empty()) {
    set_colour(cr, kInk);
    draw_text(cr, options.title, l.margin, l.title_y, l.title_font, Anchor::Left, true);
  }
  // With a window, the cells that reach into it, clipped at its frame.
  const std::vector<Outline> shown =
      options.window ? inside(cells, l, coords) : std::vector<Outline>(cells.begin(), cells.end());
  cairo_save(cr);
  cairo_rectangle(cr, l.frame[0], l.frame[1], l.frame[2], l.frame[3]);
  cairo_clip(cr);
  const double cell_pixels = mean_cell_pixels(shown, l, coords);
  const bool edges = options.draw_edges && cell_pixels >= kMinCellPixelsForEdges;
  if (in_space) {
    draw_faces(cr, shown, l, coords, cell_values, scale, cell_pixels, edges);
  } else {
    draw_cells(cr, shown, l, coords, cell_values, scale);
    if (edges) draw_edges(cr, shown, l, coords, cell_pixels);
  }
  cairo_restore(cr);
  draw_colour_bar(cr, l, g);
  canvas.finish();
  return {scale.value_at(0), scale.value_at(1)};
}

// A curved (second-order) 2D mesh's cells as outlines: each edge drawn as kCurvedEdgeSegments
// straight segments of its quadratic curve through its corners and mid-edge node. `coords` holds
// the mesh's points (curved_point_coordinates) and gets the segments' points appended, the
// outlines' vertex lists are kept in `polygons`. Throws Error unless the mesh is one of triangle6
// and quadrilateral8/9 in the plane whose cells match `arrays` (Mesh::gather's: the same cells by
// number).
constexpr int kCurvedEdgeSegments = 16;

std::vector<Outline> curved_outlines(const InputMesh& mesh, const MeshArrays& arrays,
                                     std::vector<double>& coords,
                                     std::vector<std::int64_t>& polygons) {
  if (mesh.dim != 2 || mesh.coord_dim() != 2 || mesh.num_cells() != std::ssize(arrays.types))
    fail("render: internal error: the curved mesh does not match its cells");
  std::vector<std::size_t> first = {0};
  std::array<PetscInt, kMaxCurvedNodes> p{};
  const auto point = [&](PetscInt q, int j) { return coords[2 * q + j]; };
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    curved_cell_points(mesh, c, p.data());
    const CurvedFacts& f = facts(mesh.high_order.types[c]);
    const int corners = num_vertices(f.linear);
    // Gmsh lists a triangle's and a quadrilateral's edges around it, corner k to corner k + 1.
    for (std::size_t e = 0; e < f.edges.size(); ++e) {
      const PetscInt a = p[f.edges[e][0]], b = p[f.edges[e][1]], m = p[corners + e];
      polygons.push_back(a);
      for (int k = 1; k < kCurvedEdgeSegments; ++k) {
        const double t = static_cast<double>(k) / kCurvedEdgeSegments;
        const double wa = (1 - t) * (1 - 2 * t), wm = 4 * t * (1 - t), wb = t * (2 * t - 1);
        polygons.push_back(std::ssize(coords) / 2);
        for (int j = 0; j < 2; ++j)
          coords.push_back(wa * point(a, j) + wm * point(m, j) + wb * point(b, j));
      }
    }
    first.push_back(polygons.size());
  }
  return in_drawing_order(arrays.types, polygons, first);
}

}  // namespace

ColourBarRange render_mesh(const MeshArrays& mesh, std::span<const double> cell_values,
                           const std::filesystem::path& out, const RenderOptions& options) {
  if (mesh.dim != 2 && mesh.dim != 3) fail("render: a mesh of dimension {}", mesh.dim);
  if (mesh.coordinate_dim != mesh.dim && !(mesh.dim == 2 && mesh.coordinate_dim == 3))
    fail("render: {} coordinates per vertex for {}D cells", mesh.coordinate_dim, mesh.dim);
  // A 3D mesh, or a surface mesh: in space, drawn in perspective.
  const bool in_space = mesh.coordinate_dim == 3;
  if (in_space && options.window)
    fail(
        "render: a window zooms into a 2D mesh; a mesh in space is drawn whole (a cut shows "
        "inside)");
  if (!in_space && options.cut) fail("render: a cut opens a mesh in space; this mesh is 2D");
  if (options.cut && (options.cut->axis < 0 || options.cut->axis > 2))
    fail("render: cut axis {} is not x, y or z", options.cut->axis);
  std::vector<Outline> cells;
  Projection projection;
  if (!in_space) {
    cells = outlines(mesh);
  } else {
    projection = project(mesh, options);
    cells = projection.faces;
  }
  const std::span<const double> coords =
      in_space ? projection.coords : std::span<const double>(mesh.coordinates);
  const auto d = static_cast<std::size_t>(mesh.coordinate_dim);
  if (mesh.coordinates.size() % d != 0 || cell_values.size() != mesh.types.size())
    fail(
        "render: {} coordinates and {} cell values do not fit a mesh of {} vertices and {} "
        "cells",
        mesh.coordinates.size(), cell_values.size(), mesh.coordinates.size() / d,
        mesh.types.size());
  return draw_picture(cells, coords, in_space ? &projection : nullptr, cell_values, out, options);
}

// The whole curved mesh, high-order nodes and all, which Mesh's interface does not give.
struct MeshAccess {
  static InputMesh gather_curved(const Mesh& mesh) { return gather_mesh(mesh.plex(), {}).mesh; }
};

ColourBarRange render_mesh(const Mesh& mesh, std::span<const double> cell_values,
                           const std::filesystem::path& out, const RenderOptions& options) {
  picture_format(out);  // an unknown extension fails before the gather
  const MeshArrays whole = mesh.gather({{"value", {cell_values.begin(), cell_values.end()}}});
  // A curved 2D mesh: its edges curved, and its cells the certificate does not find valid in
  // red (the values, a straight cell's, do not see a fold between the corners).
  const bool curved = mesh.curved() && mesh.coordinate_dim() == 2;
  const InputMesh input = curved ? MeshAccess::gather_curved(mesh) : InputMesh{};
  ColourBarRange range;
  on_root(mesh.comm(), [&] {
    if (!curved) {
      range = render_mesh(whole, whole.cell_fields.front().values, out, options);
      return;
    }
    std::vector<double> values = whole.cell_fields.front().values;
    std::vector<double> coords = curved_point_coordinates(input);
    for (PetscInt c = 0; c < input.num_cells(); ++c) {
      const CurvedScaledJacobian q = curved_cell_quality(input, coords, c);
      if (q.certificate.validity != Validity::Valid)
        values[c] = std::numeric_limits<double>::quiet_NaN();
      else if (options.curved_scaled_jacobian)
        values[c] = q.upper;
    }
    std::vector<std::int64_t> polygons;
    const std::vector<Outline> cells = curved_outlines(input, whole, coords, polygons);
    RenderOptions o = options;
    o.invalid_label = "not certified valid";
    range = draw_picture(cells, coords, nullptr, values, out, o);
  });
  return range;
}

}  // namespace neomesh
