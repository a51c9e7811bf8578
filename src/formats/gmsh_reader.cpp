#include "formats/gmsh_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>

#include "core/error.hpp"
#include "formats/input_file.hpp"
#include "mesh/cell_order.hpp"
#include "mesh/curved_type.hpp"

namespace neomesh {

namespace {

// Element polytopes in the order PETSc's reader sorted elements by (stably): cells are
// numbered in this order, so their numbers stay those of earlier versions.
enum Polytope { kTet, kHex, kPrism, kPyramid, kTriangle, kQuad, kLine, kPoint, kNumPolytopes };

constexpr int kPolytopeDim[kNumPolytopes] = {3, 3, 3, 3, 2, 2, 1, 0};
constexpr int kPolytopeCorners[kNumPolytopes] = {4, 8, 6, 5, 3, 4, 2, 1};

struct ElementType {
  Polytope polytope;
  int order;
  int nodes;
};

// The Gmsh element types neomesh can read or name in an error (gmsh.info, "MSH file format").
struct KnownType {
  int gmsh;
  ElementType type;
};
constexpr KnownType kKnownTypes[] = {
    {15, {kPoint, 1, 1}},    {1, {kLine, 1, 2}},     {8, {kLine, 2, 3}},
    {2, {kTriangle, 1, 3}},  {9, {kTriangle, 2, 6}}, {21, {kTriangle, 3, 10}},
    {3, {kQuad, 1, 4}},      {10, {kQuad, 2, 9}},    {16, {kQuad, 2, 8}},
    {4, {kTet, 1, 4}},       {11, {kTet, 2, 10}},    {5, {kHex, 1, 8}},
    {12, {kHex, 2, 27}},     {17, {kHex, 2, 20}},    {6, {kPrism, 1, 6}},
    {13, {kPrism, 2, 18}},   {18, {kPrism, 2, 15}},  {7, {kPyramid, 1, 5}},
    {14, {kPyramid, 2, 14}}, {19, {kPyramid, 2, 13}}};

bool element_type(long long gmsh_type, ElementType& t) {
  for (const KnownType& k : kKnownTypes)
    if (k.gmsh == gmsh_type) {
      t = k.type;
      return true;
    }
  return false;
}

constexpr int kNoTag = std::numeric_limits<int>::min();

// Node and element tags above this are an error: vertex numbers must fit PetscInt (and tags of
// 2^32 and more were once silently wrapped).
constexpr long long kMaxTag = std::min<long long>(PETSC_MAX_INT, (1LL << 32) - 1);

// The elements of one polytope in file order: corner nodes (indices into $Nodes), the other
// nodes of second-order elements and the physical tag (the first one; kNoTag for none).
struct Elements {
  std::vector<PetscInt> corners;
  std::vector<PetscInt> others;  // each element's nodes after its corners, in Gmsh order
  std::vector<std::size_t> others_offsets = {0};
  std::vector<int> tags;
  std::vector<long long> numbers;  // element tags, for messages (InputMesh::element_tag)
  int min_order = 3, order = 1;
};

// A $NodeData or $ElementData section: its name, and per node or element its tag and
// `components` values.
struct TaggedData {
  std::string name;
  int components = 1;
  std::vector<long long> tags;
  std::vector<double> values;
};

struct Contents {
  std::vector<TaggedData> node_data, element_data;   // the last section of each name
  int version = 0;                                   // 22 or 41
  std::map<std::pair<int, int>, std::string> names;  // $PhysicalNames by (dim, tag)
  std::map<std::pair<int, int>, int> entity_tag;     // 4.1: (dim, entity) → physical tag
  std::vector<double> xyz;                           // per node (file order)
  std::vector<long long> node_tags;                  // per node
  std::array<Elements, kNumPolytopes> elements;
};

// The whole file in memory, read section by section. ASCII numbers are parsed by hand (the
// reader's hot loop); binary blocks are copied.
class GmshParser {
 public:
  explicit GmshParser(const std::filesystem::path& path)
      : file_(path.string()), text_(read_input_file(path)) {
    pos_ = text_.data();
    end_ = pos_ + text_.size();
  }

