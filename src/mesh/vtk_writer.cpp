#include <cstdint>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "mesh/cell_order.hpp"
#include "mesh/mesh_writers.hpp"

namespace neomesh {

namespace {

// A FIELD section of `fields` (values written in their shortest exact form).
void write_field_data(std::ostream& f, const std::vector<Field>& fields, PetscInt tuples) {
  if (fields.empty()) return;
  fmt::print(f, "FIELD FieldData {}\n", fields.size());
  for (const Field& field : fields) {
    fmt::print(f, "{} {} {} double\n", field.name, field.components, tuples);
    for (std::size_t i = 0; i < field.values.size(); ++i)
      fmt::print(f, "{}{}", field.values[i], (i + 1) % 9 == 0 ? "\n" : " ");
    fmt::print(f, "\n");
  }
}

}  // namespace

void write_vtk(const GatheredMesh& gathered, std::ostream& f) {
  const InputMesh& mesh = gathered.mesh;
  const PetscInt nv = mesh.num_vertices(), nc = mesh.num_cells();
  fmt::print(f, "# vtk DataFile Version 4.2\nneomesh\nASCII\nDATASET UNSTRUCTURED_GRID\n");
  fmt::print(f, "POINTS {} double\n", nv);
  const std::vector<double> points = coordinates_in_space(mesh);
  for (PetscInt v = 0; v < nv; ++v)
    fmt::print(f, "{} {} {}\n", points[3 * v], points[3 * v + 1], points[3 * v + 2]);

  fmt::print(f, "CELLS {} {}\n", nc, nc + static_cast<PetscInt>(mesh.cell_vertices.size()));
  for (PetscInt c = 0; c < nc; ++c) {
    const CellType t = mesh.cell_types[c];
    const PetscInt* cell = mesh.cell_vertices.data() + mesh.cell_offsets[c];
    fmt::print(f, "{}", num_vertices(t));
    for (int i = 0; i < num_vertices(t); ++i) fmt::print(f, " {}", cell[vtk_from_canonical(t)[i]]);
    fmt::print(f, "\n");
  }
  fmt::print(f, "CELL_TYPES {}\n", nc);
  for (PetscInt c = 0; c < nc; ++c) fmt::print(f, "{}\n", facts(mesh.cell_types[c]).vtk);

  if (gathered.has_cell_groups || !gathered.fields.cell.empty()) {
    fmt::print(f, "CELL_DATA {}\n", nc);
    if (gathered.has_cell_groups) {
      fmt::print(f, "SCALARS physical int 1\nLOOKUP_TABLE default\n");
      for (PetscInt c = 0; c < nc; ++c) fmt::print(f, "{}\n", mesh.cell_tags[c]);
    }
    write_field_data(f, gathered.fields.cell, nc);
  }
  if (!gathered.fields.vertex.empty()) {
    fmt::print(f, "POINT_DATA {}\n", nv);
    write_field_data(f, gathered.fields.vertex, nv);
  }
}

}  // namespace neomesh
