#include <fmt/ostream.h>

#include "mesh/cell_order.hpp"
#include "mesh/mesh_writers.hpp"

namespace neomesh {

namespace {

void write_field(std::ostream& f, const Field& field) {
  fmt::print(
      f, "<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n",
      field.name, field.components);
  for (std::size_t i = 0; i < field.values.size(); i += field.components) {
    for (int c = 0; c < field.components; ++c)
      fmt::print(f, "{}{:.17g}", c ? " " : "", field.values[i + c]);
    fmt::print(f, "\n");
  }
  fmt::print(f, "</DataArray>\n");
}

}  // namespace

void write_vtu(const GatheredMesh& gathered, std::ostream& f) {
  const InputMesh& mesh = gathered.mesh;
  fmt::print(f,
             "<?xml version=\"1.0\"?>\n"
             "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
             "<UnstructuredGrid>\n"
             "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
             mesh.num_vertices(), mesh.num_cells());

  fmt::print(f, "<PointData>\n");
  for (const Field& field : gathered.fields.vertex) write_field(f, field);
  fmt::print(f, "</PointData>\n<CellData>\n");
  for (const Field& field : gathered.fields.cell) write_field(f, field);
  if (gathered.has_cell_groups) {
    fmt::print(f, "<DataArray type=\"Int32\" Name=\"physical\" format=\"ascii\">\n");
    for (int tag : mesh.cell_tags) fmt::print(f, "{}\n", tag);
    fmt::print(f, "</DataArray>\n");
  }
  fmt::print(f, "</CellData>\n");

  fmt::print(f,
             "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for (PetscInt v = 0; v < mesh.num_vertices(); ++v) {
    const double* x = mesh.coords.data() + v * mesh.dim;
    fmt::print(f, "{:.17g} {:.17g} {:.17g}\n", x[0], x[1], mesh.dim == 3 ? x[2] : 0.0);
  }
  fmt::print(f, "</DataArray>\n</Points>\n<Cells>\n");

  fmt::print(f, "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    const CellType t = mesh.cell_types[c];
    const PetscInt* cell = mesh.cell_vertices.data() + mesh.cell_offsets[c];
    for (int i = 0; i < num_vertices(t); ++i)
      fmt::print(f, "{}{}", i ? " " : "", cell[gmsh_from_canonical(t)[i]]);
    fmt::print(f, "\n");
  }
  fmt::print(f, "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) fmt::print(f, "{}\n", mesh.cell_offsets[c + 1]);
  fmt::print(f, "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (CellType t : mesh.cell_types) fmt::print(f, "{}\n", facts(t).vtk);
  fmt::print(f, "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
}

}  // namespace neomesh
