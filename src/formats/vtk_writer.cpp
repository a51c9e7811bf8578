#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "formats/mesh_writers.hpp"
#include "mesh/cell_order.hpp"

namespace neomesh {

namespace {

// A name as VTK's legacy writer writes it: no spaces, "%XX" for them and other special
// characters (the reader decodes them).
std::string encoded(std::string_view name) {
  std::string out;
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (u <= ' ' || u >= 127 || c == '%')
      out += fmt::format("%{:02X}", u);
    else
      out += c;
  }
  return out.empty() ? "%00" : out;
}

const char* legacy_type(ValueType type) {
  constexpr const char* names[] = {"char",  "unsigned_char", "short",        "unsigned_short",
                                   "int",   "unsigned_int",  "vtktypeint64", "vtktypeuint64",
                                   "float", "double"};
  return names[static_cast<int>(type)];
}

// The values of an array in its type, shortest exact form, nine per line.
void write_values(std::ostream& f, const std::vector<double>& values, ValueType type) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double v = values[i];
    if (type == ValueType::Float64)
      fmt::print(f, "{}", v);
    else if (type == ValueType::Float32)
      fmt::print(f, "{}", static_cast<float>(v));
    else if (type == ValueType::UInt64)  // clamped: 2^64 - 1 is 2^64 as a double
      fmt::print(f, "{}", !(v > 0) ? 0 : v >= 0x1p64 ? ~std::uint64_t{0} : std::uint64_t(v));
    else  // the values of an integer array: integers well within Int64
      fmt::print(f, "{}", std::abs(v) < 0x1p63 ? static_cast<std::int64_t>(v) : 0);
    fmt::print(f, "{}", (i + 1) % 9 == 0 ? "\n" : " ");
  }
  fmt::print(f, "\n");
}

// A FIELD section of the input's arrays and neomesh's fields, `tuples` each (cell data: the
// cells' values, then 0 for facets and points: VTK's legacy reader reads no "nan").
void write_field_data(std::ostream& f, const std::vector<DataArray>& data,
                      const std::vector<Field>& fields, PetscInt tuples) {
  if (data.empty() && fields.empty()) return;
  fmt::print(f, "FIELD FieldData {}\n", data.size() + fields.size());
  for (const DataArray& a : data) {
    fmt::print(f, "{} {} {} {}\n", encoded(a.name), a.components, tuples, legacy_type(a.type));
    write_values(f, per_element(a.values, a.components, 0.0, tuples), a.type);
  }
  for (const Field& field : fields) {
    fmt::print(f, "{} {} {} double\n", encoded(field.name), field.components, tuples);
    write_values(f, per_element(field.values, field.components, 0.0, tuples), ValueType::Float64);
  }
}

}  // namespace

void write_vtk(const GatheredMesh& gathered, std::ostream& f) {
  const InputMesh& mesh = gathered.mesh;
  const VtkElements e = vtk_elements(gathered, false);
  const PetscInt nv = mesh.num_points();
  const auto nc = static_cast<PetscInt>(e.size());
  fmt::print(f, "# vtk DataFile Version 4.2\nneomesh\nASCII\nDATASET UNSTRUCTURED_GRID\n");
  const auto named = std::count_if(mesh.groups.begin(), mesh.groups.end(),
                                   [](const PhysicalGroup& g) { return !g.name.empty(); });
  if (named > 0) {
    fmt::print(f, "FIELD FieldData {}\n", named);
    for (const PhysicalGroup& g : mesh.groups)
      if (!g.name.empty()) fmt::print(f, "{} 1 2 int\n{} {}\n", encoded(g.name), g.tag, g.dim);
  }
  fmt::print(f, "POINTS {} double\n", nv);
  const std::vector<double> points = points_in_space(mesh);
  for (PetscInt v = 0; v < nv; ++v)
    fmt::print(f, "{} {} {}\n", points[3 * v], points[3 * v + 1], points[3 * v + 2]);

  fmt::print(f, "CELLS {} {}\n", nc, nc + static_cast<PetscInt>(e.connectivity.size()));
  for (PetscInt c = 0; c < nc; ++c) {
    const std::int64_t first = c == 0 ? 0 : e.offsets[c - 1];
    fmt::print(f, "{}", e.offsets[c] - first);
    for (std::int64_t i = first; i < e.offsets[c]; ++i) fmt::print(f, " {}", e.connectivity[i]);
    fmt::print(f, "\n");
  }
  fmt::print(f, "CELL_TYPES {}\n", nc);
  for (PetscInt c = 0; c < nc; ++c) fmt::print(f, "{}\n", e.types[c]);

  if (e.has_tags || !mesh.cell_data.empty() || !gathered.fields.cell.empty()) {
    fmt::print(f, "CELL_DATA {}\n", nc);
    if (e.has_tags) {
      fmt::print(f, "SCALARS physical int 1\nLOOKUP_TABLE default\n");
      for (PetscInt c = 0; c < nc; ++c) fmt::print(f, "{}\n", e.tags[c]);
    }
    write_field_data(f, mesh.cell_data, gathered.fields.cell, nc);
  }
  if (!mesh.point_data.empty() || !gathered.fields.vertex.empty()) {
    fmt::print(f, "POINT_DATA {}\n", nv);
    write_field_data(f, mesh.point_data, gathered.fields.vertex, nv);
  }
}

}  // namespace neomesh
