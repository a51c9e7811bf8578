#include "mesh/input_mesh.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace neomesh {

InputMesh input_from_data(const MeshData& data) {
  InputMesh mesh;
  mesh.dim = data.dim;
  mesh.coords = data.coords;
  mesh.charts = data.charts;
  const int nv = num_vertices(data.cell_type);
  for (std::int64_t c = 0; c < data.num_cells(); ++c) {
    PetscInt v[8];
    for (int i = 0; i < nv; ++i) v[i] = static_cast<PetscInt>(data.cells[c * nv + i]);
    mesh.add_cell(data.cell_type, v, 0);
  }
  for (std::size_t s = 0; s < data.boundary_parts.size(); ++s) {
    VertexSet set = data.boundary_parts[s];
    if (set.tag <= 0) set.tag = static_cast<int>(s) + 1;
    mesh.groups.push_back({data.dim - 1, set.tag, set.name});
    mesh.vertex_sets.push_back(std::move(set));
  }
  std::sort(mesh.groups.begin(), mesh.groups.end(), [](const auto& a, const auto& b) {
    return std::pair(a.dim, a.tag) < std::pair(b.dim, b.tag);
  });
  return mesh;
}

void round_to_type(DataArray& array) {
  if (array.type != ValueType::Float32) return;
  for (double& v : array.values) v = static_cast<float>(v);
}

std::vector<DataArray> select_data(const std::vector<DataArray>& arrays, std::size_t count,
                                   const std::vector<std::int64_t>& kept) {
  std::vector<DataArray> out;
  for (const DataArray& a : arrays) {
    const auto k = static_cast<std::size_t>(a.components);
    if (k == 0 || a.values.size() != count * k) continue;
    DataArray selected{a.name, a.components, a.type, {}};
    selected.values.reserve(kept.size() * k);
    for (const std::int64_t i : kept)
      selected.values.insert(selected.values.end(), a.values.begin() + i * k,
                             a.values.begin() + (i + 1) * k);
    out.push_back(std::move(selected));
  }
  return out;
}

void number_used_vertices(std::vector<PetscInt>& vertex, std::span<const double> xyz,
                          const std::string& file, InputMesh& mesh) {
  std::vector<double> used;
  used.reserve(vertex.size() * 3);
  PetscInt count = 0;
  for (std::size_t n = 0; n < vertex.size(); ++n) {
    if (vertex[n] < 0) continue;
    vertex[n] = count++;
    used.insert(used.end(), xyz.begin() + 3 * n, xyz.begin() + 3 * n + 3);
  }
  if (mesh.dim == 3) {
    mesh.coords = std::move(used);
  } else if (auto plane = PlaneEmbedding::fit(used, mesh.coords, file)) {
    if (!plane->is_xy()) mesh.plane = std::make_shared<const PlaneEmbedding>(std::move(*plane));
  } else {
    mesh.surface = true;
    mesh.coords = std::move(used);
  }
}

std::vector<double> coordinates_in_space(const InputMesh& mesh) {
  if (mesh.dim == 2 && mesh.plane) return mesh.plane->to_space(mesh.coords);
  if (mesh.surface) return mesh.coords;
  std::vector<double> xyz(3 * static_cast<std::size_t>(mesh.num_vertices()), 0.0);
  for (PetscInt v = 0; v < mesh.num_vertices(); ++v)
    std::copy_n(mesh.coords.begin() + v * mesh.dim, mesh.dim, xyz.begin() + 3 * v);
  return xyz;
}

std::string describe_cell(const InputMesh& mesh, PetscInt c) {
  if (c >= 0 && c < static_cast<PetscInt>(mesh.element_tag.size()))
    return fmt::format("cell {} (0-based; element {} of the file)", c, mesh.element_tag[c]);
  return fmt::format("cell {} (0-based)", c);
}

}  // namespace neomesh
