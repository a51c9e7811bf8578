#include "formats/vtk_reader.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>

#include "core/error.hpp"
#include "formats/input_file.hpp"
#include "formats/vtk_cells.hpp"
#include "mesh/cell_order.hpp"

namespace neomesh {

namespace {

// The data types of VTK arrays, with their size in binary files ("bit": 1/8 byte; vtkIdType is
// written as 4-byte int in legacy files).
enum class Kind { Bit, Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64 };
struct DataType {
  std::string_view name;
  Kind kind;
  int bytes;
};
constexpr DataType kDataTypes[] = {{"bit", Kind::Bit, 1},
                                   {"char", Kind::Int8, 1},
                                   {"unsigned_char", Kind::UInt8, 1},
                                   {"short", Kind::Int16, 2},
                                   {"unsigned_short", Kind::UInt16, 2},
                                   {"int", Kind::Int32, 4},
                                   {"unsigned_int", Kind::UInt32, 4},
                                   {"long", Kind::Int64, 8},
                                   {"unsigned_long", Kind::UInt64, 8},
                                   {"float", Kind::Float32, 4},
                                   {"double", Kind::Float64, 8},
                                   {"vtkidtype", Kind::Int32, 4},
                                   {"vtktypeint8", Kind::Int8, 1},
                                   {"vtktypeuint8", Kind::UInt8, 1},
                                   {"vtktypeint16", Kind::Int16, 2},
                                   {"vtktypeuint16", Kind::UInt16, 2},
                                   {"vtktypeint32", Kind::Int32, 4},
                                   {"vtktypeuint32", Kind::UInt32, 4},
                                   {"vtktypeint64", Kind::Int64, 8},
                                   {"vtktypeuint64", Kind::UInt64, 8},
                                   {"vtktypefloat32", Kind::Float32, 4},
                                   {"vtktypefloat64", Kind::Float64, 8}};
constexpr DataType kInt32 = {"int", Kind::Int32, 4};
constexpr DataType kUInt8 = {"unsigned_char", Kind::UInt8, 1};
constexpr DataType kFloat = {"float", Kind::Float32, 4};

// VTK's keywords are case-insensitive.
bool is(std::string_view word, std::string_view keyword) {
  return std::equal(word.begin(), word.end(), keyword.begin(), keyword.end(), [](char a, char b) {
    return std::tolower(static_cast<unsigned char>(a)) ==
           std::tolower(static_cast<unsigned char>(b));
  });
}

class VtkParser {
 public:
  explicit VtkParser(const std::filesystem::path& path)
      : file_(path.string()), text_(read_input_file(path)) {
    pos_ = text_.data();
    end_ = pos_ + text_.size();
  }

  VtkCells parse() {
    read_preamble();
    while (true) {
      skip_space();
      if (pos_ == end_) break;
      read_section(header());
    }
    if (!have_points_) invalid("it has no POINTS");
    if (!polydata_ && !have_types_ && c_.offsets.size() > 1)
      invalid("it has CELLS but no CELL_TYPES");
    if (!c_.tags.empty() && c_.tags.size() != c_.types.size())
      invalid("it gives physical groups of {} cells, but has {} cells", c_.tags.size(),
              c_.types.size());
    return std::move(c_);
  }

 private:
  template <typename... Args>
  [[noreturn]] void invalid(fmt::format_string<Args...> format, Args&&... args) {
    const std::string why = fmt::format(format, std::forward<Args>(args)...);
    // Lines mean nothing after binary data: a binary file's errors give the byte offset.
    const char* begin = text_.data();
    if (binary_) fail("{}: byte {}: not a valid VTK file ({})", file_, where_ - begin, why);
    fail("{}:{}: not a valid VTK file ({})", file_, 1 + std::count(begin, where_, '\n'), why);
  }
  [[noreturn]] void truncated() { invalid("truncated: the file ends inside {}", section_); }

  // A word of the file for a message: short, printable.
  static std::string shown(std::string_view word) { return shown_text(word, 24); }

  static bool space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }
  void skip_space() {
    while (pos_ < end_ && space(*pos_)) ++pos_;
  }

