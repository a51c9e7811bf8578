#include <bit>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <string>
#include <vector>

#include <fmt/ostream.h>

#include "mesh/cell_order.hpp"
#include "mesh/mesh_writers.hpp"

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

void add_field(VtuDocument& doc, const Field& field) {
  doc.array("Float64",
            fmt::format(" Name=\"{}\" NumberOfComponents=\"{}\"", field.name, field.components),
            field.values);
}

}  // namespace

void write_vtu(const GatheredMesh& gathered, std::ostream& f) {
  const InputMesh& mesh = gathered.mesh;
  const PetscInt nv = mesh.num_vertices(), nc = mesh.num_cells();
  VtuDocument doc;
  doc.text(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n"
      "<UnstructuredGrid>\n"
      "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
      nv, nc);

  doc.text("<PointData>\n");
  for (const Field& field : gathered.fields.vertex) add_field(doc, field);
  doc.text("</PointData>\n<CellData>\n");
  for (const Field& field : gathered.fields.cell) add_field(doc, field);
  if (gathered.has_cell_groups) {
    const std::vector<std::int32_t> tags(mesh.cell_tags.begin(), mesh.cell_tags.end());
    doc.array("Int32", " Name=\"physical\"", tags);
  }
  doc.text("</CellData>\n<Points>\n");

  doc.array("Float64", " NumberOfComponents=\"3\"", coordinates_in_space(mesh));
  doc.text("</Points>\n<Cells>\n");

  std::vector<std::int64_t> connectivity(mesh.cell_vertices.size());
  for (PetscInt c = 0; c < nc; ++c) {
    const CellType t = mesh.cell_types[c];
    const PetscInt* cell = mesh.cell_vertices.data() + mesh.cell_offsets[c];
    for (int i = 0; i < num_vertices(t); ++i)
      connectivity[mesh.cell_offsets[c] + i] = cell[vtk_from_canonical(t)[i]];
  }
  doc.array("Int64", " Name=\"connectivity\"", connectivity);
  const std::vector<std::int64_t> offsets(mesh.cell_offsets.begin() + 1, mesh.cell_offsets.end());
  doc.array("Int64", " Name=\"offsets\"", offsets);
  std::vector<std::uint8_t> types(nc);
  for (PetscInt c = 0; c < nc; ++c)
    types[c] = static_cast<std::uint8_t>(facts(mesh.cell_types[c]).vtk);
  doc.array("UInt8", " Name=\"types\"", types);
  doc.text("</Cells>\n</Piece>\n</UnstructuredGrid>\n");
  doc.write(f);
}

}  // namespace neomesh
