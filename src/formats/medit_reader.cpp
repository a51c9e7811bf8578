#include "formats/medit_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <string_view>

#include "core/error.hpp"
#include "formats/input_file.hpp"
#include "mesh/cell_order.hpp"

namespace neomesh {

namespace {

// Element sections of the file: keyword, vertices per element (its nodes: `corners` of them
// first), dimension, and neomesh's cell type (none for edges) and curved type. The P2 sections'
// other nodes are in VTK's order (curved_type.hpp), as Gmsh reads and writes them; Medit files
// agree on no order for QuadrilateralsQ2 and HexahedraQ2 (libMeshb leaves it to an Ordering
// section), which are refused.
struct ElementKind {
  std::string_view keyword;
  int vertices;
  int corners;
  int dim;
  std::optional<CellType> cell;
  std::optional<CurvedType> curved;
};
constexpr ElementKind kElementKinds[] = {
    {"Edges", 2, 2, 1, std::nullopt, std::nullopt},
    {"Triangles", 3, 3, 2, CellType::Triangle, std::nullopt},
    {"Quadrilaterals", 4, 4, 2, CellType::Quadrilateral, std::nullopt},
    {"Tetrahedra", 4, 4, 3, CellType::Tetrahedron, std::nullopt},
    {"Pyramids", 5, 5, 3, CellType::Pyramid, std::nullopt},
    {"Prisms", 6, 6, 3, CellType::Wedge, std::nullopt},
    {"Hexahedra", 8, 8, 3, CellType::Hexahedron, std::nullopt},
    {"EdgesP2", 3, 2, 1, std::nullopt, std::nullopt},
    {"TrianglesP2", 6, 3, 2, CellType::Triangle, CurvedType::Triangle6},
    {"TetrahedraP2", 10, 4, 3, CellType::Tetrahedron, CurvedType::Tetrahedron10}};
constexpr int kNumKinds = std::size(kElementKinds);

// Sections skipped: keyword and numbers per entry (-1: `Dimension` numbers; 0: the section has
// no count, one word follows).
constexpr std::pair<std::string_view, int> kSkipped[] = {{"Corners", 1},
                                                         {"Ridges", 1},
                                                         {"RequiredVertices", 1},
                                                         {"RequiredEdges", 1},
                                                         {"RequiredTriangles", 1},
                                                         {"RequiredQuadrilaterals", 1},
                                                         {"RequiredTetrahedra", 1},
                                                         {"RequiredHexahedra", 1},
                                                         {"Normals", -1},
                                                         {"Tangents", -1},
                                                         {"NormalAtVertices", 2},
                                                         {"TangentAtVertices", 2},
                                                         {"NormalAtTriangleVertices", 3},
                                                         {"NormalAtQuadrilateralVertices", 3},
                                                         {"TangentAtEdgeVertices", 3},
                                                         {"Identifier", 0},
                                                         {"Geometry", 0}};

bool is(std::string_view word, std::string_view keyword) {
  return std::equal(word.begin(), word.end(), keyword.begin(), keyword.end(), [](char a, char b) {
    return std::tolower(static_cast<unsigned char>(a)) ==
           std::tolower(static_cast<unsigned char>(b));
  });
}

// The elements of one kind: 1-based vertex numbers and a reference each.
struct Elements {
  std::vector<std::int64_t> vertices;
  std::vector<std::int64_t> refs;
};

struct Contents {
  int dimension = 0;
  std::vector<double> xyz;         // 3 per vertex
  std::vector<std::int64_t> refs;  // per vertex
  std::array<Elements, kNumKinds> elements;
  std::vector<int> kinds;  // of the element sections, in the order they first appear
};

class MeditParser {
 public:
  explicit MeditParser(const std::filesystem::path& path)
      : file_(path.string()), text_(read_input_file(path)) {
    pos_ = text_.data();
    end_ = pos_ + text_.size();
  }

  Contents parse() {
    section_ = "the header";
    const std::string_view first = word();
    if (!is(first, "MeshVersionFormatted"))
      invalid("it does not start with MeshVersionFormatted, but '{}'", shown_text(first, 24));
    const long long version = integer();
    if (version < 1 || version > 4) invalid("unknown MeshVersionFormatted {}", version);
    while (true) {
      const std::string_view keyword = word();
      section_ = shown_text(keyword, 32);
      if (keyword.empty() || is(keyword, "End")) break;
      read_section(keyword);
    }
    if (c_.dimension == 0) invalid("it has no Dimension");
    return std::move(c_);
  }

  template <typename... Args>
  [[noreturn]] void invalid(fmt::format_string<Args...> format, Args&&... args) const {
    fail("{}:{}: not a valid Medit file ({})", file_, 1 + std::count(text_.data(), where_, '\n'),
         fmt::format(format, std::forward<Args>(args)...));
  }