  Contents parse() {
    if (word() != "$MeshFormat") invalid("it does not start with $MeshFormat");
    read_format();
    for (std::string_view section = word(); !section.empty(); section = word()) {
      section_ = section;
      const bool known = section == "$PhysicalNames" || section == "$Nodes" ||
                         section == "$Elements" || section == "$MeshFormat" ||
                         (section == "$Entities" && c_.version == 41);
      // A second $Nodes (or $Elements...) would renumber what the first one's users refer to.
      if (known && !seen_.insert(std::string(section)).second)
        invalid("it has two {} sections", section);
      // Binary sections of 4.1 start right after the newline that ends their name.
      if (binary_ && c_.version == 41 && section != "$PhysicalNames" && section != "$MeshFormat")
        skip_newline();
      if (section == "$PhysicalNames")
        read_names();
      else if (section == "$Entities" && c_.version == 41)
        read_entities();
      else if (section == "$Nodes")
        read_nodes();
      else if (section == "$Elements")
        read_elements();
      else if (section == "$NodeData" || section == "$ElementData")
        read_data(section == "$NodeData" ? c_.node_data : c_.element_data);
      else
        skip_section(section);
    }
    if (!have_nodes_) invalid("it has no $Nodes section");
    return std::move(c_);
  }

 private:
  template <typename... Args>
  [[noreturn]] void invalid(fmt::format_string<Args...> format, Args&&... args) {
    fail("{}: not a valid Gmsh mesh file ({})", file_,
         fmt::format(format, std::forward<Args>(args)...));
  }
  [[noreturn]] void truncated() { invalid("truncated: the file ends inside {}", shown(section_)); }

  // A word of the file for a message: short, printable.
  static std::string shown(std::string_view word) { return shown_text(word, 24); }

  void skip_space() {
    while (pos_ < end_ && (*pos_ == ' ' || *pos_ == '\n' || *pos_ == '\r' || *pos_ == '\t')) ++pos_;
  }

  // The next whitespace-separated word; empty at the end of the file.
  std::string_view word() {
    skip_space();
    const char* first = pos_;
    while (pos_ < end_ && !std::isspace(static_cast<unsigned char>(*pos_))) ++pos_;
    return {first, static_cast<std::size_t>(pos_ - first)};
  }

  // One byte that must be there (the newline before a binary block).
  void skip_newline() {
    if (pos_ == end_) truncated();
    ++pos_;
  }

  // A decimal integer word; out-of-range values are an error, never wrapped.
  long long integer() {
    skip_space();
    if (pos_ == end_) truncated();
    const char* first = pos_;
    if (*pos_ == '+') ++pos_;  // from_chars takes '-' but not '+'
    long long value = 0;
    const auto [next, ec] = std::from_chars(pos_, end_, value);
    if (ec == std::errc::result_out_of_range) {
      pos_ = first;
      invalid("the number '{}' in {} is out of range", shown(word()), shown(section_));
    }
    if (ec != std::errc() || (next < end_ && !std::isspace(static_cast<unsigned char>(*next))))
      not_a_number(first, "an integer");
    pos_ = next;
    return value;
  }

  // An integer that must lie in [lo, hi] (`what` names it in the message).
  long long integer_in(long long value, long long lo, long long hi, const char* what) {
    if (value < lo || value > hi)
      invalid("{} {} in {} is out of range ({}..{})", what, value, shown(section_), lo, hi);
    return value;
  }

  double real() {
    skip_space();
    if (pos_ == end_) truncated();
    double value = 0;
    const auto [next, ec] = std::from_chars(pos_, end_, value);
    if (ec == std::errc::result_out_of_range)  // subnormal or huge: strtod rounds it
      value = std::strtod(std::string(pos_, next).c_str(), nullptr);
    else if (ec != std::errc() || (next < end_ && !std::isspace(static_cast<unsigned char>(*next))))
      not_a_number(pos_, "a number");
    pos_ = next;
    return value;
  }

  [[noreturn]] void not_a_number(const char* at, const char* what) {
    pos_ = at;
    invalid("expected {} in {}, found '{}'", what, shown(section_), shown(word()));
  }

