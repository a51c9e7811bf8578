#include "formats/vtu_reader.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>

#include <pugixml.hpp>

#include "core/error.hpp"
#include "formats/input_file.hpp"
#include "formats/vtk_cells.hpp"

namespace neomesh {

namespace {

// zlib's largest ratio of output to input is 1032:1 (deflate's best case); a block that claims
// more (plus a stream header's worth) is not zlib data and is refused before memory is taken for
// its output.
constexpr std::uint64_t kZlibMaxRatio = 1032, kZlibSlack = 64;
// vtkGhostType's bit for a cell that another piece owns (vtkDataSetAttributes::DUPLICATECELL).
constexpr std::int64_t kDuplicateCell = 1;

// What is wrong with an array's data, before the reader adds which array and file.
struct DataError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

enum class Kind { Signed, Unsigned, Real };
struct ScalarType {
  std::string_view name;
  Kind kind;
  int bytes;
};
constexpr ScalarType kScalarTypes[] = {{"Int8", Kind::Signed, 1},  {"UInt8", Kind::Unsigned, 1},
                                       {"Int16", Kind::Signed, 2}, {"UInt16", Kind::Unsigned, 2},
                                       {"Int32", Kind::Signed, 4}, {"UInt32", Kind::Unsigned, 4},
                                       {"Int64", Kind::Signed, 8}, {"UInt64", Kind::Unsigned, 8},
                                       {"Float32", Kind::Real, 4}, {"Float64", Kind::Real, 8}};

// Bytes read in order from binary data: raw bytes, or base64 (RFC 4648) text decoded a group
// of 4 characters at a time, whitespace skipped. A group may end in padding and another group
// follow: VTK encodes an array's header and its values separately, one after the other.
class ByteSource {
 public:
  ByteSource(std::string_view data, bool base64) : data_(data), base64_(base64) {}

  // At least the number of bytes left.
  std::uint64_t bound() const {
    const std::uint64_t left = data_.size() - pos_;
    return base64_ ? left / 4 * 3 + 3 + (group_size_ - group_used_) : left;
  }

  void read(char* out, std::size_t n) {
    if (!base64_) {
      if (n > data_.size() - pos_) throw DataError("the data end early");
      std::memcpy(out, data_.data() + pos_, n);
      pos_ += n;
      return;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (group_used_ == group_size_) next_group();
      out[i] = static_cast<char>(group_[group_used_++]);
    }
  }

 private:
  static int sextet(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return c == '=' ? -1 : -2;
  }

  void next_group() {
    int bits[4], n = 0;
    while (n < 4 && pos_ < data_.size()) {
      const char c = data_[pos_++];
      if (std::isspace(static_cast<unsigned char>(c))) continue;
      bits[n] = sextet(c);
      if (bits[n] == -2) throw DataError(fmt::format("'{}' is not a base64 character", shown(c)));
      ++n;
    }
    if (n < 2) throw DataError("the data end early");
    for (int k = n; k < 4; ++k) bits[k] = -1;  // unpadded end
    if (bits[0] < 0 || bits[1] < 0 || (bits[2] < 0 && bits[3] >= 0))
      throw DataError("misplaced base64 padding '='");
    const std::uint32_t v =
        bits[0] << 18 | bits[1] << 12 | std::max(bits[2], 0) << 6 | std::max(bits[3], 0);
    group_ = {static_cast<unsigned char>(v >> 16), static_cast<unsigned char>(v >> 8),
              static_cast<unsigned char>(v)};
    group_size_ = bits[2] < 0 ? 1 : bits[3] < 0 ? 2 : 3;
    group_used_ = 0;
  }

  static std::string shown(char c) { return shown_text(std::string_view(&c, 1), 1); }

