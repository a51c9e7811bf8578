#include "mesh/feat_reader.hpp"

#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "core/error.hpp"

namespace neomesh {

namespace {

struct Tag {
  std::string name;  // "Mesh", or "/Mesh" for a closing tag
  std::map<std::string, std::string> attributes;
  bool empty = false;  // <Tag ... />: no content, no closing tag
};

class FeatParser {
 public:
  explicit FeatParser(const std::filesystem::path& path) : file_(path.string()), in_(path) {
    if (!in_) fail("{}: cannot be opened for reading", file_);
  }

  MeshData parse() {
    Tag root = next_tag();
    if (root.name == "?xml") root = next_tag();
    if (root.name != "FeatMeshFile") error("expected <FeatMeshFile>, found <{}>", root.name);
    for (Tag tag = next_tag(); tag.name != "/FeatMeshFile"; tag = next_tag()) {
      if (tag.name == "Mesh")
        read_mesh(tag);
      else if (tag.name == "MeshPart")
        read_part(tag);
      else
        skip_block(tag);
    }
    if (data_.coords.empty()) error("no <Mesh> block");
    return std::move(data_);
  }

 private:
  template <typename... Args>
  [[noreturn]] void error(fmt::format_string<Args...> format, Args&&... args) {
    fail("{}:{}: {}", file_, line_number_, fmt::format(format, std::forward<Args>(args)...));
  }

  // The next non-empty line, trimmed; error at the end of the file.
  std::string next_line() {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_number_;
      const auto first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos) continue;
      return line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
    }
    error("unexpected end of file (truncated?)");
  }

  static bool is_tag(const std::string& line) { return line.front() == '<'; }

  Tag parse_tag(const std::string& line) {
    static const std::regex name(R"(^<\s*(/?[?\w]+))");
    static const std::regex attribute(R"((\w+)\s*=\s*\"([^\"]*)\")");
    std::smatch m;
    if (line.back() != '>' || !std::regex_search(line, m, name)) error("malformed tag '{}'", line);
    Tag tag{m[1], {}, line.ends_with("/>")};
    for (auto it = std::sregex_iterator(line.begin(), line.end(), attribute);
         it != std::sregex_iterator(); ++it)
      tag.attributes[(*it)[1]] = (*it)[2];
    return tag;
  }

  Tag next_tag() {
    const std::string line = next_line();
    if (!is_tag(line)) error("expected a tag, found '{}'", line);
    return parse_tag(line);
  }

  std::string attribute(const Tag& tag, const std::string& key) {
    auto it = tag.attributes.find(key);
    if (it == tag.attributes.end()) error("<{}> has no {}=\"...\" attribute", tag.name, key);
    return it->second;
  }

  // Lines of numbers up to </name>, each with `per_line` values (any number if 0).
  template <typename T>
  std::vector<T> read_numbers(const std::string& name, int per_line) {
    std::vector<T> values;
    for (std::string line = next_line(); line != "</" + name + ">"; line = next_line()) {
      if (is_tag(line)) error("expected </{}>, found '{}'", name, line);
      std::istringstream fields(line);
      int count = 0;
      for (T value; fields >> value; ++count) values.push_back(value);
      if (!fields.eof() || (per_line > 0 && count != per_line))
        error("expected {} numbers in <{}>, found '{}'", per_line, name, line);
    }
    return values;
  }

  void skip_block(const Tag& tag) {
    if (tag.name.starts_with('/')) error("unexpected closing tag <{}>", tag.name);
    if (tag.empty) return;
    for (std::string line = next_line(); line != "</" + tag.name + ">"; line = next_line())
      if (is_tag(line)) {
        Tag inner = parse_tag(line);
        if (inner.name.starts_with('/')) error("expected </{}>, found '{}'", tag.name, line);
        skip_block(inner);
      }
  }

  void read_type(const std::string& type) {
    static const std::regex pattern(R"(^conformal:(hypercube|simplex):(\d):(\d)$)");
    std::smatch m;
    if (!std::regex_match(type, m, pattern))
      error("unsupported mesh type '{}' (expected conformal:hypercube|simplex:d:d)", type);
    const int shape_dim = std::stoi(m[2]), world_dim = std::stoi(m[3]);
    if (shape_dim != world_dim || shape_dim < 2 || shape_dim > 3)
      error("unsupported mesh type '{}': neomesh needs 2D or 3D cells in as many dimensions", type);
    const bool simplex = m[1] == "simplex";
    data_.dim = shape_dim;
    data_.cell_type = shape_dim == 2 ? (simplex ? CellType::Triangle : CellType::Quadrilateral)
                                     : (simplex ? CellType::Tetrahedron : CellType::Hexahedron);
  }

  void read_mesh(const Tag& mesh) {
    read_type(attribute(mesh, "type"));
    std::istringstream sizes(attribute(mesh, "size"));
    std::int64_t num_vertices = -1;
    sizes >> num_vertices;
    for (Tag tag = next_tag(); tag.name != "/Mesh"; tag = next_tag()) {
      if (tag.name == "Vertices") {
        data_.coords = read_numbers<double>("Vertices", data_.dim);
      } else if (tag.name == "Topology" && std::stoi(attribute(tag, "dim")) == data_.dim) {
        data_.cells = read_numbers<std::int64_t>("Topology", num_vertices_per_cell());
      } else {
        skip_block(tag);
      }
    }
    if (data_.num_vertices() != num_vertices)
      error("<Mesh size=...> announces {} vertices, <Vertices> has {}", num_vertices,
            data_.num_vertices());
    if (data_.cells.empty()) error("<Mesh> has no <Topology dim=\"{}\"> block", data_.dim);
  }

  int num_vertices_per_cell() const { return num_vertices(data_.cell_type); }

  void read_part(const Tag& part) {
    VertexSet set{attribute(part, "name"), static_cast<int>(data_.boundary_parts.size()) + 1, {}};
    for (Tag tag = next_tag(); tag.name != "/MeshPart"; tag = next_tag()) {
      if (tag.name == "Mapping" && attribute(tag, "dim") == "0")
        set.vertices = read_numbers<std::int64_t>("Mapping", 1);
      else
        skip_block(tag);
    }
    data_.boundary_parts.push_back(std::move(set));
  }

  std::string file_;
  std::ifstream in_;
  int line_number_ = 0;
  MeshData data_;
};

}  // namespace

MeshData read_feat(const std::filesystem::path& path) {
  return FeatParser(path).parse();
}

}  // namespace neomesh
