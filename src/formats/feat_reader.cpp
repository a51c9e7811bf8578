#include "formats/feat_reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string_view>

#include <petscsys.h>
#include <pugixml.hpp>

#include "core/error.hpp"
#include "core/log.hpp"
#include "formats/input_file.hpp"

namespace neomesh {

namespace {

// FEAT3 chart types neomesh does not use: skipped (a part on one of them has no chart).
constexpr std::string_view kSkippedCharts[] = {"Tube", "Spline", "Polyline", "CGALSurfaceMesh"};

// FEAT3's Bezier segments have degree 5 at most.
constexpr std::int64_t kMaxBezierDegree = 5;

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

// FEAT3's own XML parser splits a tag's attributes at their quotes, so it reads
// `chart="inner"parent="root"` (no blank between two attributes), which pugixml refuses: such
// a blank is put in. Comments, CDATA and text between tags are left alone; no newline is added,
// so line numbers stay those of the file.
void separate_attributes(InputText& text) {
  std::size_t i = 0;
  const auto skip_past = [&](std::string_view end) {
    const std::size_t at = text.find(end.data(), i, end.size());
    i = at == InputText::npos ? text.size() : at + end.size();
  };
  while ((i = text.find('<', i)) != InputText::npos) {
    const std::string_view rest(text.data() + i, text.size() - i);
    if (rest.starts_with("<!--")) {
      skip_past("-->");
      continue;
    }
    if (rest.starts_with("<![CDATA[")) {
      skip_past("]]>");
      continue;
    }
    for (++i; i < text.size() && text[i] != '>' && text[i] != '<'; ++i) {
      const char quote = text[i];
      if (quote != '"' && quote != '\'') continue;
      const std::size_t close = text.find(quote, i + 1);
      if (close == InputText::npos) return;  // pugixml reports it
      i = close;
      const char next = close + 1 < text.size() ? text[close + 1] : ' ';
      if (std::isalpha(static_cast<unsigned char>(next)) || next == '_' || next == ':')
        text.insert(close + 1, 1, ' ');
    }
  }
}

class FeatParser {
 public:
  explicit FeatParser(const std::filesystem::path& path)
      : file_(path.string()), text_(read_input_file(path)) {
    separate_attributes(text_);
    for (std::size_t i = 0; i < text_.size(); ++i)
      if (text_[i] == '\n') newlines_.push_back(static_cast<std::ptrdiff_t>(i));
  }

  // The file's mesh (if it has one: a chart file has none), charts and parts; parts keep the
  // name of their chart whether or not this file declares it (read_feat resolves them).
  FeatFile parse() {
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
    FeatFile out;
    out.path = file_;
    out.has_mesh = static_cast<bool>(mesh);
    if (mesh) read_mesh(mesh);
    for (pugi::xml_node chart : root.children("Chart")) read_chart(chart);
    if (mesh)
      for (pugi::xml_node part : root.children("MeshPart")) read_part(part);
    if (!mesh && data_.charts.empty() && skipped_charts_.empty())
      error_at(static_cast<std::ptrdiff_t>(text_.size()), "no <Mesh> block and no <Chart>");
    out.data = std::move(data_);
    out.skipped_charts = std::move(skipped_charts_);
    return out;
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
  static std::string shown(std::string_view text) { return shown_text(text, 40); }

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
    pugi::xml_node shape = first_element(node);
    if (!shape) error(node, "<Chart name=\"{}\"> has no shape inside", shown(chart.name));
    if (std::string_view(shape.name()) == "Extrude") {
      // FEAT3 extrudes a 2D Circle, Bezier or Polyline along z.
      chart.extruded = true;
      const auto placement = [&](const char* key, std::size_t n, std::array<double, 3>& out) {
        if (!shape.attribute(key)) return;
        const auto v = reals(shape, key, n);
        std::copy(v.begin(), v.end(), out.begin());
      };
      placement("origin", 2, chart.origin);
      placement("offset", 3, chart.offset);
      placement("angles", 3, chart.angles);
      shape = first_element(shape);
      if (!shape) error(node, "<Chart name=\"{}\"> has an empty <Extrude>", shown(chart.name));
      const std::string_view inner = shape.name();
      if (inner != "Circle" && inner != "Bezier" && inner != "Polyline")
        error(shape, "chart '{}' extrudes a <{}>; FEAT3 extrudes Circle, Bezier or Polyline",
              shown(chart.name), shown(inner));
    }
    const std::string_view type = shape.name();
    if (std::find(std::begin(kSkippedCharts), std::end(kSkippedCharts), type) !=
        std::end(kSkippedCharts)) {
      skipped_charts_.push_back(chart.name);
      return;
    }
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
            "chart '{}' is a <{}>; neomesh reads Circle, Sphere, Bezier, SurfaceMesh and Extrude "
            "charts",
            shown(chart.name), shown(type));
    }
    data_.charts.push_back(std::move(chart));
  }

  static pugi::xml_node first_element(pugi::xml_node parent) {
    return parent.find_child([](pugi::xml_node n) { return n.type() == pugi::node_element; });
  }