  // `n` values of type T from a binary block.
  template <typename T>
  void binary(T* out, std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (static_cast<std::size_t>(end_ - pos_) < bytes) truncated();
    std::memcpy(out, pos_, bytes);
    pos_ += bytes;
  }
  template <typename T>
  T binary() {
    T value;
    binary(&value, 1);
    return value;
  }
  // A size_t of the file (4.1 binary: data-size bytes); beyond long long is an error.
  long long size() {
    if (!binary_) return integer();
    if (size_bytes_ == 4) return binary<std::uint32_t>();
    const std::uint64_t value = binary<std::uint64_t>();
    if (value > static_cast<std::uint64_t>(std::numeric_limits<long long>::max()))
      invalid("the number {} in {} is out of range", value, shown(section_));
    return static_cast<long long>(value);
  }
  // An int of the file (entity and physical tags, element types, counts of tags).
  int small_int() {
    if (binary_) return binary<int>();
    return static_cast<int>(integer_in(integer(), std::numeric_limits<int>::min(),
                                       std::numeric_limits<int>::max(), "the number"));
  }
  // A node or element tag: in 0..kMaxTag.
  long long tag(long long value, const char* what) { return integer_in(value, 0, kMaxTag, what); }
  // A number of items to allocate for, each taking at least `bytes` bytes of the file: a count
  // the rest of the file cannot hold is an error (and never a huge allocation).
  long long count(long long n, long long bytes = 1) {
    if (n < 0) invalid("{} announces {} items", shown(section_), n);
    if (n > (end_ - pos_) / bytes)
      invalid("truncated: the file ends inside {}, which announces {} items", shown(section_), n);
    return n;
  }
  double real_value() { return binary_ ? binary<double>() : real(); }

  void expect_end(std::string_view section) {
    const std::string end = "$End" + std::string(section.substr(1));
    const std::string_view found = word();
    if (found.empty()) truncated();
    if (found != end) invalid("expected {}, found '{}'", end, shown(found));
  }

  void skip_section(std::string_view section) {
    if (!section.starts_with('$'))
      invalid("expected a section such as $Nodes, found '{}'", shown(section));
    const std::string end = "$End" + std::string(section.substr(1));
    const char* at = std::search(pos_, end_, end.begin(), end.end());
    if (at == end_) truncated();
    pos_ = at + end.size();
  }

  void read_format() {
    section_ = "$MeshFormat";
    seen_.insert("$MeshFormat");
    const std::string_view version = word();
    const long long file_type = integer();
    size_bytes_ = static_cast<int>(integer_in(integer(), 0, 64, "the data size"));
    if (version == "2.2")
      c_.version = 22;
    else if (version == "4.1")
      c_.version = 41;
    else
      fail("{}: is a Gmsh {} file; neomesh reads Gmsh formats 2.2 and 4.1", file_, shown(version));
    binary_ = file_type == 1;
    if (binary_) {
      if (size_bytes_ != 4 && size_bytes_ != 8) invalid("data size {}", size_bytes_);
      skip_newline();  // the newline before the binary one
      if (binary<int>() != 1) invalid("binary data of another byte order");
    }
    expect_end("$MeshFormat");
  }

  // Names between the first and the last quote of each line.
  void read_names() {
    const long long n = integer();
    for (long long i = 0; i < n; ++i) {
      const int dim = small_int(), tag = small_int();
      const char* eol = std::find(pos_, end_, '\n');
      const std::string_view line(pos_, static_cast<std::size_t>(eol - pos_));
      const auto open = line.find('"'), close = line.rfind('"');
      if (open != std::string_view::npos && close > open)
        c_.names[{dim, tag}] = std::string(line.substr(open + 1, close - open - 1));
      pos_ = eol;
    }
    expect_end("$PhysicalNames");
  }