  // The rest of the line, and past its newline.
  std::string_view line() {
    where_ = pos_;
    const char* eol = std::find(pos_, end_, '\n');
    const std::string_view out(pos_, static_cast<std::size_t>(eol - pos_));
    pos_ = eol == end_ ? end_ : eol + 1;
    return out;
  }

  // The words of the next non-blank line: a keyword and its arguments. Binary data starts
  // right after its newline.
  std::vector<std::string_view> header() {
    skip_space();
    const std::string_view text = line();
    std::vector<std::string_view> words;
    for (std::size_t i = 0; i < text.size();) {
      while (i < text.size() && space(text[i])) ++i;
      const std::size_t first = i;
      while (i < text.size() && !space(text[i])) ++i;
      if (i > first) words.push_back(text.substr(first, i - first));
    }
    return words;
  }

  // The next header if its keyword is `keyword`; else nothing is read.
  std::optional<std::vector<std::string_view>> header_if(std::string_view keyword) {
    const char* at = pos_;
    const bool found = is(word(), keyword);
    pos_ = at;
    if (!found) return std::nullopt;
    return header();
  }

  // Argument `i` of header `h` ("POINTS n type"), which must be there.
  std::string_view argument(const std::vector<std::string_view>& h, std::size_t i,
                            const char* what) {
    if (h.size() <= i) invalid("{} lacks its {}", section_, what);
    return h[i];
  }

