#include "mesh/feat_reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <string_view>

#include <petscsys.h>
#include <pugixml.hpp>

#include "core/error.hpp"
#include "mesh/input_file.hpp"

namespace neomesh {

namespace {

// FEAT3 chart types neomesh does not use: skipped (a part on one of them has no chart).
constexpr std::string_view kSkippedCharts[] = {"Extrude", "Tube", "Spline", "Polyline",
                                               "CGALSurfaceMesh"};

// A curved Bezier segment becomes this many straight pieces (its points lie on the curve).
constexpr int kBezierPieces = 8;

// Vertex indices must fit PetscInt (and were once silently wrapped at 2^32).
constexpr std::int64_t kMaxIndex = PETSC_MAX_INT;

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

// The whitespace-separated words of `text`.
std::vector<std::string_view> words(std::string_view text) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && is_blank(text[i])) ++i;
    const std::size_t first = i;
    while (i < text.size() && !is_blank(text[i])) ++i;
    if (i > first) out.push_back(text.substr(first, i - first));
  }
  return out;
}

// The word as a T, or nullopt unless all of it is one.
template <typename T>
std::optional<T> number(std::string_view word) {
  T value{};
  const char* first = word.data();
  const char* last = first + word.size();
  if (first != last && *first == '+') ++first;
  const auto [next, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || next != last) return std::nullopt;
  return value;
}

class FeatParser {
 public:
  explicit FeatParser(const std::filesystem::path& path)
      : file_(path.string()), text_(read_input_file(path)) {
    for (std::size_t i = 0; i < text_.size(); ++i)
      if (text_[i] == '\n') newlines_.push_back(static_cast<std::ptrdiff_t>(i));
  }

  MeshData parse() {
    const pugi::xml_parse_result result =
        doc_.load_buffer(text_.data(), text_.size(), pugi::parse_default, pugi::encoding_utf8);
    if (!result) {
      if (result.offset + 1 >= static_cast<std::ptrdiff_t>(text_.size()))
        error_at(result.offset, "unexpected end of file (truncated?): {}", result.description());
      error_at(result.offset, "not a valid XML file ({})", result.description());
    }
    const pugi::xml_node root = doc_.document_element();
    if (std::string_view(root.name()) != "FeatMeshFile")
      error(root, "expected <FeatMeshFile>, found <{}>", shown(root.name()));
    // Mesh first, then the charts, then the parts that refer to both: in any order in the file.
    pugi::xml_node mesh;
    for (pugi::xml_node node : root.children("Mesh")) {
      if (mesh) error(node, "a second <Mesh> block (neomesh reads one mesh per file)");
      mesh = node;
    }
    if (!mesh) error_at(static_cast<std::ptrdiff_t>(text_.size()), "no <Mesh> block");
    read_mesh(mesh);
    for (pugi::xml_node chart : root.children("Chart")) read_chart(chart);
    for (pugi::xml_node part : root.children("MeshPart")) read_part(part);
    return std::move(data_);
  }

 private:
  // The 1-based line of a byte offset of the file.
  int line_of(std::ptrdiff_t offset) const {
    return static_cast<int>(std::lower_bound(newlines_.begin(), newlines_.end(), offset) -
                            newlines_.begin()) +
           1;
  }
  int line_of(pugi::xml_node node) const { return line_of(node.offset_debug()); }

  template <typename... Args>
  [[noreturn]] void error_at(std::ptrdiff_t offset, fmt::format_string<Args...> format,
                             Args&&... args) {
    error_line(line_of(offset), format, std::forward<Args>(args)...);
  }
  template <typename... Args>
  [[noreturn]] void error(pugi::xml_node node, fmt::format_string<Args...> format, Args&&... args) {
    error_line(line_of(node), format, std::forward<Args>(args)...);
  }
  template <typename... Args>
  [[noreturn]] void error_line(int line, fmt::format_string<Args...> format, Args&&... args) {
    fail("{}:{}: {}", file_, line, fmt::format(format, std::forward<Args>(args)...));
  }

  // A piece of the file for a message: short, printable, on one line.
  static std::string shown(std::string_view text) {
    std::string out(text.substr(0, 40));
    for (char& c : out)
      if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
    return text.size() > 40 ? out + "..." : out;
  }

