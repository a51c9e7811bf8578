#include "mesh/input_mesh.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"

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

int curved_cell_points(const InputMesh& mesh, PetscInt c, PetscInt* points) {
  const HighOrderNodes& h = mesh.high_order;
  const CellType linear = mesh.cell_types[c];
  const int corners = num_vertices(linear);
  const PetscInt* v = mesh.cell_vertices.data() + mesh.cell_offsets[c];
  for (int i = 0; i < corners; ++i) points[i] = v[facts(linear).gmsh_order[i]];
  int n = corners;
  for (PetscInt k = h.offsets[c]; k < h.offsets[c + 1]; ++k)
    points[n++] = mesh.num_vertices() + h.nodes[k];
  return n;
}

void number_high_order_nodes(std::vector<PetscInt>& node, const std::vector<PetscInt>& vertex,
                             std::span<const double> xyz, const std::string& file,
                             InputMesh& mesh) {
  for (std::size_t n = 0; n < node.size(); ++n) {
    if (node[n] < 0) continue;
    if (vertex[n] >= 0)
      fail("{}: node {} is a corner of one element and a mid-edge, face or centre node of another",
           file, n + 1);
    node[n] = mesh.high_order.num_nodes();
    mesh.high_order.xyz.insert(mesh.high_order.xyz.end(), xyz.begin() + 3 * n,
                               xyz.begin() + 3 * n + 3);
  }
}

CurvedFacets::CurvedFacets(const InputMesh& mesh) : mesh_(mesh) {
  if (!mesh.curved() || mesh.facets.size() == 0) return;
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    PetscInt p[kMaxCurvedNodes];
    curved_cell_points(mesh, c, p);
    nodes_.add_cell(mesh.high_order.types[c], p);
  }
}

int CurvedFacets::points(PetscInt k, PetscInt* out) const {
  const TaggedEntities& facets = mesh_.facets;
  const PetscInt* v = facets.vertices.data() + facets.offsets[k];
  const int n = static_cast<int>(facets.offsets[k + 1] - facets.offsets[k]);
  std::copy(v, v + n, out);
  if (nodes_.empty()) return n;
  int count = n;
  for (int i = 0; i < (n == 2 ? 1 : n); ++i) {
    const PetscInt node = nodes_.find(std::array{v[i], v[(i + 1) % n]});
    if (node < 0) return n;
    out[count++] = node;
  }
  if (n == 4)
    if (const PetscInt node = nodes_.find(std::span(v, 4)); node >= 0) out[count++] = node;
  return count;
}

std::vector<double> curved_point_coordinates(const InputMesh& mesh) {
  std::vector<double> x = mesh.coords;
  const int d = mesh.coord_dim();
  x.reserve(x.size() + d * mesh.high_order.num_nodes());
  for (PetscInt n = 0; n < mesh.high_order.num_nodes(); ++n) {
    const double* xyz = mesh.high_order.xyz.data() + 3 * n;
    if (d == 3) {
      x.insert(x.end(), xyz, xyz + 3);
    } else {
      const auto uv = mesh.plane ? mesh.plane->to_plane(xyz) : std::array{xyz[0], xyz[1]};
      x.insert(x.end(), uv.begin(), uv.end());
    }
  }
  return x;
}

void set_high_order_coordinates(HighOrderNodes& nodes, int dim, const PlaneEmbedding* plane,
                                std::span<const double> x) {
  if (x.size() != static_cast<std::size_t>(dim * nodes.num_nodes()))
    fail("internal error: {} coordinates for {} high-order nodes", x.size(), nodes.num_nodes());
  if (dim == 3)
    std::copy(x.begin(), x.end(), nodes.xyz.begin());
  else if (plane)
    nodes.xyz = plane->to_space(x);
  else
    for (PetscInt n = 0; n < nodes.num_nodes(); ++n)
      std::copy_n(x.begin() + 2 * n, 2, nodes.xyz.begin() + 3 * n);
}

void set_curved_point_coordinates(InputMesh& mesh, std::span<const double> x) {
  const std::size_t corners = mesh.coords.size();
  if (mesh.surface || x.size() < corners) fail("internal error: curved points of a surface mesh");
  std::copy_n(x.begin(), corners, mesh.coords.begin());
  set_high_order_coordinates(mesh.high_order, mesh.dim, mesh.plane.get(), x.subspan(corners));
}

std::vector<double> points_in_space(const InputMesh& mesh) {
  std::vector<double> xyz = coordinates_in_space(mesh);
  xyz.insert(xyz.end(), mesh.high_order.xyz.begin(), mesh.high_order.xyz.end());
  return xyz;
}

void check_high_order_nodes(const InputMesh& mesh, const std::string& file) {
  if (!mesh.curved()) return;
  for (double x : mesh.high_order.xyz)
    if (!std::isfinite(x))
      fail("{}: a node of a second-order cell has a non-finite coordinate ({})", file, x);
  if (mesh.surface)
    fail(
        "{}: is a curved surface mesh (second-order 2D cells off one plane); neomesh reads curved "
        "cells in a plane or in 3D only",
        file);
  if (mesh.dim == 3) return;
  const std::vector<double> space = coordinates_in_space(mesh);
  double size = 0;  // the vertices' extent
  for (int k = 0; k < 3; ++k) {
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t i = k; i < space.size(); i += 3) {
      lo = std::min(lo, space[i]);
      hi = std::max(hi, space[i]);
    }
    size = std::max(size, hi - lo);
  }
  const PlaneEmbedding xy;
  const PlaneEmbedding& plane = mesh.plane ? *mesh.plane : xy;
  for (PetscInt n = 0; n < mesh.high_order.num_nodes(); ++n)
    if (plane.distance(mesh.high_order.xyz.data() + 3 * n) >
        PlaneEmbedding::kPlanarTolerance * size)
      fail(
          "{}: is a curved surface mesh (a node of a second-order cell lies off the plane {} of "
          "the vertices); neomesh reads curved cells in a plane or in 3D only",
          file, plane.describe());
}

std::string describe_cell(const InputMesh& mesh, PetscInt c) {
  if (c >= 0 && c < static_cast<PetscInt>(mesh.element_tag.size()))
    return fmt::format("cell {} (0-based; element {} of the file)", c, mesh.element_tag[c]);
  return fmt::format("cell {} (0-based)", c);
}

}  // namespace neomesh