  long long number(std::string_view word, const char* what) {
    long long value = 0;
    const auto [next, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (ec != std::errc() || next != word.data() + word.size())
      invalid("expected {} in {}, found '{}'", what, section_, shown(word));
    return value;
  }

  // The number of values `tuples` × `components` of type `t` that follow, which the rest of the
  // file must be able to hold.
  long long values(long long tuples, long long components, const DataType& t) {
    if (tuples < 0 || components < 0)
      invalid("{} announces {} items", section_, std::min(tuples, components));
    // Per value at least a digit and a blank (ASCII), its bytes or a bit (binary).
    const long long room =
        binary_ ? (end_ - pos_) * (t.kind == Kind::Bit ? 8 : 1) / t.bytes : (end_ - pos_) / 2;
    if (tuples != 0 && components > room / tuples) {
      if (components == 1)
        invalid("truncated: the file ends inside {}, which announces {} values", section_, tuples);
      invalid("truncated: the file ends inside {}, which announces {} × {} values", section_,
              tuples, components);
    }
    return tuples * components;
  }

  const DataType& data_type(std::string_view name) {
    for (const DataType& t : kDataTypes)
      if (is(name, t.name)) return t;
    invalid("unknown data type '{}' in {}", shown(name), section_);
  }

  // The next value of type `t`, as a double (binary: big-endian).
  double value(const DataType& t) {
    if (!binary_) return ascii_real();
    where_ = pos_;
    if (t.kind == Kind::Bit) invalid("bit values in {}", section_);
    if (end_ - pos_ < t.bytes) truncated();
    std::uint64_t bits = 0;
    for (int i = 0; i < t.bytes; ++i) bits = bits << 8 | static_cast<unsigned char>(pos_[i]);
    pos_ += t.bytes;
    const auto sign = [&](int n) {  // two's complement of an n-byte integer
      return static_cast<double>(static_cast<std::int64_t>(bits << (64 - 8 * n)) >> (64 - 8 * n));
    };
    switch (t.kind) {
      case Kind::Int8:
        return sign(1);
      case Kind::Int16:
        return sign(2);
      case Kind::Int32:
        return sign(4);
      case Kind::Int64:
        return sign(8);
      case Kind::Float32:
        return std::bit_cast<float>(static_cast<std::uint32_t>(bits));
      case Kind::Float64:
        return std::bit_cast<double>(bits);
      default:
        return static_cast<double>(bits);
    }
  }

  // An index (point, offset, cell type) of type `t`, which must be an integer type.
  long long index(const DataType& t) {
    if (binary_) {
      if (t.kind == Kind::Float32 || t.kind == Kind::Float64)
        invalid("{} has {} values; it needs integers", section_, t.name);
      const double v = value(t);
      if (!(std::abs(v) < 0x1p62)) invalid("the number {} in {} is out of range", v, section_);
      return static_cast<long long>(v);
    }
    skip_space();
    where_ = pos_;
    if (pos_ == end_) truncated();
    long long v = 0;
    const auto [next, ec] = std::from_chars(pos_, end_, v);
    if (ec != std::errc() || (next < end_ && !space(*next)))
      invalid("expected an integer in {}, found '{}'", section_, shown(word()));
    pos_ = next;
    return v;
  }

  std::string_view word() {
    skip_space();
    const char* first = pos_;
    while (pos_ < end_ && !space(*pos_)) ++pos_;
    return {first, static_cast<std::size_t>(pos_ - first)};
  }

  double ascii_real() {
    skip_space();
    where_ = pos_;
    if (pos_ == end_) truncated();
    double v = 0;
    const auto [next, ec] = std::from_chars(pos_, end_, v);
    if (ec == std::errc::result_out_of_range)  // subnormal or huge: strtod rounds it
      v = std::strtod(std::string(pos_, next).c_str(), nullptr);
    else if (ec != std::errc() || (next < end_ && !space(*next)))
      invalid("expected a number in {}, found '{}'", section_, shown(word()));
    pos_ = next;
    return v;
  }

  void skip_values(long long n, const DataType& t) {
    if (binary_) {
      const long long bytes = t.kind == Kind::Bit ? (n + 7) / 8 : n * t.bytes;
      if (end_ - pos_ < bytes) truncated();
      pos_ += bytes;
      return;
    }
    for (long long i = 0; i < n; ++i)
      if (word().empty()) truncated();
  }

  void read_preamble() {
    section_ = "the header";
    where_ = pos_;
    const std::string_view first = line();
    if (!is(first.substr(0, 14), "# vtk DataFile"))
      invalid("it does not start with '# vtk DataFile Version'");
    // Before 5.1, Lagrange hexahedra come in VTK's order before 9.1 (curved_type.hpp).
    const auto digit = first.find_first_of("0123456789");
    int major = 0, minor = 0;
    if (digit != std::string_view::npos) {
      const auto [next, ec] =
          std::from_chars(first.data() + digit, first.data() + first.size(), major);
      if (ec == std::errc() && next < first.data() + first.size() && *next == '.')
        std::from_chars(next + 1, first.data() + first.size(), minor);
    }
    c_.old_lagrange_hexahedra = major < 5 || (major == 5 && minor < 1);
    line();  // the title
    const std::vector<std::string_view> format = header();
    if (format.size() == 1 && is(format[0], "BINARY"))
      binary_ = true;
    else if (format.size() != 1 || !is(format[0], "ASCII"))
      invalid("expected ASCII or BINARY on line 3, found '{}'",
              shown(format.empty() ? "" : format[0]));
    const std::vector<std::string_view> dataset = header();
    section_ = "DATASET";
    if (dataset.empty() || !is(dataset[0], "DATASET"))
      invalid("expected DATASET, found '{}'", shown(dataset.empty() ? "" : dataset[0]));
    const std::string_view type = argument(dataset, 1, "type");
    if (is(type, "STRUCTURED_POINTS") || is(type, "STRUCTURED_GRID") ||
        is(type, "RECTILINEAR_GRID"))
      fail("{}: is a structured grid; neomesh reads unstructured grids (DATASET {})", file_, type);
    if (is(type, "POLYDATA"))
      polydata_ = true;
    else if (!is(type, "UNSTRUCTURED_GRID"))
      invalid("unknown DATASET {}", shown(type));
  }

  void read_section(const std::vector<std::string_view>& h) {
    const std::string_view keyword = h.empty() ? "" : h[0];
    section_ = shown(keyword);
    const auto polydata_cells = [&]() -> int {
      if (!polydata_) return -1;
      if (is(keyword, "VERTICES")) return kPolyVertex;
      if (is(keyword, "LINES")) return kPolyLine;
      if (is(keyword, "POLYGONS")) return kPolygon;
      if (is(keyword, "TRIANGLE_STRIPS")) return kStrip;
      return -1;
    }();
    if (is(keyword, "POINTS"))
      read_points(h);
    else if (polydata_cells >= 0 || (!polydata_ && is(keyword, "CELLS")))
      read_cells(h, polydata_cells);
    else if (!polydata_ && is(keyword, "CELL_TYPES"))
      read_cell_types(h);
    else if (is(keyword, "POINT_DATA") || is(keyword, "CELL_DATA")) {
      read_data_size(h);
      in_cell_data_ = is(keyword, "CELL_DATA");
    } else if (is(keyword, "FIELD"))
      read_field(h);
    else if (is(keyword, "METADATA"))
      skip_metadata();
    else
      read_attribute(h);
  }

  // Attributes may announce more tuples than follow (none at the end of the file).
  void read_data_size(const std::vector<std::string_view>& h) {
    data_size_ = number(argument(h, 1, "size"), "a size");
    if (data_size_ < 0) invalid("{} announces {} items", section_, data_size_);
  }

  void read_points(const std::vector<std::string_view>& h) {
    if (have_points_) invalid("it has two POINTS sections");
    const DataType& t = data_type(argument(h, 2, "data type"));
    const long long n = values(number(argument(h, 1, "size"), "a size"), 3, t) / 3;
    c_.xyz.resize(3 * n);
    for (long long i = 0; i < 3 * n; ++i) {
      c_.xyz[i] = value(t);
      if (!std::isfinite(c_.xyz[i]))
        invalid("point {} (0-based) has the coordinate {}", i / 3, c_.xyz[i]);
    }
    have_points_ = true;
  }

  // A point of a cell: an index into POINTS.
  std::int64_t point(const DataType& t) {
    const long long p = index(t);
    const long long n = static_cast<long long>(c_.xyz.size() / 3);
    if (p < 0 || p >= n)
      invalid("cell {} (0-based) refers to point {}, which is out of range (0..{})",
              c_.offsets.size() - 1, p, n - 1);
    return p;
  }

  // CELLS (or a POLYDATA section of cells of VTK type `type`): "n size" and per cell its
  // number of points and the points, or (5.1) OFFSETS and CONNECTIVITY.
  void read_cells(const std::vector<std::string_view>& h, int type) {
    if (!have_points_) invalid("{} comes before POINTS", section_);
    if (type < 0 && (c_.offsets.size() > 1 || have_types_))
      invalid("it has two CELLS sections, or CELL_TYPES before CELLS");
    const long long n = number(argument(h, 1, "number of cells"), "a size");
    const long long size = number(argument(h, 2, "size"), "a size");
    if (auto offsets = header_if("OFFSETS")) {
      read_offsets_and_connectivity(n, size, *offsets);
    } else {
      values(n, 1, kInt32);
      values(size, 1, kInt32);
      long long used = 0;
      for (long long i = 0; i < n; ++i) {
        const long long k = index(kInt32);
        if (k < 0 || k >= size - used)
          invalid("cell {} (0-based) has {} points, more than {} {} announces",
                  c_.offsets.size() - 1, k, size, section_);
        used += 1 + k;
        for (long long j = 0; j < k; ++j) c_.points.push_back(point(kInt32));
        c_.offsets.push_back(static_cast<std::int64_t>(c_.points.size()));
      }
      if (used != size) invalid("{} announces {} numbers and lists {}", section_, size, used);
    }
    if (type >= 0) c_.types.resize(c_.offsets.size() - 1, type);
  }

  void read_offsets_and_connectivity(long long n, long long size,
                                     const std::vector<std::string_view>& h) {
    section_ = "OFFSETS";
    const DataType& t = data_type(argument(h, 1, "data type"));
    const std::int64_t base = c_.points.size();
    std::vector<std::int64_t> offsets(values(n, 1, t));
    for (long long i = 0; i < n; ++i) {
      offsets[i] = index(t);
      if (offsets[i] < (i == 0 ? 0 : offsets[i - 1]) || offsets[i] > size ||
          (i == 0 && offsets[i] != 0))
        invalid("offset {} of cell {} (0-based) is out of order", offsets[i], i);
    }
    const long long last = n > 0 ? offsets.back() : 0;
    if (last != size) invalid("the offsets end at {}, CONNECTIVITY has {} numbers", last, size);
    const auto connectivity = header_if("CONNECTIVITY");
    section_ = "CONNECTIVITY";
    if (!connectivity) invalid("OFFSETS is not followed by CONNECTIVITY");
    const DataType& ct = data_type(argument(*connectivity, 1, "data type"));
    values(size, 1, ct);
    for (long long i = 1; i < n; ++i) {
      for (long long j = offsets[i - 1]; j < offsets[i]; ++j) c_.points.push_back(point(ct));
      c_.offsets.push_back(base + offsets[i]);
    }
  }

  void read_cell_types(const std::vector<std::string_view>& h) {
    const std::size_t cells = c_.offsets.size() - 1;
    const long long n = values(number(argument(h, 1, "size"), "a size"), 1, kInt32);
    if (have_types_) invalid("it has two CELL_TYPES sections");
    have_types_ = true;
    // More types than cells: VTK's reader uses the first ones (MOAB wrote such files).
    if (static_cast<std::size_t>(n) < cells)
      invalid("CELL_TYPES lists {} cells, CELLS {}", n, cells);
    c_.types.resize(cells);
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
      const long long type = index(kInt32);
      if (i >= cells) continue;
      const VtkType* t = vtk_type(type);
      if (!t) invalid("cell {} (0-based) has the unknown VTK cell type {}", i, type);
      const long long k = c_.offsets[i + 1] - c_.offsets[i];
      if (t->vertices >= 0 && k != t->vertices)
        invalid("cell {} (0-based) is a {} of {} points (a {} has {})", i, t->name, k, t->name,
                t->vertices);
      c_.types[i] = t->vtk;
    }
  }