 private:
  static bool space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

  // The next word, skipping blanks and comments; empty at the end of the file.
  std::string_view word() {
    while (pos_ < end_) {
      if (space(*pos_)) {
        ++pos_;
      } else if (*pos_ == '#') {
        pos_ = std::find(pos_, end_, '\n');
      } else {
        break;
      }
    }
    where_ = pos_;
    const char* first = pos_;
    while (pos_ < end_ && !space(*pos_) && *pos_ != '#') ++pos_;
    return {first, static_cast<std::size_t>(pos_ - first)};
  }

  template <typename T>
  T number(const char* what) {
    const std::string_view w = word();
    if (w.empty()) invalid("truncated: the file ends inside {}", section_);
    T v{};
    const auto [next, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec != std::errc() || next != w.data() + w.size())
      invalid("expected {} in {}, found '{}'", what, section_, shown_text(w, 24));
    return v;
  }
  long long integer() { return number<long long>("an integer"); }

  // A section's count, for `per` numbers per entry, which the rest of the file must hold.
  long long count(long long per) {
    const long long n = integer();
    if (n < 0) invalid("{} announces {} entries", section_, n);
    if (per > 0 && n > (end_ - pos_) / (2 * per))  // a digit and a blank per number at least
      invalid("truncated: the file ends inside {}, which announces {} entries", section_, n);
    return n;
  }

  void read_section(std::string_view keyword) {
    if (is(keyword, "Dimension")) {
      c_.dimension = static_cast<int>(integer());
      if (c_.dimension != 2 && c_.dimension != 3)
        invalid("Dimension {}; neomesh reads 2 or 3", c_.dimension);
      return;
    }
    if (c_.dimension == 0) invalid("{} comes before Dimension", section_);
    if (is(keyword, "Vertices")) return read_vertices();
    for (int k = 0; k < kNumKinds; ++k)
      if (is(keyword, kElementKinds[k].keyword)) return read_elements(k);
    for (const auto& [name, per] : kSkipped)
      if (is(keyword, name)) {
        if (per == 0) {
          word();
          return;
        }
        const long long numbers = per < 0 ? c_.dimension : per;
        const long long n = count(numbers);
        for (long long i = 0; i < n * numbers; ++i) number<double>("a number");
        return;
      }
    if (keyword.size() > 2 && (keyword.ends_with("P2") || keyword.ends_with("Q2")))
      fail(
          "{}: has {}, whose node order Medit files do not agree on; of the second-order "
          "(curved) elements neomesh reads EdgesP2, TrianglesP2 and TetrahedraP2",
          file_, section_);
    invalid("unknown keyword '{}'", section_);
  }

  void read_vertices() {
    if (!c_.xyz.empty()) invalid("it has two Vertices sections");
    const int d = c_.dimension;
    const long long n = count(d + 1);
    c_.xyz.assign(3 * n, 0.0);
    c_.refs.assign(n, 0);
    for (long long v = 0; v < n; ++v) {
      for (int i = 0; i < d; ++i) {
        const double x = number<double>("a coordinate");
        if (!std::isfinite(x)) invalid("vertex {} has the coordinate {}", v + 1, x);
        c_.xyz[3 * v + i] = x;
      }
      c_.refs[v] = integer();
    }
  }

  void read_elements(int kind) {
    const int nv = kElementKinds[kind].vertices;
    Elements& e = c_.elements[kind];
    const long long n = count(nv + 1);
    if (std::find(c_.kinds.begin(), c_.kinds.end(), kind) == c_.kinds.end())
      c_.kinds.push_back(kind);
    for (long long i = 0; i < n; ++i) {
      for (int k = 0; k < nv; ++k) e.vertices.push_back(integer());
      e.refs.push_back(integer());
    }
  }