  // $NodeData/$ElementData: string tags (the first is the name), real tags (the time), integer
  // tags (time step, components, count), then per node or element its tag and values (binary
  // files: an int and `components` doubles, after the newline that ends the integer tags). A
  // later section of the same name (a later time step) replaces an earlier one.
  void read_data(std::vector<TaggedData>& all) {
    TaggedData d;
    const long long strings = count(integer(), 2);
    for (long long i = 0; i < strings; ++i) {
      skip_space();
      const char* eol = std::find(pos_, end_, '\n');
      std::string_view line(pos_, static_cast<std::size_t>(eol - pos_));
      const auto open = line.find('"'), close = line.rfind('"');
      if (open != std::string_view::npos && close > open)
        line = line.substr(open + 1, close - open - 1);
      if (i == 0) d.name = std::string(line);
      pos_ = eol;
    }
    const long long reals = count(integer(), 2);
    for (long long i = 0; i < reals; ++i) real();
    const long long integers = count(integer(), 2);
    if (integers < 3) invalid("{} has {} integer tags (3 or more)", shown(section_), integers);
    long long ints[3];
    for (long long i = 0; i < integers; ++i) {
      const long long v = integer();
      if (i < 3) ints[i] = v;
    }
    d.components = static_cast<int>(integer_in(ints[1], 1, 1024, "the number of components"));
    // (an entry takes an int and its doubles, or in ASCII at least a digit and a space each)
    const long long n = count(ints[2], binary_ ? 4 + 8LL * d.components : 2LL * (1 + d.components));
    d.tags.reserve(n);
    d.values.reserve(n * d.components);
    if (binary_) skip_newline();
    for (long long k = 0; k < n; ++k) {
      d.tags.push_back(tag(binary_ ? binary<int>() : integer(), "tag"));
      for (int j = 0; j < d.components; ++j) d.values.push_back(real_value());
    }
    expect_end(section_);
    if (d.name.empty()) return;
    std::erase_if(all, [&](const TaggedData& a) { return a.name == d.name; });
    all.push_back(std::move(d));
  }

  void read_entities() {
    long long counts[4];
    for (auto& n : counts) n = size();
    for (int dim = 0; dim < 4; ++dim)
      for (long long e = 0; e < counts[dim]; ++e) {
        const int tag = small_int();
        for (int i = 0; i < (dim == 0 ? 3 : 6); ++i) real_value();
        const long long physicals = size();
        for (long long i = 0; i < physicals; ++i) {
          const int physical = small_int();
          if (i == 0) c_.entity_tag[{dim, tag}] = physical;
        }
        if (dim == 0) continue;
        for (long long i = 0, n = size(); i < n; ++i) small_int();  // bounding entities
      }
    expect_end("$Entities");
  }

  void read_nodes() {
    if (c_.version == 22) {
      // ASCII in binary files too; a node takes at least "1 0 0 0\n" or 4 + 3 * 8 bytes.
      const long long n = count(integer(), binary_ ? 28 : 8);
      c_.node_tags.resize(n);
      c_.xyz.resize(3 * n);
      if (binary_) skip_newline();
      for (long long i = 0; i < n; ++i) {
        c_.node_tags[i] = tag(binary_ ? binary<int>() : integer(), "node tag");
        for (int d = 0; d < 3; ++d) c_.xyz[3 * i + d] = real_value();
      }
    } else {
      const long long blocks = size(), total = count(size(), binary_ ? size_bytes_ + 24 : 8);
      size();  // smallest and largest node tag
      size();
      c_.node_tags.reserve(total);
      c_.xyz.reserve(3 * total);
      for (long long b = 0; b < blocks; ++b) {
        small_int();  // entity dimension and tag
        small_int();
        if (small_int() != 0) invalid("parametric nodes are not supported");
        const long long n = size();
        if (n > total - static_cast<long long>(c_.node_tags.size()))
          invalid("$Nodes announces {} nodes and lists more", total);
        for (long long i = 0; i < n; ++i) c_.node_tags.push_back(tag(size(), "node tag"));
        for (long long i = 0; i < 3 * n; ++i) c_.xyz.push_back(real_value());
      }
      if (static_cast<long long>(c_.node_tags.size()) != total)
        invalid("$Nodes announces {} nodes and lists {}", total, c_.node_tags.size());
    }
    expect_end("$Nodes");
    index_nodes();
    have_nodes_ = true;
  }

  // Node tags may be sparse: index them through a table over their range.
  void index_nodes() {
    if (c_.node_tags.empty()) return;
    const auto [lo, hi] = std::minmax_element(c_.node_tags.begin(), c_.node_tags.end());
    first_tag_ = *lo;
    if (*hi - *lo > 64 * static_cast<long long>(c_.node_tags.size()) + (1 << 20))
      invalid("node tags range from {} to {} for {} nodes", *lo, *hi, c_.node_tags.size());
    node_index_.assign(*hi - *lo + 1, -1);
    for (std::size_t n = 0; n < c_.node_tags.size(); ++n) {
      PetscInt& index = node_index_[c_.node_tags[n] - first_tag_];
      if (index >= 0) invalid("node tag {} appears twice", c_.node_tags[n]);
      index = static_cast<PetscInt>(n);
    }
  }