  // The cell scalars "physical" (neomesh's and meshio's name for the cells' physical groups).
  void read_cell_groups(long long n, const DataType& t) {
    c_.tags.resize(static_cast<std::size_t>(n));
    for (int& tag : c_.tags) {
      const double v = value(t);
      if (!(v >= 0 && v < 2147483647.0) || v != std::floor(v))
        invalid("a cell's physical group is {} (must be a whole number, 0 or more)", v);
      tag = static_cast<int>(v);
    }
  }

  // The values of an attribute or field array of `components` per tuple, kept as point or cell
  // data (bit arrays are skipped).
  void read_data(std::string_view name, long long tuples, long long components, const DataType& t) {
    const long long n = values(tuples, components, t);
    if (t.kind == Kind::Bit || components < 1 || components > 1024) {
      skip_values(n, t);
      return;
    }
    DataArray a{decoded(name),
                static_cast<int>(components),
                static_cast<ValueType>(static_cast<int>(t.kind) - 1),
                {}};
    a.values.resize(static_cast<std::size_t>(n));
    for (double& v : a.values) v = value(t);
    round_to_type(a);
    (in_cell_data_ ? c_.cell_data : c_.point_data).push_back(std::move(a));
  }

  // A name as VTK writes it, with "%XX" for spaces and other special characters.
  static std::string decoded(std::string_view name) {
    std::string out;
    for (std::size_t i = 0; i < name.size(); ++i) {
      unsigned code = 0;
      if (name[i] == '%' && i + 2 < name.size() &&
          std::from_chars(name.data() + i + 1, name.data() + i + 3, code, 16).ptr ==
              name.data() + i + 3) {
        out += static_cast<char>(code);
        i += 2;
      } else {
        out += name[i];
      }
    }
    return out;
  }

