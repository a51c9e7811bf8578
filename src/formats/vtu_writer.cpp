#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include <fmt/ostream.h>

#include "formats/mesh_writers.hpp"
#include "mesh/cell_order.hpp"

namespace neomesh {

namespace {

// The file declares byte_order="LittleEndian" and the arrays are copied as they are in memory.
static_assert(std::endian::native == std::endian::little);

// A .vtu file whose arrays are in one <AppendedData encoding="raw"> section: each is a UInt64
// byte count followed by the values, and its DataArray tag gives its offset into the section.
//
// The section holds the arrays in the reverse order of their tags. meshio (5.x) converts raw
// data to base64 array by array in section order, finding each tag by its offset and then
// setting that to the offset in base64: a converted tag earlier in the file could then carry the
// offset of a later array and be taken for it (a hex mesh's "volume" came back as another
// field). In reverse order every tag not yet converted comes before the converted ones.
class VtuDocument {
 public:
  template <typename... Args>
  void text(fmt::format_string<Args...> format, Args&&... args) {
    fmt::format_to(std::back_inserter(pending_), format, std::forward<Args>(args)...);
  }
  // A DataArray whose values go to the appended section.
  template <class T>
  void array(std::string_view type, std::string_view attributes, const std::vector<T>& values) {
    const std::uint64_t bytes = values.size() * sizeof(T);
    std::string block(sizeof bytes + bytes, '\0');
    std::memcpy(block.data(), &bytes, sizeof bytes);
    if (bytes) std::memcpy(block.data() + sizeof bytes, values.data(), bytes);
    arrays_.push_back(
        {std::move(pending_),
         fmt::format("<DataArray type=\"{}\"{} format=\"appended\"", type, attributes),
         std::move(block)});
    pending_.clear();
  }
  // Ends the data with a newline before the closing tag: meshio drops what follows the last
  // newline.
  void write(std::ostream& f) const {
    std::vector<std::uint64_t> offset(arrays_.size());
    std::uint64_t at = 0;
    for (std::size_t k = arrays_.size(); k-- > 0;) {
      offset[k] = at;
      at += arrays_[k].block.size();
    }
    for (std::size_t k = 0; k < arrays_.size(); ++k)
      fmt::print(f, "{}{} offset=\"{}\"/>\n", arrays_[k].before, arrays_[k].tag, offset[k]);
    fmt::print(f, "{}<AppendedData encoding=\"raw\">\n_", pending_);
    for (std::size_t k = arrays_.size(); k-- > 0;)
      f.write(arrays_[k].block.data(), static_cast<std::streamsize>(arrays_[k].block.size()));
    fmt::print(f, "\n</AppendedData>\n</VTKFile>\n");
  }