  std::string file_;
  InputText text_;
  const char* pos_ = nullptr;
  const char* end_ = nullptr;
  const char* where_ = nullptr;  // where the last word starts, for messages
  std::string section_;
  Contents c_;
};

// The dimension of the elements of the highest dimension, which are the cells.
int cell_dimension(const Contents& c, const std::string& file) {
  int dim = 0;
  for (int k = 0; k < kNumKinds; ++k)
    if (!c.elements[k].refs.empty()) dim = std::max(dim, kElementKinds[k].dim);
  if (dim < 2)
    fail(
        "{}: has no 2D or 3D cells (only {}D elements); neomesh needs triangles, "
        "quadrilaterals, tetrahedra, hexahedra, prisms or pyramids",
        file, dim);
  return dim;
}

// A reference as a group tag: > 0, or 0 for none.
int group_tag(std::int64_t ref, const std::string& file, std::string_view section) {
  if (ref > std::numeric_limits<int>::max())
    fail("{}: the reference {} of {} is beyond the range of int", file, ref, section);
  return ref > 0 ? static_cast<int>(ref) : 0;
}

}  // namespace

InputMesh read_medit(const std::filesystem::path& path) {
  const std::string file = path.string();
  const Contents c = MeditParser(path).parse();
  InputMesh mesh;
  mesh.dim = cell_dimension(c, file);
  const auto kept = [&](int k, std::size_t i) {
    return kElementKinds[k].dim == mesh.dim ||
           (kElementKinds[k].dim == mesh.dim - 1 && c.elements[k].refs[i] > 0);
  };
  // Vertices: the corners of cells and kept facets; nodes: the other nodes of curved cells.
  const std::int64_t nv = static_cast<std::int64_t>(c.xyz.size() / 3);
  std::vector<PetscInt> vertex(nv, -1), node(nv, -1);
  const ElementKind* first = nullptr;  // a kind of cells
  for (int k = 0; k < kNumKinds; ++k) {
    const Elements& e = c.elements[k];
    const ElementKind& kind = kElementKinds[k];
    if (kind.dim == mesh.dim && !e.refs.empty()) {
      if (first && first->curved.has_value() != kind.curved.has_value())
        fail(
            "{}: mixes first-order and second-order cells ({} and {}); neomesh reads meshes of "
            "one order",
            file, first->keyword, kind.keyword);
      first = &kind;
    }
    for (std::size_t i = 0; i < e.refs.size(); ++i) {
      if (!kept(k, i)) continue;
      for (int j = 0; j < kind.vertices; ++j) {
        const std::int64_t v = e.vertices[i * kind.vertices + j];
        if (v < 1 || v > nv)
          fail("{}: {} {} refers to vertex {}, which is out of range (1..{})", file, kind.keyword,
               i + 1, v, nv);
        // (a facet's other nodes are the cells')
        if (j < kind.corners)
          vertex[v - 1] = 0;
        else if (kind.dim == mesh.dim)
          node[v - 1] = 0;
      }
    }
  }
  number_used_vertices(vertex, c.xyz, file, mesh);
  number_high_order_nodes(node, vertex, c.xyz, file, mesh);

  std::set<int> cell_tags, facet_tags;
  for (int k : c.kinds) {
    const ElementKind& kind = kElementKinds[k];
    const Elements& e = c.elements[k];
    for (std::size_t i = 0; i < e.refs.size(); ++i) {
      if (!kept(k, i)) continue;
      const std::int64_t* medit = e.vertices.data() + i * kind.vertices;
      const int tag = group_tag(e.refs[i], file, kind.keyword);
      PetscInt v[8];
      for (int j = 0; j < kind.vertices; ++j)
        if (std::find(medit, medit + j, medit[j]) != medit + j)
          fail("{}: {} {} has a repeated vertex", file, kind.keyword, i + 1);
      for (int j = 0; j < kind.corners; ++j)
        v[kind.dim == mesh.dim ? gmsh_from_canonical(*kind.cell)[j] : j] = vertex[medit[j] - 1];
      if (kind.dim == mesh.dim) {
        mesh.add_cell(*kind.cell, v, tag);
        if (tag > 0) cell_tags.insert(tag);
        if (kind.curved) {
          PetscInt gmsh[kMaxCurvedNodes];
          for (int j = kind.corners; j < kind.vertices; ++j)
            gmsh[facts(*kind.curved).vtk_order[j]] = node[medit[j] - 1];
          mesh.high_order.add(*kind.curved, gmsh + kind.corners);
        }
      } else {
        mesh.facets.add(v, kind.corners, tag);
        facet_tags.insert(tag);
      }
    }
  }
  check_high_order_nodes(mesh, file);
  for (int tag : facet_tags) mesh.groups.push_back({mesh.dim - 1, tag, ""});
  for (int tag : cell_tags) mesh.groups.push_back({mesh.dim, tag, ""});

  // Vertex references, unless all are 0: the point data "medit:ref" (as meshio names them).
  DataArray refs{"medit:ref", 1, ValueType::Int32, {}};
  bool any = false;
  for (std::int64_t v = 0; v < nv; ++v) {
    if (vertex[v] < 0) continue;
    const std::int64_t r = c.refs[v];
    any = any || r != 0;
    if (r < std::numeric_limits<std::int32_t>::min() ||
        r > std::numeric_limits<std::int32_t>::max())
      refs.type = ValueType::Int64;
    refs.values.push_back(static_cast<double>(r));
  }
  // (A curved mesh's would need its nodes' references too: they are not carried.)
  if (any && !mesh.curved()) mesh.point_data.push_back(std::move(refs));
  return mesh;
}

}  // namespace neomesh
