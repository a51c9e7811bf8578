#include "generate/serial_view.hpp"

#include <numeric>

#include "generate/generate.hpp"
#include "mesh/boundary_surface.hpp"

namespace neomesh {

MeshView serial_view(const MeshData& mesh) {
  MeshView view;
  view.dim = mesh.dim;
  view.num_vertices = static_cast<PetscInt>(mesh.num_vertices());
  view.num_cells = static_cast<PetscInt>(mesh.num_cells());
  view.coords = mesh.coords;

  CellBlock block;
  block.type = mesh.cell_type;
  block.vertices.assign(mesh.cells.begin(), mesh.cells.end());
  view.blocks.push_back(std::move(block));

  view.owned.assign(view.num_vertices, 1);
  view.on_boundary = boundary_vertices(mesh);
  view.boundary_part.assign(view.num_vertices, -1);
  view.part_count.assign(view.num_vertices, 0);
  for (std::size_t p = 0; p < mesh.boundary_parts.size(); ++p) {
    const VertexSet& part = mesh.boundary_parts[p];
    view.parts.push_back({part.name, part.tag});
    for (std::int64_t v : part.vertices) {
      if (view.boundary_part[v] < 0) view.boundary_part[v] = static_cast<int>(p);
      ++view.part_count[v];
    }
  }
  view.global_cell.resize(view.num_cells);
  std::iota(view.global_cell.begin(), view.global_cell.end(), PetscInt{0});
  view.input_vertex.resize(view.num_vertices);
  std::iota(view.input_vertex.begin(), view.input_vertex.end(), PetscInt{0});
  InputMesh input = input_from_data(mesh);
  const FacetTable table(input);
  const InputTopology topology = input_topology(input, table, "serial view");
  view.boundary = std::make_shared<const BoundarySurface>(boundary_surface(input, table, topology));
  return view;
}

}  // namespace neomesh