 private:
  struct Array {
    std::string before;  // the text between the previous array's tag and this one's
    std::string tag;     // without the offset
    std::string block;   // byte count and values
  };
  std::vector<Array> arrays_;
  std::string pending_;  // text since the last array
};

// `text` as XML attribute text.
std::string escaped(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      case '\n':
        out += "&#10;";
        break;
      case '\r':
        out += "&#13;";
        break;
      case '\t':
        out += "&#9;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string attributes(std::string_view name, int components) {
  return fmt::format(" Name=\"{}\" NumberOfComponents=\"{}\"", escaped(name), components);
}

void add_field(VtuDocument& doc, const Field& field, const std::vector<double>& values) {
  doc.array("Float64", attributes(field.name, field.components), values);
}

// The values in type T; integer types take the nearest value they hold (0 for NaN), as a double
// beyond an integer type's range (2^64 from a UInt64 rounded) has no conversion.
template <class T>
std::vector<T> converted(const std::vector<double>& values) {
  std::vector<T> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double v = values[i];
    if constexpr (std::is_integral_v<T>) {
      constexpr double lo = static_cast<double>(std::numeric_limits<T>::lowest());
      constexpr double hi = static_cast<double>(std::numeric_limits<T>::max());
      out[i] = std::isnan(v) ? T{0}
               : v <= lo     ? std::numeric_limits<T>::lowest()
               : v >= hi     ? std::numeric_limits<T>::max()
                             : static_cast<T>(v);
    } else {
      out[i] = static_cast<T>(v);
    }
  }
  return out;
}

// An input array in its own type (a scalar without NumberOfComponents, as VTK writes it).
void add_data(VtuDocument& doc, const DataArray& a, const std::vector<double>& values) {
  const std::string attr = a.components == 1 ? fmt::format(" Name=\"{}\"", escaped(a.name))
                                             : attributes(a.name, a.components);
  switch (a.type) {
    case ValueType::Int8:
      return doc.array("Int8", attr, converted<std::int8_t>(values));
    case ValueType::UInt8:
      return doc.array("UInt8", attr, converted<std::uint8_t>(values));
    case ValueType::Int16:
      return doc.array("Int16", attr, converted<std::int16_t>(values));
    case ValueType::UInt16:
      return doc.array("UInt16", attr, converted<std::uint16_t>(values));
    case ValueType::Int32:
      return doc.array("Int32", attr, converted<std::int32_t>(values));
    case ValueType::UInt32:
      return doc.array("UInt32", attr, converted<std::uint32_t>(values));
    case ValueType::Int64:
      return doc.array("Int64", attr, converted<std::int64_t>(values));
    case ValueType::UInt64:
      return doc.array("UInt64", attr, converted<std::uint64_t>(values));
    case ValueType::Float32:
      return doc.array("Float32", attr, converted<float>(values));
    case ValueType::Float64:
      return doc.array("Float64", attr, values);
  }
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool real(ValueType t) {
  return t == ValueType::Float32 || t == ValueType::Float64;
}

// The VTK type of a facet or point of `n` points: vertex, line, triangle, quadrilateral; a
// curved mesh's facets as quadratic or Lagrange cells, as its cells (`lagrange`).
std::uint8_t vtk_facet_type(int dim, int n, bool lagrange) {
  if (dim == 2 && n == 3) return lagrange ? 68 : 21;  // the curve of 3 points
  constexpr std::uint8_t types[] = {0, 1, 3, 5, 9, 0, 22, 0, 23, 28};
  constexpr std::uint8_t lagrange_types[] = {0, 1, 3, 5, 9, 0, 69, 0, 23, 70};
  return (lagrange ? lagrange_types : types)[n];
}

}  // namespace

VtkElements vtk_elements(const GatheredMesh& gathered, bool lagrange) {
  const InputMesh& mesh = gathered.mesh;
  VtkElements e;
  const PetscInt nc = mesh.num_cells();
  if (mesh.curved()) {
    for (PetscInt c = 0; c < nc; ++c) {
      const CurvedFacts& f = facts(mesh.high_order.types[c]);
      PetscInt points[kMaxCurvedNodes];
      curved_cell_points(mesh, c, points);
      // .vtu files are written as version 1.0: Lagrange hexahedra in VTK's order before 9.1.
      const bool as_lagrange = lagrange && f.vtk_lagrange > 0;
      const bool old = as_lagrange && mesh.high_order.types[c] == CurvedType::Hexahedron27;
      const auto& order = vtk_order(mesh.high_order.types[c], as_lagrange);
      for (int i = 0; i < f.nodes; ++i)
        e.connectivity.push_back(points[order[old ? old_lagrange_hexahedron_position(i) : i]]);
      e.types.push_back(static_cast<std::uint8_t>(as_lagrange ? f.vtk_lagrange : f.vtk));
      e.offsets.push_back(static_cast<std::int64_t>(e.connectivity.size()));
    }
  } else {
    e.connectivity.resize(mesh.cell_vertices.size());
    for (PetscInt c = 0; c < nc; ++c) {
      const CellType t = mesh.cell_types[c];
      const PetscInt* cell = mesh.cell_vertices.data() + mesh.cell_offsets[c];
      for (int i = 0; i < num_vertices(t); ++i)
        e.connectivity[mesh.cell_offsets[c] + i] = cell[vtk_from_canonical(t)[i]];
      e.types.push_back(static_cast<std::uint8_t>(facts(t).vtk));
      e.offsets.push_back(mesh.cell_offsets[c + 1]);
    }
  }
  e.tags.assign(mesh.cell_tags.begin(), mesh.cell_tags.end());
  e.has_tags = gathered.has_cell_groups;
  const CurvedFacets curved(mesh);
  for (const TaggedEntities* group : {&mesh.facets, &mesh.points})
    for (PetscInt k = 0; k < group->size(); ++k) {
      PetscInt points[9] = {group->vertices[group->offsets[k]]};
      const int n = group == &mesh.facets ? curved.points(k, points) : 1;
      e.connectivity.insert(e.connectivity.end(), points, points + n);
      e.types.push_back(vtk_facet_type(mesh.dim, n, lagrange));
      e.offsets.push_back(static_cast<std::int64_t>(e.connectivity.size()));
      e.tags.push_back(group->tags[k]);
      e.has_tags = true;
    }
  return e;
}

std::vector<double> per_element(const std::vector<double>& values, int components, double fill,
                                std::size_t elements) {
  std::vector<double> out = values;
  out.resize(elements * components, fill);
  return out;
}

void write_vtu(const GatheredMesh& gathered, std::ostream& f) {
  const InputMesh& mesh = gathered.mesh;
  const VtkElements elements = vtk_elements(gathered, true);
  const PetscInt nv = mesh.num_points();
  const auto nc = static_cast<PetscInt>(elements.size());
  VtuDocument doc;
  doc.text(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n"
      "<UnstructuredGrid>\n");
  bool named = false;
  for (const PhysicalGroup& g : mesh.groups) {
    if (g.name.empty()) continue;
    if (!named) doc.text("<FieldData>\n");
    named = true;
    doc.text(
        "<DataArray type=\"Int32\" Name=\"{}\" NumberOfTuples=\"2\" format=\"ascii\">{} "
        "{}</DataArray>\n",
        escaped(g.name), g.tag, g.dim);
  }
  if (named) doc.text("</FieldData>\n");
  doc.text("<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", nv, nc);

  doc.text("<PointData>\n");
  // (A curved mesh's high-order nodes have no values: NaN.)
  for (const DataArray& a : mesh.point_data)
    add_data(doc, a, per_element(a.values, a.components, real(a.type) ? kNaN : 0.0, nv));
  for (const Field& field : gathered.fields.vertex)
    add_field(doc, field, per_element(field.values, field.components, kNaN, nv));
  doc.text("</PointData>\n<CellData>\n");
  for (const DataArray& a : mesh.cell_data)
    add_data(doc, a,
             per_element(a.values, a.components, real(a.type) ? kNaN : 0.0, elements.size()));
  for (const Field& field : gathered.fields.cell)
    add_field(doc, field, per_element(field.values, field.components, kNaN, elements.size()));
  if (elements.has_tags) doc.array("Int32", " Name=\"physical\"", elements.tags);
  doc.text("</CellData>\n<Points>\n");

  doc.array("Float64", " NumberOfComponents=\"3\"", points_in_space(mesh));
  doc.text("</Points>\n<Cells>\n");
  doc.array("Int64", " Name=\"connectivity\"", elements.connectivity);
  doc.array("Int64", " Name=\"offsets\"", elements.offsets);
  doc.array("UInt8", " Name=\"types\"", elements.types);
  doc.text("</Cells>\n</Piece>\n</UnstructuredGrid>\n");
  doc.write(f);
}

}  // namespace neomesh