  std::string_view attribute(pugi::xml_node node, const char* key) {
    const pugi::xml_attribute a = node.attribute(key);
    if (!a) error(node, "<{}> has no {}=\"...\" attribute", shown(node.name()), key);
    return a.value();
  }

  // An attribute holding exactly `n` finite numbers.
  std::vector<double> reals(pugi::xml_node node, const char* key, std::size_t n) {
    std::vector<double> out;
    for (std::string_view w : words(attribute(node, key))) {
      const auto value = number<double>(w);
      if (!value || !std::isfinite(*value))
        error(node, "<{}> {}=\"...\" has '{}', not a finite number", shown(node.name()), key,
              shown(w));
      out.push_back(*value);
    }
    if (out.size() != n)
      error(node, "<{}> {}=\"...\" has {} numbers, expected {}", shown(node.name()), key,
            out.size(), n);
    return out;
  }

  std::int64_t count_attribute(pugi::xml_node node, const char* key) {
    const auto w = words(attribute(node, key));
    const auto value = w.empty() ? std::nullopt : number<std::int64_t>(w[0]);
    if (!value || *value < 0 || *value > kMaxIndex)
      error(node, "<{}> {}=\"...\" is not a count", shown(node.name()), key);
    return *value;
  }

  // The one child element `name` of `parent`, or an error.
  pugi::xml_node child(pugi::xml_node parent, const char* name) {
    const pugi::xml_node c = parent.child(name);
    if (!c) error(parent, "<{}> has no <{}> block", shown(parent.name()), name);
    return c;
  }

  // Calls row(line, values) for each non-blank line of the text inside `block`, with the
  // line's words (`per_line` of them unless 0).
  template <typename Row>
  void for_each_line(pugi::xml_node block, std::size_t per_line, Row&& row) {
    if (pugi::xml_node inner =
            block.find_child([](pugi::xml_node n) { return n.type() == pugi::node_element; }))
      error(inner, "unexpected <{}> inside <{}>", shown(inner.name()), shown(block.name()));
    for (pugi::xml_node text : block.children()) {
      if (text.type() != pugi::node_pcdata && text.type() != pugi::node_cdata) continue;
      const std::string_view all = text.value();
      int line = line_of(text);
      for (std::size_t first = 0; first <= all.size(); ++line) {
        std::size_t eol = all.find('\n', first);
        if (eol == std::string_view::npos) eol = all.size();
        const auto w = words(all.substr(first, eol - first));
        if (!w.empty()) {
          if (per_line > 0 && w.size() != per_line)
            error_line(line, "expected {} numbers per line in <{}>, found {}", per_line,
                       shown(block.name()), w.size());
          row(line, w);
        }
        first = eol + 1;
      }
    }
  }

  std::vector<double> read_reals(pugi::xml_node block, std::size_t per_line) {
    std::vector<double> values;
    for_each_line(block, per_line, [&](int line, const std::vector<std::string_view>& w) {
      for (std::string_view word : w) {
        const auto value = number<double>(word);
        if (!value || !std::isfinite(*value))
          error_line(line, "'{}' in <{}> is not a finite number", shown(word), shown(block.name()));
        values.push_back(*value);
      }
    });
    return values;
  }

  // Indices into `size` items (vertices, or a chart's points).
  std::vector<std::int64_t> read_indices(pugi::xml_node block, std::size_t per_line,
                                         std::int64_t size, const char* what) {
    std::vector<std::int64_t> values;
    for_each_line(block, per_line, [&](int line, const std::vector<std::string_view>& w) {
      for (std::string_view word : w) {
        const auto value = number<std::int64_t>(word);
        if (!value || *value < 0 || *value > kMaxIndex)
          error_line(line, "'{}' in <{}> is not a valid {} index", shown(word), shown(block.name()),
                     what);
        if (*value >= size)
          error_line(line, "<{}> refers to {} {}, but there are {}", shown(block.name()), what,
                     *value, size);
        values.push_back(*value);
      }
    });
    return values;
  }