  std::string_view data_;
  bool base64_;
  std::size_t pos_ = 0;
  std::array<unsigned char, 3> group_{};
  int group_size_ = 0, group_used_ = 0;
};

// How the binary arrays of a file are laid out (attributes of <VTKFile>).
struct BinaryLayout {
  bool big_endian = false;
  int header_bytes = 4;  // UInt32 or UInt64
  bool zlib = false;
};

// `bytes` bytes at `p` as an unsigned number of the file's byte order.
std::uint64_t unsigned_at(const char* p, int bytes, bool big_endian) {
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i)
    v |= std::uint64_t{static_cast<unsigned char>(p[i])} << 8 * (big_endian ? bytes - 1 - i : i);
  return v;
}

std::uint64_t header_number(ByteSource& s, const BinaryLayout& layout) {
  char bytes[8];
  s.read(bytes, layout.header_bytes);
  return unsigned_at(bytes, layout.header_bytes, layout.big_endian);
}

// The values' bytes of a binary array: a header (the byte count; compressed: the number of
// blocks, the block size, the last block's size, each block's compressed size), then the data.
std::string array_bytes(ByteSource& s, const BinaryLayout& layout) {
  if (!layout.zlib) {
    const std::uint64_t n = header_number(s, layout);
    if (n > s.bound())
      throw DataError(fmt::format("it announces {} bytes, more than the file holds", n));
    std::string out(n, '\0');
    s.read(out.data(), n);
    return out;
  }
  const std::uint64_t blocks = header_number(s, layout), block = header_number(s, layout),
                      last = header_number(s, layout);
  if (blocks > s.bound() / layout.header_bytes)
    throw DataError(
        fmt::format("it announces {} compressed blocks, more than the file holds", blocks));
  std::vector<std::uint64_t> compressed(blocks);
  std::uint64_t total = 0;
  for (std::uint64_t k = 0; k < blocks; ++k) {
    compressed[k] = header_number(s, layout);
    const std::uint64_t size = k + 1 == blocks && last != 0 ? last : block;
    if (compressed[k] > s.bound() || size > kZlibMaxRatio * compressed[k] + kZlibSlack)
      throw DataError(fmt::format("compressed block {} of {} bytes cannot hold {} bytes", k,
                                  compressed[k], size));
    total += size;
  }
  std::string out(total, '\0'), in;
  std::uint64_t at = 0;
  for (std::uint64_t k = 0; k < blocks; ++k) {
    const std::uint64_t size = k + 1 == blocks && last != 0 ? last : block;
    in.resize(compressed[k]);
    s.read(in.data(), in.size());
    uLongf length = size;
    if (uncompress(reinterpret_cast<Bytef*>(out.data() + at), &length,
                   reinterpret_cast<const Bytef*>(in.data()), in.size()) != Z_OK ||
        length != size)
      throw DataError(fmt::format("compressed block {} is not valid zlib data", k));
    at += size;
  }
  return out;
}

// The value of type `t` at `p` converted to T (an integer or double); throws DataError for a
// value T cannot hold.
template <typename T>
T binary_value(const char* p, const ScalarType& t, bool big_endian) {
  const std::uint64_t bits = unsigned_at(p, t.bytes, big_endian);
  if (t.kind == Kind::Real) {
    const double v = t.bytes == 4 ? std::bit_cast<float>(static_cast<std::uint32_t>(bits))
                                  : std::bit_cast<double>(bits);
    return static_cast<T>(v);  // T is double: integer arrays of Float are refused earlier
  }
  if (t.kind == Kind::Signed) {
    const int shift = 64 - 8 * t.bytes;
    return static_cast<T>(static_cast<std::int64_t>(bits << shift) >> shift);
  }
  if (std::is_integral_v<T> &&
      bits > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
    throw DataError(fmt::format("the value {} is out of range", bits));
  return static_cast<T>(bits);  // a double: data values (input_mesh.hpp, ValueType)
}

// The whitespace-separated numbers of an ASCII array, at most `count` of them.
template <typename T>
std::vector<T> ascii_values(std::string_view text, std::size_t count) {
  std::vector<T> out;
  const char* p = text.data();
  const char* end = p + text.size();
  const auto space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (true) {
    while (p < end && space(*p)) ++p;
    if (p == end) return out;
    if (out.size() == count) throw DataError(fmt::format("it holds more than {} values", count));
    const char* word = p;
    while (p < end && !space(*p)) ++p;
    T v{};
    const auto [next, ec] = std::from_chars(word, p, v);
    if (ec != std::errc() || next != p) {
      const std::string_view w(word, static_cast<std::size_t>(p - word));
      throw DataError(fmt::format("'{}' is not {}", shown_text(w, 24),
                                  std::is_integral_v<T> ? "an integer" : "a number"));
    }
    out.push_back(v);
  }
}

class VtuReader {
 public:
  explicit VtuReader(const std::filesystem::path& path)
      : file_(path.string()), text_(read_input_file(path)) {
    split_appended_data();
    const pugi::xml_parse_result result = doc_.load_buffer_inplace(
        xml_.data(), xml_.size(), pugi::parse_default, pugi::encoding_utf8);
    if (!result) {
      const auto line = 1 + std::count(xml_.data(), xml_.data() + result.offset, '\n');
      fail("{}:{}: not a valid VTK XML file ({})", file_, line, result.description());
    }
    root_ = doc_.child("VTKFile");
    if (!root_) invalid("it has no <VTKFile> element");
    read_layout();
  }

  // True if the file's version (major.minor, none: 0.1) is before 2.2, which VTK 9.1's Lagrange
  // hexahedra came with (curved_type.hpp).
  bool old_lagrange_hexahedra() const {
    const std::string_view version = root_.attribute("version").value();
    int major = 0, minor = 1;
    const auto dot = version.find('.');
    std::from_chars(version.data(), version.data() + version.size(), major);
    if (dot != std::string_view::npos)
      std::from_chars(version.data() + dot + 1, version.data() + version.size(), minor);
    return major < 2 || (major == 2 && minor < 2);
  }

  // The grid's type ("UnstructuredGrid", "PUnstructuredGrid"); throws Error for structured
  // grids and polydata.
  std::string_view grid_type() const {
    const std::string_view type = root_.attribute("type").value();
    for (std::string_view structured : {"ImageData", "StructuredGrid", "RectilinearGrid"})
      if (type == structured || type.substr(std::min<std::size_t>(1, type.size())) == structured)
        fail("{}: is a structured grid ({}); neomesh reads unstructured grids (.vtu, .pvtu)", file_,
             type);
    if (type == "PolyData" || type == "PPolyData")
      fail("{}: is VTK polydata ({}); neomesh reads unstructured grids (.vtu, .pvtu)", file_, type);
    return type;
  }

  pugi::xml_node grid(std::string_view type) const {
    if (grid_type() != type)
      invalid("its VTKFile type is '{}', expected '{}'",
              shown_text(root_.attribute("type").value(), 40), type);
    const pugi::xml_node grid = root_.child(std::string(type).c_str());
    if (!grid) invalid("it has no <{}> element", type);
    return grid;
  }

  // The ValueType of a numeric DataArray, or none for other types (String, Bit).
  static std::optional<ValueType> value_type(pugi::xml_node array) {
    const std::string_view name = array.attribute("type").value();
    for (std::size_t k = 0; k < std::size(kScalarTypes); ++k)
      if (name == kScalarTypes[k].name) return static_cast<ValueType>(k);
    return std::nullopt;
  }

  template <typename... Args>
  [[noreturn]] void invalid(fmt::format_string<Args...> format, Args&&... args) const {
    fail("{}: not a valid VTK XML file ({})", file_,
         fmt::format(format, std::forward<Args>(args)...));
  }

  const std::string& file() const { return file_; }

  // A count attribute of `node` ("NumberOfPoints").
  std::size_t count(pugi::xml_node node, const char* attribute, std::string_view where) const {
    const std::string_view text = node.attribute(attribute).value();
    std::uint64_t n = 0;
    const auto [next, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
    if (text.empty() || ec != std::errc() || next != text.data() + text.size())
      invalid("{} lacks {} or it is not a count: '{}'", where, attribute, shown_text(text, 24));
    if (n > text_.size() * 8)  // each value takes a bit at least
      invalid("{} announces {} = {}, more than the file can hold", where, attribute, n);
    return static_cast<std::size_t>(n);
  }

  // The `count` values of DataArray `array` (`what` names it in messages) as T: double, or
  // std::int64_t (which refuses Float arrays).
  template <typename T>
  std::vector<T> values(pugi::xml_node array, std::size_t count, const std::string& what) const {
    try {
      const ScalarType& t = scalar_type(array, what);
      if (std::is_integral_v<T> && t.kind == Kind::Real)
        invalid("{} has {} values; it needs integers", what, t.name);
      const std::string_view format = array.attribute("format").value();
      if (format == "ascii") {
        std::vector<T> out = ascii_values<T>(array.child_value(), count);
        if (out.size() != count)
          invalid("{} holds {} values, expected {}", what, out.size(), count);
        return out;
      }
      std::string bytes;
      if (format == "binary") {
        ByteSource source(array.child_value(), true);
        bytes = array_bytes(source, layout_);
      } else if (format == "appended") {
        ByteSource source = appended(array, what);
        bytes = array_bytes(source, layout_);
      } else {
        invalid("{} has the format '{}' (ascii, binary or appended)", what, shown_text(format, 24));
      }
      if (bytes.size() / t.bytes != count || bytes.size() % t.bytes != 0)
        invalid("{} holds {} bytes, expected {} values of {}", what, bytes.size(), count, t.name);
      std::vector<T> out(count);
      for (std::size_t i = 0; i < count; ++i)
        out[i] = binary_value<T>(bytes.data() + i * t.bytes, t, layout_.big_endian);
      return out;
    } catch (const DataError& e) {
      invalid("{}: {}", what, e.what());
    }
  }

 private:
  // Appended raw data is not XML: the XML parsed is the text before <AppendedData>, closed, and
  // the data (after its '_') is kept aside.
  void split_appended_data() {
    const std::string_view text(text_.data(), text_.size());
    const std::size_t tag = text.find("<AppendedData");
    if (tag == std::string_view::npos) {
      xml_.assign(text);
      return;
    }
    const std::size_t close = text.find('>', tag);
    if (close == std::string_view::npos) invalid("the <AppendedData> tag is not closed");
    std::string element(text.substr(tag, close - tag));
    if (element.ends_with('/')) element.pop_back();
    xml_.assign(text.substr(0, tag));
    xml_ += "</VTKFile>";
    if (!appended_doc_.load_string((element + "/>").c_str()))
      invalid("the <AppendedData> tag is not valid XML");
    const std::size_t underscore = text.find('_', close);
    if (underscore == std::string_view::npos) invalid("<AppendedData> lacks its '_'");
    appended_ = text.substr(underscore + 1);
    have_appended_ = true;
  }

  void read_layout() {
    const std::string_view order = root_.attribute("byte_order").value();
    if (order == "BigEndian")
      layout_.big_endian = true;
    else if (!order.empty() && order != "LittleEndian")
      invalid("unknown byte_order '{}'", shown_text(order, 24));
    const std::string_view header = root_.attribute("header_type").value();
    if (header == "UInt64")
      layout_.header_bytes = 8;
    else if (!header.empty() && header != "UInt32")
      invalid("unknown header_type '{}'", shown_text(header, 24));
    const std::string_view compressor = root_.attribute("compressor").value();
    if (compressor == "vtkZLibDataCompressor")
      layout_.zlib = true;
    else if (!compressor.empty())
      fail(
          "{}: is compressed with {}; neomesh reads VTK XML files compressed with zlib "
          "(vtkZLibDataCompressor) or not compressed",
          file_, shown_text(compressor, 40));
  }

  const ScalarType& scalar_type(pugi::xml_node array, const std::string& what) const {
    const std::string_view name = array.attribute("type").value();
    for (const ScalarType& t : kScalarTypes)
      if (name == t.name) return t;
    invalid("{} has the unknown type '{}'", what, shown_text(name, 24));
  }

  ByteSource appended(pugi::xml_node array, const std::string& what) const {
    if (!have_appended_) invalid("{} is appended, but the file has no <AppendedData>", what);
    const std::string_view encoding =
        appended_doc_.child("AppendedData").attribute("encoding").value();
    if (encoding != "raw" && encoding != "base64")
      invalid("<AppendedData> has the encoding '{}' (raw or base64)", shown_text(encoding, 24));
    const std::string_view text = array.attribute("offset").value();
    std::uint64_t offset = 0;
    const auto [next, ec] = std::from_chars(text.data(), text.data() + text.size(), offset);
    if (text.empty() || ec != std::errc() || next != text.data() + text.size() ||
        offset > appended_.size())
      invalid("{} has the offset '{}', not one into the appended data", what, shown_text(text, 24));
    return ByteSource(appended_.substr(offset), encoding == "base64");
  }

  std::string file_;
  InputText text_;
  std::string xml_;
  pugi::xml_document doc_, appended_doc_;
  pugi::xml_node root_;
  std::string_view appended_;
  bool have_appended_ = false;
  BinaryLayout layout_;
};

// The DataArray of `node` named `name`, or a null node.
pugi::xml_node named_array(pugi::xml_node node, std::string_view name) {
  for (pugi::xml_node array : node.children("DataArray"))
    if (name == array.attribute("Name").value()) return array;
  return {};
}

// Cell data that are not carried as data: the groups and the ghost marks.
bool is_special_cell_data(std::string_view name) {
  return name == "physical" || name == "gmsh:physical" || name == "vtkGhostType";
}

// The numeric arrays of <PointData> or <CellData> `node` with `count` tuples each, but those
// `skip` names (arrays of other types, String, are left out).
std::vector<DataArray> data_arrays(const VtuReader& r, pugi::xml_node node, std::size_t count,
                                   const std::string& where, bool (*skip)(std::string_view)) {
  std::vector<DataArray> out;
  for (pugi::xml_node array : node.children("DataArray")) {
    const std::string name = array.attribute("Name").value();
    const std::optional<ValueType> type = VtuReader::value_type(array);
    if (name.empty() || !type || (skip && skip(name))) continue;
    const std::string what =
        fmt::format("the {} '{}' of {}", node.name(), shown_text(name, 40), where);
    int components = 1;
    const std::string_view text = array.attribute("NumberOfComponents").value();
    if (!text.empty()) {
      const auto [next, ec] = std::from_chars(text.data(), text.data() + text.size(), components);
      if (ec != std::errc() || next != text.data() + text.size() || components < 1 ||
          components > 1024)
        r.invalid("{} has {} components", what, shown_text(text, 24));
    }
    if (count > std::numeric_limits<std::size_t>::max() / 1024)
      r.invalid("{} has too many values", what);
    out.push_back({name, components, *type,
                   r.values<double>(array, count * static_cast<std::size_t>(components), what)});
    round_to_type(out.back());
  }
  return out;
}

// One <Piece> of a .vtu as the file lists it.
struct Piece {
  VtkCells cells;
  std::vector<std::int64_t> global_ids;  // per point, if the piece gives them
  std::vector<std::int64_t> ghost;       // per cell: vtkGhostType, if the piece gives it
};

std::vector<std::int64_t> optional_integers(const VtuReader& r, pugi::xml_node array, std::size_t n,
                                            const std::string& what) {
  if (!array) return {};
  return r.values<std::int64_t>(array, n, what);
}

Piece read_piece(const VtuReader& r, pugi::xml_node node, int index) {
  const std::string where = fmt::format("piece {}", index);
  const std::size_t points = r.count(node, "NumberOfPoints", where);
  const std::size_t cells = r.count(node, "NumberOfCells", where);
  Piece p;
  const pugi::xml_node xyz = node.child("Points").child("DataArray");
  if (!xyz) r.invalid("{} has no <Points> with a <DataArray>", where);
  const std::string_view components = xyz.attribute("NumberOfComponents").value();
  if (components != "3")
    r.invalid("the points of {} have {} components; VTK's points have 3", where,
              shown_text(components.empty() ? "1" : components, 24));
  p.cells.xyz = r.values<double>(xyz, 3 * points, "the points of " + where);
  for (std::size_t i = 0; i < p.cells.xyz.size(); ++i)
    if (!std::isfinite(p.cells.xyz[i]))
      r.invalid("point {} (0-based) of {} has the coordinate {}", i / 3, where, p.cells.xyz[i]);

  const pugi::xml_node cell_arrays = node.child("Cells");
  const auto cell_array = [&](const char* name) {
    const pugi::xml_node array = named_array(cell_arrays, name);
    if (!array && cells > 0) r.invalid("{} has no <Cells> DataArray '{}'", where, name);
    return array;
  };
  const std::vector<std::int64_t> ends =
      optional_integers(r, cell_array("offsets"), cells, "the offsets of " + where);
  const std::vector<std::int64_t> types =
      optional_integers(r, cell_array("types"), cells, "the types of " + where);
  for (std::size_t i = 0; i < cells; ++i)
    if (ends[i] < (i == 0 ? 0 : ends[i - 1]))
      r.invalid("offset {} of cell {} (0-based) of {} is out of order", ends[i], i, where);
  const std::size_t size = cells > 0 ? ends.back() : 0;
  p.cells.points =
      optional_integers(r, cell_array("connectivity"), size, "the connectivity of " + where);
  p.cells.offsets.insert(p.cells.offsets.end(), ends.begin(), ends.end());
  for (std::size_t i = 0; i < cells; ++i) {
    const VtkType* t = vtk_type(types[i]);
    if (!t)
      r.invalid("cell {} (0-based) of {} has the unknown VTK cell type {}", i, where, types[i]);
    const std::int64_t k = ends[i] - p.cells.offsets[i];
    if (t->vertices >= 0 && k != t->vertices)
      r.invalid("cell {} (0-based) of {} is a {} of {} points (a {} has {})", i, where, t->name, k,
                t->name, t->vertices);
    p.cells.types.push_back(t->vtk);
  }
  for (const std::int64_t v : p.cells.points)
    if (v < 0 || static_cast<std::size_t>(v) >= points)
      r.invalid("a cell of {} refers to point {}, which is out of range (0..{})", where, v,
                static_cast<std::int64_t>(points) - 1);

  const pugi::xml_node cell_data = node.child("CellData");
  pugi::xml_node tags = named_array(cell_data, "physical");
  if (!tags) tags = named_array(cell_data, "gmsh:physical");
  const std::vector<std::int64_t> tag_values =
      optional_integers(r, tags, cells, "the cell data 'physical' of " + where);
  for (const std::int64_t tag : tag_values) {
    if (tag > std::numeric_limits<int>::max())
      r.invalid("the physical group {} of {} is beyond the range of int", tag, where);
    p.cells.tags.push_back(static_cast<int>(tag));
  }
  p.ghost = optional_integers(r, named_array(cell_data, "vtkGhostType"), cells,
                              "the cell data 'vtkGhostType' of " + where);
  const pugi::xml_node point_data = node.child("PointData");
  const char* ids = point_data.attribute("GlobalIds").value();
  if (*ids)
    p.global_ids = optional_integers(r, named_array(point_data, ids), points,
                                     fmt::format("the global ids '{}' of {}", ids, where));
  p.cells.point_data = data_arrays(r, point_data, points, where, nullptr);
  p.cells.cell_data = data_arrays(r, cell_data, cells, where, is_special_cell_data);
  return p;
}

// The group names of the grid's <FieldData> (vtk_cells.hpp).
void read_group_names(const VtuReader& r, pugi::xml_node grid, std::vector<PhysicalGroup>& names) {
  for (pugi::xml_node array : grid.child("FieldData").children("DataArray")) {
    const std::string name = array.attribute("Name").value();
    const std::string_view components = array.attribute("NumberOfComponents").value();
    if (name.empty() || !VtuReader::value_type(array) ||
        !(components.empty() || components == "1" || components == "2"))
      continue;
    PhysicalGroup group;
    if (group_name_array(r.values<double>(array, 2, "the field data '" + name + "'"), group)) {
      group.name = name;
      names.push_back(std::move(group));
    }
  }
}

std::vector<Piece> read_pieces(const VtuReader& r, std::vector<PhysicalGroup>& names) {
  std::vector<Piece> pieces;
  const pugi::xml_node grid = r.grid("UnstructuredGrid");
  for (pugi::xml_node node : grid.children("Piece"))
    pieces.push_back(read_piece(r, node, static_cast<int>(pieces.size())));
  if (pieces.empty()) r.invalid("it has no <Piece>");
  read_group_names(r, grid, names);
  return pieces;
}

// A point's three coordinates, bit for bit, as a hash key.
struct PointKey {
  std::array<std::uint64_t, 3> bits;
  bool operator==(const PointKey&) const = default;
};
struct PointKeyHash {
  std::size_t operator()(const PointKey& k) const {
    std::uint64_t h = 0xcbf29ce484222325;
    for (std::uint64_t b : k.bits) h = (h ^ b) * 0x100000001b3;
    return static_cast<std::size_t>(h ^ h >> 29);
  }
};

// The arrays of every piece (same name and components), empty, with the type of the first.
std::vector<DataArray> common_arrays(const std::vector<Piece>& pieces, bool point) {
  const auto arrays = [&](const Piece& p) -> const std::vector<DataArray>& {
    return point ? p.cells.point_data : p.cells.cell_data;
  };
  std::map<std::pair<std::string, int>, std::size_t> count;  // pieces having each array
  for (const Piece& p : pieces) {
    std::set<std::pair<std::string, int>> names;
    for (const DataArray& a : arrays(p)) names.emplace(a.name, a.components);
    for (const auto& key : names) ++count[key];
  }
  std::vector<DataArray> out;
  std::set<std::string> taken;
  for (const DataArray& a : arrays(pieces.front()))
    if (count[{a.name, a.components}] == pieces.size() && taken.insert(a.name).second)
      out.push_back({a.name, a.components, a.type, {}});
  return out;
}

// For each array of `to`: the index of the array of the same name and components in `from`.
std::vector<std::size_t> matching(const std::vector<DataArray>& to,
                                  const std::vector<DataArray>& from) {
  std::map<std::pair<std::string, int>, std::size_t> index;
  for (std::size_t k = from.size(); k-- > 0;) index[{from[k].name, from[k].components}] = k;
  std::vector<std::size_t> out;
  for (const DataArray& a : to) out.push_back(index.at({a.name, a.components}));
  return out;
}

// Appends tuple `i` of the arrays `from[match[j]]` to the arrays `to[j]`.
void append_tuple(std::vector<DataArray>& to, const std::vector<DataArray>& from,
                  const std::vector<std::size_t>& match, std::size_t i) {
  for (std::size_t j = 0; j < to.size(); ++j) {
    const DataArray& a = from[match[j]];
    const auto k = static_cast<std::size_t>(a.components);
    to[j].values.insert(to[j].values.end(), a.values.begin() + i * k,
                        a.values.begin() + (i + 1) * k);
  }
}

// The pieces as one list of cells: a point shared by pieces is one point (see vtu_reader.hpp),
// duplicate ghost cells are left out. Point data of shared points come from their first piece.
VtkCells join_pieces(std::vector<Piece>& pieces) {
  const bool by_id = std::all_of(pieces.begin(), pieces.end(),
                                 [](const Piece& p) { return !p.global_ids.empty(); });
  std::unordered_map<std::int64_t, std::int64_t> by_global_id;
  std::unordered_map<PointKey, std::pair<std::int64_t, std::size_t>, PointKeyHash> by_position;
  VtkCells all;
  all.point_data = common_arrays(pieces, true);
  all.cell_data = common_arrays(pieces, false);
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const VtkCells& c = pieces[k].cells;
    const auto point_match = matching(all.point_data, c.point_data);
    const auto cell_match = matching(all.cell_data, c.cell_data);
    std::vector<std::int64_t> point(c.xyz.size() / 3);
    for (std::size_t i = 0; i < point.size(); ++i) {
      const std::int64_t next = static_cast<std::int64_t>(all.xyz.size() / 3);
      if (by_id) {
        point[i] = by_global_id.try_emplace(pieces[k].global_ids[i], next).first->second;
      } else if (pieces.size() > 1) {
        PointKey key;
        for (int d = 0; d < 3; ++d) key.bits[d] = std::bit_cast<std::uint64_t>(c.xyz[3 * i + d]);
        const auto [it, added] = by_position.try_emplace(key, next, k);
        point[i] = added || it->second.second == k ? next : it->second.first;
      } else {
        point[i] = next;
      }
      if (point[i] != next) continue;
      all.xyz.insert(all.xyz.end(), &c.xyz[3 * i], &c.xyz[3 * i + 3]);
      append_tuple(all.point_data, c.point_data, point_match, i);
    }
    for (std::size_t i = 0; i < c.types.size(); ++i) {
      if (!pieces[k].ghost.empty() && (pieces[k].ghost[i] & kDuplicateCell)) continue;
      all.types.push_back(c.types[i]);
      for (std::int64_t j = c.offsets[i]; j < c.offsets[i + 1]; ++j)
        all.points.push_back(point[c.points[j]]);
      all.offsets.push_back(static_cast<std::int64_t>(all.points.size()));
      append_tuple(all.cell_data, c.cell_data, cell_match, i);
      if (!c.tags.empty()) {
        all.tags.resize(all.types.size() - 1, 0);
        all.tags.push_back(c.tags[i]);
      }
    }
    pieces[k] = {};  // its memory is not needed any more
  }
  if (!all.tags.empty()) all.tags.resize(all.types.size(), 0);
  return all;
}

}  // namespace

InputMesh read_vtu(const std::filesystem::path& path) {
  const VtuReader reader(path);
  std::vector<PhysicalGroup> names;
  std::vector<Piece> pieces = read_pieces(reader, names);
  VtkCells cells = join_pieces(pieces);
  cells.names = std::move(names);
  cells.old_lagrange_hexahedra = reader.old_lagrange_hexahedra();
  return input_from_vtk_cells(cells, reader.file());
}

InputMesh read_pvtu(const std::filesystem::path& path) {
  const VtuReader reader(path);
  std::vector<Piece> pieces;
  std::vector<PhysicalGroup> names;
  for (pugi::xml_node node : reader.grid("PUnstructuredGrid").children("Piece")) {
    const std::string_view source = node.attribute("Source").value();
    if (source.empty()) reader.invalid("a <Piece> lacks its Source");
    const std::filesystem::path piece = path.parent_path() / std::filesystem::path(source);
    if (piece.extension() != ".vtu")
      fail("{}: piece {} is {}; the pieces of a .pvtu are .vtu files", reader.file(), pieces.size(),
           piece.string());
    const VtuReader piece_reader(piece);
    for (Piece& p : read_pieces(piece_reader, names)) pieces.push_back(std::move(p));
  }
  if (pieces.empty()) reader.invalid("it has no <Piece>");
  VtkCells cells = join_pieces(pieces);
  cells.names = std::move(names);
  cells.old_lagrange_hexahedra = reader.old_lagrange_hexahedra();
  return input_from_vtk_cells(cells, reader.file());
}

}  // namespace neomesh