  // POINT_DATA and CELL_DATA attributes: "KEYWORD name ..." and data_size_ values per tuple.
  void read_attribute(const std::vector<std::string_view>& h) {
    const std::string_view keyword = h.empty() ? "" : h[0];
    const auto in_data = [&] {
      if (data_size_ < 0) invalid("{} comes before POINT_DATA or CELL_DATA", section_);
    };
    if (is(keyword, "SCALARS")) {
      in_data();
      const DataType& t = data_type(argument(h, 2, "data type"));
      const long long components = h.size() > 3 ? number(h[3], "a number of components") : 1;
      header_if("LOOKUP_TABLE");
      const std::string_view name = argument(h, 1, "name");
      if (in_cell_data_ && components == 1 && (name == "physical" || name == "gmsh:physical"))
        read_cell_groups(values(data_size_, 1, t), t);
      else
        read_data(name, data_size_, components, t);
    } else if (is(keyword, "LOOKUP_TABLE")) {
      const long long n = number(argument(h, 2, "size"), "a size");
      skip_values(values(n, 4, binary_ ? kUInt8 : kFloat), kUInt8);  // RGBA
    } else if (is(keyword, "COLOR_SCALARS")) {
      in_data();
      const long long n = number(argument(h, 2, "number of values"), "a number of values");
      skip_values(values(data_size_, n, binary_ ? kUInt8 : kFloat), kUInt8);
    } else {
      const std::array<std::pair<std::string_view, int>, 6> tuples = {{{"VECTORS", 3},
                                                                       {"NORMALS", 3},
                                                                       {"TENSORS", 9},
                                                                       {"TENSORS6", 6},
                                                                       {"GLOBAL_IDS", 1},
                                                                       {"PEDIGREE_IDS", 1}}};
      for (const auto& [name, components] : tuples)
        if (is(keyword, name)) {
          in_data();
          const DataType& t = data_type(argument(h, 2, "data type"));
          read_data(argument(h, 1, "name"), data_size_, components, t);
          return;
        }
      if (!is(keyword, "TEXTURE_COORDINATES")) invalid("unknown keyword '{}'", shown(keyword));
      in_data();
      const DataType& t = data_type(argument(h, 3, "data type"));
      const long long dim = number(h[2], "a dimension");
      skip_values(values(data_size_, dim, t), t);
    }
  }