  void read_type(pugi::xml_node mesh) {
    const std::string_view type = attribute(mesh, "type");
    const auto unsupported = [&] {
      error(mesh, "unsupported mesh type '{}' (expected conformal:hypercube|simplex:d:d)",
            shown(type));
    };
    if (!type.starts_with("conformal:")) unsupported();
    const std::string_view rest = type.substr(10);
    bool simplex = false;
    std::string_view dims;
    if (rest.starts_with("hypercube:"))
      dims = rest.substr(10);
    else if (rest.starts_with("simplex:"))
      dims = rest.substr(8), simplex = true;
    else
      unsupported();
    if (dims.size() != 3 || dims[1] != ':' || !std::isdigit(static_cast<unsigned char>(dims[0])) ||
        !std::isdigit(static_cast<unsigned char>(dims[2])))
      unsupported();
    const int shape_dim = dims[0] - '0', world_dim = dims[2] - '0';
    if (shape_dim != world_dim || shape_dim < 2 || shape_dim > 3)
      error(mesh, "unsupported mesh type '{}': neomesh needs 2D or 3D cells in as many dimensions",
            shown(type));
    data_.dim = shape_dim;
    data_.cell_type = shape_dim == 2 ? (simplex ? CellType::Triangle : CellType::Quadrilateral)
                                     : (simplex ? CellType::Tetrahedron : CellType::Hexahedron);
  }

  void read_mesh(pugi::xml_node mesh) {
    read_type(mesh);
    const std::int64_t announced = count_attribute(mesh, "size");
    const pugi::xml_node vertices = child(mesh, "Vertices");
    data_.coords = read_reals(vertices, data_.dim);
    if (data_.num_vertices() != announced)
      error(vertices, "<Mesh size=...> announces {} vertices, <Vertices> has {}", announced,
            data_.num_vertices());
    pugi::xml_node cells;
    for (pugi::xml_node topology : mesh.children("Topology"))
      if (number<int>(attribute(topology, "dim")) == data_.dim) cells = topology;
    if (!cells) error(mesh, "<Mesh> has no <Topology dim=\"{}\"> block", data_.dim);
    data_.cells =
        read_indices(cells, num_vertices(data_.cell_type), data_.num_vertices(), "vertex");
    if (data_.cells.empty()) error(cells, "<Topology dim=\"{}\"> has no cells", data_.dim);
  }

  // The chart's shape: the first element inside <Chart>.
  void read_chart(pugi::xml_node node) {
    Chart chart;
    chart.name = attribute(node, "name");
    if (!chart_names_.insert(chart.name).second)
      error(node, "a second chart named '{}'", shown(chart.name));
    const pugi::xml_node shape =
        node.find_child([](pugi::xml_node n) { return n.type() == pugi::node_element; });
    if (!shape) error(node, "<Chart name=\"{}\"> has no shape inside", shown(chart.name));
    const std::string_view type = shape.name();
    if (std::find(std::begin(kSkippedCharts), std::end(kSkippedCharts), type) !=
        std::end(kSkippedCharts))
      return;
    if (type == "Circle" || type == "Sphere") {
      const std::size_t dim = type == "Circle" ? 2 : 3;
      chart.kind = type == "Circle" ? Chart::Kind::Circle : Chart::Kind::Sphere;
      chart.radius = reals(shape, "radius", 1)[0];
      if (chart.radius <= 0) error(shape, "<{}> radius=\"...\" must be positive", type);
      const auto midpoint = reals(shape, "midpoint", dim);
      std::copy(midpoint.begin(), midpoint.end(), chart.centre.begin());
    } else if (type == "Bezier") {
      read_bezier(shape, chart);
    } else if (type == "SurfaceMesh") {
      chart.kind = Chart::Kind::SurfaceMesh;
      const std::int64_t verts = count_attribute(shape, "verts");
      const std::int64_t trias = count_attribute(shape, "trias");
      const pugi::xml_node points = child(shape, "Vertices");
      chart.points = read_reals(points, 3);
      if (static_cast<std::int64_t>(chart.points.size()) != 3 * verts)
        error(points, "<SurfaceMesh verts=\"{}\"> has {} vertices", verts, chart.points.size() / 3);
      const pugi::xml_node triangles = child(shape, "Triangles");
      chart.triangles = read_indices(triangles, 3, verts, "point");
      if (static_cast<std::int64_t>(chart.triangles.size()) != 3 * trias)
        error(triangles, "<SurfaceMesh trias=\"{}\"> has {} triangles", trias,
              chart.triangles.size() / 3);
    } else {
      error(shape,
            "chart '{}' is a <{}>; neomesh reads Circle, Sphere, Bezier and SurfaceMesh charts",
            shown(chart.name), shown(type));
    }
    data_.charts.push_back(std::move(chart));
    usable_charts_.insert(data_.charts.back().name);
  }