  PetscInt node(long long tag) {
    if (tag < 0 || tag > kMaxTag)
      invalid("an element refers to node {}, which is out of range (0..{})", tag, kMaxTag);
    const long long i = tag - first_tag_;
    if (i < 0 || i >= static_cast<long long>(node_index_.size()) || node_index_[i] < 0)
      invalid("an element refers to node {}, which $Nodes does not list", tag);
    return node_index_[i];
  }

  ElementType type_of(long long gmsh_type) {
    ElementType t;
    if (!element_type(gmsh_type, t))
      fail(
          "{}: has elements of Gmsh type {}, which neomesh does not read (it reads points, "
          "lines, triangles, quadrilaterals, tetrahedra, hexahedra, wedges and pyramids)",
          file_, gmsh_type);
    return t;
  }

  // One element's nodes (after its number and tags).
  void add_element(const ElementType& t, int tag, const long long* nodes, long long number) {
    Elements& e = c_.elements[t.polytope];
    for (int i = 0; i < kPolytopeCorners[t.polytope]; ++i) e.corners.push_back(node(nodes[i]));
    for (int i = kPolytopeCorners[t.polytope]; i < t.nodes; ++i) e.others.push_back(node(nodes[i]));
    e.others_offsets.push_back(e.others.size());
    e.min_order = std::min(e.min_order, t.order);
    e.tags.push_back(tag);
    e.numbers.push_back(number);
    e.order = std::max(e.order, t.order);
  }

  void read_elements() {
    if (!have_nodes_) invalid("$Elements comes before $Nodes");
    long long nodes[32];
    if (c_.version == 22) {
      const long long total = integer();
      if (binary_) skip_newline();
      for (long long e = 0; e < total;) {
        // ASCII: number, type, tags, nodes per line; binary: blocks of elements of one type.
        long long number = binary_ ? 0 : tag(integer(), "element tag");
        const ElementType t = type_of(small_int());
        const int block_size = binary_ ? binary<int>() : 1;
        if (block_size < 1 || block_size > total - e)
          invalid("a block of {} elements where {} are left", block_size, total - e);
        const int num_tags = small_int();
        for (int k = 0; k < block_size; ++k, ++e) {
          if (binary_) number = tag(binary<int>(), "element tag");
          int physical = kNoTag;
          for (int i = 0; i < num_tags; ++i) {
            const int value = small_int();
            if (i == 0) physical = value;
          }
          for (int i = 0; i < t.nodes; ++i) nodes[i] = binary_ ? binary<int>() : integer();
          add_element(t, physical, nodes, number);
        }
      }
    } else {
      const long long blocks = size();
      size();  // number of elements, smallest and largest element tag
      size();
      size();
      for (long long b = 0; b < blocks; ++b) {
        const int dim = small_int(), entity = small_int();
        const ElementType t = type_of(small_int());
        const auto it = c_.entity_tag.find({dim, entity});
        const int physical = it == c_.entity_tag.end() ? kNoTag : it->second;
        for (long long k = 0, n = size(); k < n; ++k) {
          const long long number = tag(size(), "element tag");
          for (int i = 0; i < t.nodes; ++i) nodes[i] = size();
          add_element(t, physical, nodes, number);
        }
      }
    }
    expect_end("$Elements");
  }