  // <Points> lines "k c1x c1y ... ckx cky x y" (FEAT3's BezierPointsParser): the segment from
  // the previous line's vertex to this line's vertex (x, y) is a Bezier curve with the k inner
  // control points before it (degree k + 1); the first line is "0 x y". A closed curve's file
  // repeats its first vertex at the end, so the segments are those between consecutive lines.
  void read_bezier(pugi::xml_node shape, Chart& chart) {
    chart.kind = Chart::Kind::Bezier;
    if (number<int>(attribute(shape, "dim")) != 2)
      error(shape, "<Bezier dim=\"...\"> must be 2 (a curve in the plane)");
    const std::string_view type = shape.attribute("type").value();
    if (type != "" && type != "open" && type != "closed")
      error(shape, "<Bezier type=\"{}\">: expected open or closed", shown(type));
    const std::int64_t size = count_attribute(shape, "size");
    const pugi::xml_node points = child(shape, "Points");
    for_each_line(points, 0, [&](int line, const std::vector<std::string_view>& w) {
      const auto inner = number<std::int64_t>(w[0]);
      const bool first = chart.vertices.empty();
      if (!inner || *inner < 0 || *inner >= kMaxBezierDegree || (first && *inner != 0) ||
          w.size() != 3 + 2 * static_cast<std::size_t>(*inner))
        error_line(line,
                   "a <Points> line of a Bezier chart is 'k', k control points and the vertex "
                   "'x y' (k < {}; 0 on the first line)",
                   kMaxBezierDegree);
      for (std::size_t i = 1; i < w.size(); ++i) {
        const auto value = number<double>(w[i]);
        if (!value || !std::isfinite(*value))
          error_line(line, "'{}' in <Points> is not a finite number", shown(w[i]));
        chart.points.push_back(*value);
      }
      chart.vertices.push_back(static_cast<std::int64_t>(chart.points.size() / 2) - 1);
    });
    if (static_cast<std::int64_t>(chart.vertices.size()) != size || size < 2)
      error(points, "<Bezier size=\"{}\"> has {} points (at least 2 needed)", size,
            chart.vertices.size());
  }

  void read_part(pugi::xml_node part) {
    VertexSet set;
    set.name = attribute(part, "name");
    set.tag = static_cast<int>(data_.boundary_parts.size()) + 1;
    set.chart = part.attribute("chart").value();  // "" (or no attribute): on no chart
    for (pugi::xml_node mapping : part.children("Mapping"))
      if (number<int>(attribute(mapping, "dim")) == 0)
        set.vertices = read_indices(mapping, 1, data_.num_vertices(), "vertex");
    data_.boundary_parts.push_back(std::move(set));
  }

  std::string file_;
  InputText text_;
  std::vector<std::ptrdiff_t> newlines_;  // byte offsets of the file's '\n's
  pugi::xml_document doc_;
  std::set<std::string, std::less<>> chart_names_;
  std::vector<std::string> skipped_charts_;
  MeshData data_;
};

std::string list(std::span<const std::filesystem::path> paths) {
  std::string out;
  for (const auto& p : paths) out += (out.empty() ? "" : ", ") + p.string();
  return out;
}

}  // namespace

FeatFile read_feat_file(const std::filesystem::path& path) {
  return FeatParser(path).parse();
}

MeshData read_feat(std::span<const std::filesystem::path> paths) {
  std::vector<FeatFile> files;
  for (const auto& path : paths) files.push_back(read_feat_file(path));
  const FeatFile* mesh = nullptr;
  for (const FeatFile& f : files)
    if (f.has_mesh) {
      if (mesh)
        fail("{} and {} both hold a <Mesh>; give one mesh file and its chart files", mesh->path,
             f.path);
      mesh = &f;
    }
  if (!mesh)
    fail("{}: no <Mesh> block in {}", list(paths),
         paths.size() > 1 ? "any of these files" : "the file");
  MeshData data = mesh->data;
  // The charts of all files, once each; a part's chart in none of them means no chart.
  std::map<std::string, std::string, std::less<>> defined_in;  // chart name → file
  data.charts.clear();
  for (const FeatFile& f : files) {
    std::vector<std::string> names = f.skipped_charts;
    for (const Chart& c : f.data.charts) names.push_back(c.name);
    for (const std::string& name : names)
      if (const auto [it, added] = defined_in.emplace(name, f.path); !added)
        fail("{}: chart '{}' is defined in {} too; give each chart once", f.path, name, it->second);
    data.charts.insert(data.charts.end(), f.data.charts.begin(), f.data.charts.end());
  }
  for (VertexSet& part : data.boundary_parts) {
    if (part.chart.empty()) continue;
    const bool usable = std::any_of(data.charts.begin(), data.charts.end(),
                                    [&](const Chart& c) { return c.name == part.chart; });
    if (!usable && !defined_in.count(part.chart))
      say("notice: {}: part '{}' lies on chart '{}', which {} does not define; it is read as a "
          "part without chart\n",
          mesh->path, part.name, part.chart,
          paths.size() > 1 ? "none of the given files" : "the file");
    if (!usable) part.chart.clear();
  }
  return data;
}

MeshData read_feat(const std::filesystem::path& path) {
  return read_feat(std::span<const std::filesystem::path>(&path, 1));
}

}  // namespace neomesh