  // <Points> lines "k x y" followed by k inner control points (x y each): the curve passes
  // through the first point of each line; a line's segment to the next line's point is a
  // Bezier curve of degree k + 1, sampled into kBezierPieces straight pieces when curved.
  void read_bezier(pugi::xml_node shape, Chart& chart) {
    chart.kind = Chart::Kind::Polyline;
    if (number<int>(attribute(shape, "dim")) != 2)
      error(shape, "<Bezier dim=\"...\"> must be 2 (a curve in the plane)");
    const std::string_view type = shape.attribute("type").value();
    if (type != "" && type != "open" && type != "closed")
      error(shape, "<Bezier type=\"{}\">: expected open or closed", shown(type));
    chart.closed = type == "closed";
    const std::int64_t size = count_attribute(shape, "size");
    const pugi::xml_node points = child(shape, "Points");
    std::vector<std::vector<double>> segments;  // per line: its point, then its controls
    for_each_line(points, 0, [&](int line, const std::vector<std::string_view>& w) {
      const auto degree = number<std::int64_t>(w[0]);
      if (!degree || *degree < 0 || w.size() != 3 + 2 * static_cast<std::size_t>(*degree))
        error_line(line, "a <Points> line of a Bezier chart is 'k x y' and k more points");
      std::vector<double> values;
      for (std::size_t i = 1; i < w.size(); ++i) {
        const auto value = number<double>(w[i]);
        if (!value || !std::isfinite(*value))
          error_line(line, "'{}' in <Points> is not a finite number", shown(w[i]));
        values.push_back(*value);
      }
      segments.push_back(std::move(values));
    });
    if (static_cast<std::int64_t>(segments.size()) != size || size < 2)
      error(points, "<Bezier size=\"{}\"> has {} points (at least 2 needed)", size,
            segments.size());
    for (std::size_t s = 0; s < segments.size(); ++s) {
      const std::vector<double>& p = segments[s];
      chart.points.insert(chart.points.end(), p.begin(), p.begin() + 2);
      if (p.size() == 2 || s + 1 == segments.size()) continue;
      std::vector<double> control(p);  // de Casteljau on point, controls, next point
      control.insert(control.end(), segments[s + 1].begin(), segments[s + 1].begin() + 2);
      for (int piece = 1; piece < kBezierPieces; ++piece)
        append_bezier_point(control, static_cast<double>(piece) / kBezierPieces, chart.points);
    }
    // A closed curve's file repeats its first point at the end.
    const std::size_t n = chart.points.size();
    if (chart.closed && n >= 4 && chart.points[n - 2] == chart.points[0] &&
        chart.points[n - 1] == chart.points[1])
      chart.points.resize(n - 2);
  }

  static void append_bezier_point(std::vector<double> control, double t, std::vector<double>& out) {
    for (std::size_t n = control.size() / 2; n > 1; --n)
      for (std::size_t i = 0; i + 1 < n; ++i)
        for (int d = 0; d < 2; ++d)
          control[2 * i + d] = (1 - t) * control[2 * i + d] + t * control[2 * (i + 1) + d];
    out.push_back(control[0]);
    out.push_back(control[1]);
  }

  void read_part(pugi::xml_node part) {
    VertexSet set;
    set.name = attribute(part, "name");
    set.tag = static_cast<int>(data_.boundary_parts.size()) + 1;
    if (const pugi::xml_attribute chart = part.attribute("chart")) {
      if (!chart_names_.count(chart.value()))
        error(part, "<MeshPart name=\"{}\"> lies on chart '{}', which the file does not declare",
              shown(set.name), shown(chart.value()));
      if (usable_charts_.count(chart.value())) set.chart = chart.value();
    }
    for (pugi::xml_node mapping : part.children("Mapping"))
      if (number<int>(attribute(mapping, "dim")) == 0)
        set.vertices = read_indices(mapping, 1, data_.num_vertices(), "vertex");
    data_.boundary_parts.push_back(std::move(set));
  }

  std::string file_;
  InputText text_;
  std::vector<std::ptrdiff_t> newlines_;  // byte offsets of the file's '\n's
  pugi::xml_document doc_;
  std::set<std::string, std::less<>> chart_names_, usable_charts_;
  MeshData data_;
};

}  // namespace

MeshData read_feat(const std::filesystem::path& path) {
  return FeatParser(path).parse();
}

}  // namespace neomesh