  // "FIELD name n", then n arrays "name components tuples type" with their values: point or
  // cell data after POINT_DATA or CELL_DATA, else the dataset's (group names, vtk_cells.hpp).
  void read_field(const std::vector<std::string_view>& h) {
    // Each array has a header line of at least 4 bytes.
    const long long arrays =
        values(number(argument(h, 2, "number of arrays"), "a size"), 1, kInt32);
    for (long long i = 0; i < arrays; ++i) {
      const std::vector<std::string_view> a = header();
      if (a.size() == 1 && a[0] == "NULL_ARRAY") continue;
      if (a.empty()) truncated();
      const DataType& t = data_type(argument(a, 3, "data type"));
      const long long components = number(a[1], "a number of components");
      const long long tuples = number(a[2], "a number of tuples");
      if (data_size_ >= 0 && tuples == data_size_) {
        read_data(a[0], tuples, components, t);
      } else if (data_size_ < 0 && components * tuples == 2 && t.kind != Kind::Bit) {
        values(2, 1, t);
        std::vector<double> pair = {value(t), value(t)};
        PhysicalGroup group;
        if (group_name_array(pair, group)) {
          group.name = decoded(a[0]);
          c_.names.push_back(std::move(group));
        }
      } else {
        skip_values(values(components, tuples, t), t);
      }
      if (header_if("METADATA")) skip_metadata();
    }
  }

  // METADATA (VTK 5): lines up to an empty one.
  void skip_metadata() {
    while (pos_ < end_) {
      const std::string_view text = line();
      if (std::all_of(text.begin(), text.end(), space)) return;
    }
  }

  std::string file_;
  InputText text_;
  const char* pos_ = nullptr;
  const char* end_ = nullptr;
  const char* where_ = nullptr;  // where what is being read starts, for messages
  std::string section_;
  bool binary_ = false;
  bool polydata_ = false;
  bool have_points_ = false;
  bool have_types_ = false;
  long long data_size_ = -1;  // tuples per attribute after POINT_DATA or CELL_DATA
  bool in_cell_data_ = false;
  VtkCells c_;
};

}  // namespace

InputMesh read_vtk(const std::filesystem::path& path) {
  return input_from_vtk_cells(VtkParser(path).parse(), path.string());
}

}  // namespace neomesh