  std::string file_;
  InputText text_;
  const char* pos_ = nullptr;
  const char* end_ = nullptr;
  std::string_view section_ = "$MeshFormat";
  std::set<std::string> seen_;  // sections read (each at most once)
  bool binary_ = false;
  bool have_nodes_ = false;
  int size_bytes_ = 8;
  long long first_tag_ = 0;
  std::vector<PetscInt> node_index_;
  Contents c_;
};

constexpr const char* kPolytopeName[kNumPolytopes] = {
    "tetrahedron", "hexahedron",    "triangular_prism", "pyramid",
    "triangle",    "quadrilateral", "segment",          "point"};

// neomesh's cell type of each polytope (none for lines and points).
constexpr std::optional<CellType> kCellType[kNumPolytopes] = {
    CellType::Tetrahedron, CellType::Hexahedron,    CellType::Wedge, CellType::Pyramid,
    CellType::Triangle,    CellType::Quadrilateral, std::nullopt,    std::nullopt};

// Vertices are the nodes some element has as a corner, numbered in the order of $Nodes.
std::vector<PetscInt> number_vertices(const Contents& c, const std::string& file, InputMesh& mesh) {
  std::vector<PetscInt> vertex(c.node_tags.size(), -1);
  for (const Elements& e : c.elements)
    for (PetscInt n : e.corners) vertex[n] = 0;
  number_used_vertices(vertex, c.xyz, file, mesh);
  return vertex;
}

// The other nodes of the cells (second-order elements of the mesh's dimension), numbered in the
// order of $Nodes into mesh.high_order.
std::vector<PetscInt> number_high_order_nodes(const Contents& c, const std::string& file,
                                              const std::vector<PetscInt>& vertex,
                                              InputMesh& mesh) {
  std::vector<PetscInt> node(c.node_tags.size(), -1);
  for (int p = 0; p < kNumPolytopes; ++p)
    if (kPolytopeDim[p] == mesh.dim)
      for (PetscInt n : c.elements[p].others) node[n] = 0;
  for (std::size_t n = 0; n < node.size(); ++n) {
    if (node[n] < 0) continue;
    if (vertex[n] >= 0)
      fail("{}: node {} is a corner of one element and a mid-edge, face or centre node of another",
           file, c.node_tags[n]);
    node[n] = mesh.high_order.num_nodes();
    mesh.high_order.xyz.insert(mesh.high_order.xyz.end(), c.xyz.begin() + 3 * n,
                               c.xyz.begin() + 3 * n + 3);
  }
  return node;
}

void add_cells(const Contents& c, const std::string& file, const std::vector<PetscInt>& vertex,
               const std::vector<PetscInt>& node, InputMesh& mesh, std::set<int>& cell_tags) {
  PetscInt index = 0;
  for (int p = 0; p < kNumPolytopes; ++p) {
    const Elements& e = c.elements[p];
    if (kPolytopeDim[p] != mesh.dim || e.tags.empty()) continue;
    if (!kCellType[p])
      fail(
          "{}: cell {} (0-based) is a {}; neomesh supports triangles, quadrilaterals, "
          "tetrahedra, hexahedra, wedges and pyramids",
          file, index, kPolytopeName[p]);
    const CellType type = *kCellType[p];
    const int n = kPolytopeCorners[p];
    for (std::size_t k = 0; k < e.tags.size(); ++k, ++index) {
      const PetscInt* gmsh = e.corners.data() + k * n;
      PetscInt canonical[8];
      for (int i = 0; i < n; ++i) {
        canonical[gmsh_from_canonical(type)[i]] = vertex[gmsh[i]];
        if (std::find(gmsh, gmsh + i, gmsh[i]) != gmsh + i)
          fail("{}: cell {} (0-based) has a repeated vertex", file, index);
      }
      const int tag = e.tags[k] > 0 ? e.tags[k] : 0;
      if (tag > 0) cell_tags.insert(tag);
      mesh.add_cell(type, canonical, tag);
      if (e.order > 1) {
        PetscInt others[kMaxCurvedNodes];
        const std::size_t first = e.others_offsets[k], count = e.others_offsets[k + 1] - first;
        for (std::size_t i = 0; i < count; ++i) others[i] = node[e.others[first + i]];
        mesh.high_order.add(*curved_type(type, n + static_cast<int>(count)), others);
      }
      mesh.element_tag.push_back(e.numbers[k]);
    }
  }
}

// Facet elements with a physical tag; points and lower-dimensional elements are not kept.
void add_facets(const Contents& c, const std::vector<PetscInt>& vertex, InputMesh& mesh,
                std::set<int>& facet_tags) {
  for (int p = 0; p < kNumPolytopes; ++p) {
    const Elements& e = c.elements[p];
    if (kPolytopeDim[p] != mesh.dim - 1) continue;
    const int n = kPolytopeCorners[p];
    for (std::size_t k = 0; k < e.tags.size(); ++k) {
      if (e.tags[k] == kNoTag) continue;
      PetscInt v[4];
      for (int i = 0; i < n; ++i) v[i] = vertex[e.corners[k * n + i]];
      mesh.facets.add(v, n, e.tags[k]);
      facet_tags.insert(e.tags[k]);
    }
  }
}

// The dimension of the highest-dimensional elements, which are the cells; throws Error unless
// they are 2D or 3D and first-order.
int cell_dimension(const Contents& c, const std::string& file) {
  int dim = 0, order = 1;
  for (int p = 0; p < kNumPolytopes; ++p)
    if (!c.elements[p].tags.empty()) dim = std::max(dim, kPolytopeDim[p]);
  if (dim < 2)
    fail(
        "{}: has no 2D or 3D cells (only {}D elements); neomesh needs triangles, "
        "quadrilaterals, tetrahedra, hexahedra, wedges or pyramids",
        file, dim);
  int min_order = 3;
  for (int p = 0; p < kNumPolytopes; ++p) {
    const Elements& e = c.elements[p];
    if (kPolytopeDim[p] != dim || e.tags.empty()) continue;
    order = std::max(order, e.order);
    min_order = std::min(min_order, e.min_order);
    if (e.order == 1) continue;
    // Second-order elements: those of curved_type.hpp only, all of the same order.
    for (std::size_t k = 0; k < e.tags.size(); ++k) {
      const int nodes =
          kPolytopeCorners[p] + static_cast<int>(e.others_offsets[k + 1] - e.others_offsets[k]);
      if (e.others_offsets[k + 1] == e.others_offsets[k]) continue;
      if (!kCellType[p] || !curved_type(*kCellType[p], nodes))
        fail(
            "{}: has a {} of {} nodes (element {}); of the curved cells neomesh reads triangles "
            "(6 nodes), quadrilaterals (8, 9), tetrahedra (10), hexahedra (20, 27) and wedges "
            "(15, 18), not yet curved pyramids or cells of third order",
            file, kPolytopeName[p], nodes, e.numbers[k]);
    }
  }
  if (order > 1 && min_order == 1)
    fail(
        "{}: mixes first-order and second-order cells; neomesh reads meshes of one order "
        "(Gmsh: Mesh.ElementOrder)",
        file);
  return dim;
}

}  // namespace

// The data of $NodeData/$ElementData per entity of `numbers` (tags, in order); entities without
// a value get NaN, values of other tags are dropped.
std::vector<DataArray> data_by_tag(const std::vector<TaggedData>& data,
                                   const std::vector<long long>& numbers) {
  std::vector<DataArray> out;
  if (data.empty()) return out;
  std::unordered_map<long long, std::size_t> index;
  for (std::size_t i = numbers.size(); i-- > 0;) index[numbers[i]] = i;
  for (const TaggedData& d : data) {
    const auto k = static_cast<std::size_t>(d.components);
    DataArray a{d.name, d.components, ValueType::Float64,
                std::vector<double>(numbers.size() * k, std::nan(""))};
    for (std::size_t t = 0; t < d.tags.size(); ++t)
      if (const auto it = index.find(d.tags[t]); it != index.end())
        std::copy_n(d.values.begin() + t * k, k, a.values.begin() + it->second * k);
    out.push_back(std::move(a));
  }
  return out;
}

InputMesh read_gmsh(const std::filesystem::path& path) {
  const std::string file = path.string();
  const Contents c = GmshParser(path).parse();
  InputMesh mesh;
  mesh.dim = cell_dimension(c, file);
  const std::vector<PetscInt> vertex = number_vertices(c, file, mesh);
  const std::vector<PetscInt> node = number_high_order_nodes(c, file, vertex, mesh);
  std::set<int> cell_tags, facet_tags;
  add_cells(c, file, vertex, node, mesh, cell_tags);
  check_high_order_nodes(mesh, file);
  add_facets(c, vertex, mesh, facet_tags);

  auto add_groups = [&](int gdim, const std::set<int>& tags) {
    for (int tag : tags) {
      auto it = c.names.find({gdim, tag});
      mesh.groups.push_back({gdim, tag, it == c.names.end() ? "" : it->second});
    }
  };
  add_groups(mesh.dim - 1, facet_tags);
  add_groups(mesh.dim, cell_tags);

  std::vector<long long> node_tags;
  for (std::size_t n = 0; n < vertex.size(); ++n)
    if (vertex[n] >= 0) node_tags.push_back(c.node_tags[n]);
  // (A curved mesh's node data would need its high-order nodes' values too: it is not carried.)
  if (!mesh.curved()) mesh.point_data = data_by_tag(c.node_data, node_tags);
  mesh.cell_data = data_by_tag(c.element_data, {mesh.element_tag.begin(), mesh.element_tag.end()});
  return mesh;
}

}  // namespace neomesh
