// Generators on a structured lattice (the moved-midpoint cases, the random square, the
// boxes), plus rotation and boundary detection for any MeshData.
#include "generate/generate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <unordered_set>

#include "core/error.hpp"

namespace neomesh {

namespace {

using Index = std::array<int, 3>;

// Vertex (i, j[, k]) of a lattice with n cells per direction.
std::int64_t lattice_vertex(int dim, int n, const Index& ijk) {
  std::int64_t v = 0;
  for (int d = dim - 1; d >= 0; --d) v = v * (n + 1) + ijk[d];
  return v;
}

// n^dim quads/hexes in tensor order on a lattice whose vertex (i, j[, k]) sits at
// `place(ijk, x)`; the sides i = 0, i = n, j = 0, ... become the boundary parts.
MeshData lattice_mesh(int dim, int n, const std::function<void(const Index&, double*)>& place) {
  if (n < 1) fail("a mesh needs at least 1 cell per direction (got {})", n);
  MeshData mesh;
  mesh.dim = dim;
  mesh.cell_type = dim == 2 ? CellType::Quadrilateral : CellType::Hexahedron;
  const int nk = dim == 3 ? n + 1 : 1;
  mesh.coords.resize(static_cast<std::size_t>(n + 1) * (n + 1) * nk * dim);
  for (int k = 0; k < nk; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const Index ijk{i, j, k};
        place(ijk, mesh.coords.data() + dim * lattice_vertex(dim, n, ijk));
      }

  const int corners = 1 << dim;
  for (int k = 0; k < (dim == 3 ? n : 1); ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int l = 0; l < corners; ++l)
          mesh.cells.push_back(
              lattice_vertex(dim, n, {i + (l & 1), j + ((l >> 1) & 1), k + ((l >> 2) & 1)}));

  static constexpr std::array<const char*, 6> side_names = {"left", "right", "bottom",
                                                            "top",  "front", "back"};
  for (int side = 0; side < 2 * dim; ++side) {
    VertexSet part{side_names[side], side + 1, {}, {}};
    const int axis = side / 2, fixed = side % 2 ? n : 0;
    for (int k = 0; k < nk; ++k)
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
          const Index ijk{i, j, k};
          if (ijk[axis] == fixed) part.vertices.push_back(lattice_vertex(dim, n, ijk));
        }
    mesh.boundary_parts.push_back(std::move(part));
  }
  return mesh;
}

// The moved-midpoint meshes: a 2^dim coarse lattice whose points are `coarse(a)` (a_j ∈
// {0,1,2}), each coarse cell subdivided as the multilinear image of a uniform (n/2)^dim grid.
MeshData moved_midpoint(int dim, int n, const std::function<void(const Index&, double*)>& coarse) {
  if (n < 2 || n % 2 != 0)
    fail("the moved-midpoint meshes need an even number of cells per direction (got {})", n);
  const int m = n / 2;
  return lattice_mesh(dim, n, [&](const Index& ijk, double* x) {
    Index cell{};
    std::array<double, 3> s{};
    for (int d = 0; d < dim; ++d) {
      cell[d] = std::min(ijk[d] / m, 1);
      s[d] = static_cast<double>(ijk[d] - cell[d] * m) / m;
    }
    for (int d = 0; d < dim; ++d) x[d] = 0.0;
    for (int l = 0; l < (1 << dim); ++l) {
      double weight = 1.0;
      Index corner{};
      for (int d = 0; d < dim; ++d) {
        const bool upper = (l >> d) & 1;
        weight *= upper ? s[d] : 1.0 - s[d];
        corner[d] = cell[d] + upper;
      }
      std::array<double, 3> p{};
      coarse(corner, p.data());
      for (int d = 0; d < dim; ++d) x[d] += weight * p[d];
    }
  });
}

// Uniform in [0, 1) from 32 random bits: the same numbers on every standard library.
double uniform01(std::mt19937& random) {
  return random() * 0x1p-32;
}

double simplex_det(const MeshData& mesh, const std::int64_t* cell) {
  const int d = mesh.dim;
  auto x = [&](int i, int c) {
    return mesh.coords[d * cell[i] + c] - mesh.coords[d * cell[0] + c];
  };
  if (d == 2) return x(1, 0) * x(2, 1) - x(1, 1) * x(2, 0);
  return x(1, 0) * (x(2, 1) * x(3, 2) - x(2, 2) * x(3, 1)) -
         x(1, 1) * (x(2, 0) * x(3, 2) - x(2, 2) * x(3, 0)) +
         x(1, 2) * (x(2, 0) * x(3, 1) - x(2, 1) * x(3, 0));
}

// Splits every quad/hex of a lattice mesh into simplices that share the diagonal from local
// vertex 0 to the opposite one (Kuhn's triangulation), so neighbouring cells' facets match.
void split_into_simplices(MeshData& mesh) {
  const int dim = mesh.dim;
  const int corners = 1 << dim;
  std::vector<std::vector<int>> pieces;
  if (dim == 2) {
    pieces = {{0, 1, 3}, {0, 3, 2}};
  } else {
    std::array<int, 3> axes{0, 1, 2};
    do {
      pieces.push_back({0, 1 << axes[0], (1 << axes[0]) | (1 << axes[1]), 7});
    } while (std::next_permutation(axes.begin(), axes.end()));
  }
  std::vector<std::int64_t> simplices;
  for (std::size_t c = 0; c * corners < mesh.cells.size(); ++c)
    for (const auto& piece : pieces)
      for (int l : piece) simplices.push_back(mesh.cells[c * corners + l]);
  mesh.cells = std::move(simplices);
  mesh.cell_type = dim == 2 ? CellType::Triangle : CellType::Tetrahedron;
  // Half of Kuhn's tets are negatively oriented; swapping two vertices fixes that.
  for (std::size_t c = 0; c * (dim + 1) < mesh.cells.size(); ++c) {
    std::int64_t* cell = mesh.cells.data() + c * (dim + 1);
    if (simplex_det(mesh, cell) < 0) std::swap(cell[dim - 1], cell[dim]);
  }
}

}  // namespace

MeshData square_midpoint(int cells_per_direction) {
  return moved_midpoint(2, cells_per_direction, [](const Index& a, double* p) {
    const bool centre = a[0] == 1 && a[1] == 1;
    for (int d = 0; d < 2; ++d) p[d] = centre ? 0.26 : 0.5 * a[d];
  });
}

MeshData cube_midpoint(int cells_per_direction) {
  return moved_midpoint(3, cells_per_direction, [](const Index& a, double* p) {
    const bool centre = a[0] == 1 && a[1] == 1 && a[2] == 1;
    for (int d = 0; d < 3; ++d) p[d] = centre ? 1.2 : a[d];
  });
}

MeshData square_random(int cells_per_direction, double amplitude, unsigned seed) {
  const int n = cells_per_direction;
  MeshData mesh = lattice_mesh(2, n, [n](const Index& ijk, double* x) {
    for (int d = 0; d < 2; ++d) x[d] = static_cast<double>(ijk[d]) / n;
  });
  jitter(mesh, 1.0 / n, amplitude, seed);
  return mesh;
}

// Splits every hex of a lattice mesh into the two wedges on either side of its vertical
// diagonal plane through local vertices 0, 3, 4, 7 (the same plane in every cube, so faces
// match): bottom triangles 0 1 3 and 0 3 2, counter-clockwise seen from above.
void split_into_wedges(MeshData& mesh) {
  constexpr int kPieces[2][6] = {{0, 1, 3, 4, 5, 7}, {0, 3, 2, 4, 7, 6}};
  std::vector<std::int64_t> wedges;
  for (std::size_t c = 0; c * 8 < mesh.cells.size(); ++c)
    for (const auto& piece : kPieces)
      for (int l : piece) wedges.push_back(mesh.cells[c * 8 + l]);
  mesh.cells = std::move(wedges);
  mesh.cell_type = CellType::Wedge;
}

// Splits every hex of a lattice mesh into six pyramids, one on each face with a new vertex at
// the centre of the hex as their apex. The base of each is the face seen from the apex:
// the hexahedron's outward facet cycle a b c d reversed, in tensor order a d b c.
void split_into_pyramids(MeshData& mesh) {
  const CellFacts& hex = facts(CellType::Hexahedron);
  std::vector<std::int64_t> pyramids;
  for (std::size_t c = 0; c * 8 < mesh.cells.size(); ++c) {
    const std::int64_t* cell = mesh.cells.data() + c * 8;
    const std::int64_t apex = mesh.num_vertices();
    for (int d = 0; d < 3; ++d) {
      double centre = 0.0;
      for (int i = 0; i < 8; ++i) centre += mesh.coords[3 * cell[i] + d] / 8.0;
      mesh.coords.push_back(centre);
    }
    for (int f = 0; f < hex.num_facets; ++f) {
      const auto& v = hex.facets[f].vertices;
      for (int l : {v[0], v[3], v[1], v[2]}) pyramids.push_back(cell[l]);
      pyramids.push_back(apex);
    }
  }
  mesh.cells = std::move(pyramids);
  mesh.cell_type = CellType::Pyramid;
}

MeshData box(CellType type, int cells_per_direction) {
  const int dim = dimension(type), n = cells_per_direction;
  MeshData mesh = lattice_mesh(dim, n, [dim, n](const Index& ijk, double* x) {
    for (int d = 0; d < dim; ++d) x[d] = -1.0 + 2.0 * ijk[d] / n;
  });
  if (is_simplex(type)) split_into_simplices(mesh);
  if (type == CellType::Wedge) split_into_wedges(mesh);
  if (type == CellType::Pyramid) split_into_pyramids(mesh);
  return mesh;
}

MeshData quarter_annulus(CellType type, int cells_per_direction) {
  if (type == CellType::Wedge || type == CellType::Pyramid)
    fail("quarter annulus: quadrilaterals, triangles, hexahedra or tetrahedra only");
  const int dim = dimension(type), n = cells_per_direction;
  // (i, j, k) → (r, θ, z): i across, j around, k up; a positive Jacobian (r > 0).
  MeshData mesh = lattice_mesh(dim, n, [dim, n](const Index& ijk, double* x) {
    const double r = 1.0 + static_cast<double>(ijk[0]) / n;
    const double theta = 0.5 * std::numbers::pi * ijk[1] / n;
    x[0] = r * std::cos(theta);
    x[1] = r * std::sin(theta);
    if (dim == 3) x[2] = static_cast<double>(ijk[2]) / n;
  });
  static constexpr std::array<const char*, 6> names = {"inner", "outer",  "start",
                                                       "end",   "bottom", "top"};
  for (std::size_t p = 0; p < mesh.boundary_parts.size(); ++p)
    mesh.boundary_parts[p].name = names[p];
  if (is_simplex(type)) split_into_simplices(mesh);
  return mesh;
}

MeshData ring(CellType type, int angular, int radial, double bunching) {
  if (type == CellType::Tetrahedron) fail("ring: no tetrahedral version");
  if (angular < 3 || radial < 1) fail("ring: needs at least 3 cells around and 1 across");
  if (!(bunching >= 1.0)) fail("ring: bunching must be at least 1 (got {})", bunching);
  const int dim = dimension(type), layers = dim == 3 ? radial : 0;
  const double a = (bunching - 1.0) / (bunching + 1.0);  // (1 + a) / (1 - a) = bunching
  MeshData mesh;
  mesh.dim = dim;
  mesh.cell_type = type;
  // Vertex (i around, j across, k up).
  auto vertex = [&](int i, int j, int k) -> std::int64_t {
    return (static_cast<std::int64_t>(k) * (radial + 1) + j) * angular + (i % angular);
  };
  for (int k = 0; k <= layers; ++k)
    for (int j = 0; j <= radial; ++j)
      for (int i = 0; i < angular; ++i) {
        const double s = static_cast<double>(i) / angular;
        const double theta = 2 * std::numbers::pi * s + a * std::sin(2 * std::numbers::pi * s);
        const double r = 0.5 + 0.5 * j / radial;
        mesh.coords.push_back(r * std::cos(theta));
        mesh.coords.push_back(r * std::sin(theta));
        if (dim == 3) mesh.coords.push_back(0.5 * k / layers);
      }
  // Tensor order with ξ0 across, ξ1 around (and ξ2 up): positively oriented.
  for (int k = 0; k < std::max(layers, 1); ++k)
    for (int j = 0; j < radial; ++j)
      for (int i = 0; i < angular; ++i) {
        std::int64_t v[8];
        for (int corner = 0; corner < (dim == 3 ? 8 : 4); ++corner)
          v[corner] = vertex(i + ((corner >> 1) & 1), j + (corner & 1), k + ((corner >> 2) & 1));
        if (type == CellType::Triangle)
          mesh.cells.insert(mesh.cells.end(), {v[0], v[1], v[3], v[0], v[3], v[2]});
        else
          mesh.cells.insert(mesh.cells.end(), v, v + (dim == 3 ? 8 : 4));
      }
  auto part = [&](const char* name, auto&& on) {
    VertexSet set{name, static_cast<int>(mesh.boundary_parts.size()) + 1, {}, {}};
    for (int k = 0; k <= layers; ++k)
      for (int j = 0; j <= radial; ++j)
        for (int i = 0; i < angular; ++i)
          if (on(j, k)) set.vertices.push_back(vertex(i, j, k));
    mesh.boundary_parts.push_back(std::move(set));
  };
  part("inner", [](int j, int) { return j == 0; });
  part("outer", [&](int j, int) { return j == radial; });
  if (dim == 3) {
    part("bottom", [](int, int k) { return k == 0; });
    part("top", [&](int, int k) { return k == layers; });
  }
  return mesh;
}

void jitter(MeshData& mesh, double h, double amplitude, unsigned seed) {
  // Corner Jacobians of quads and triangles stay positive while every edge vector is off by
  // less than h/2; larger amplitudes fold cells over (test meshes for untangling).
  if (!(amplitude >= 0.0 && amplitude < 1.0))
    fail("the random displacement amplitude must be in [0, 1) (got {})", amplitude);
  const std::vector<std::uint8_t> on_boundary = boundary_vertices(mesh);
  std::mt19937 random(seed);
  for (std::int64_t v = 0; v < mesh.num_vertices(); ++v) {
    if (on_boundary[v]) continue;
    for (int d = 0; d < mesh.dim; ++d)
      mesh.coords[mesh.dim * v + d] += amplitude * h * (2.0 * uniform01(random) - 1.0);
  }
}

void rotate(MeshData& mesh, double degrees) {
  const double angle = degrees * std::numbers::pi / 180.0;
  const double c = std::cos(angle), s = std::sin(angle);
  for (std::size_t v = 0; v < mesh.coords.size(); v += mesh.dim) {
    const double x = mesh.coords[v], y = mesh.coords[v + 1];
    mesh.coords[v] = c * x - s * y;
    mesh.coords[v + 1] = s * x + c * y;
  }
}

std::vector<std::uint8_t> boundary_vertices(const MeshData& mesh) {
  // A facet seen a second time is interior and dropped at once, so the set only holds the
  // facets between visited and unvisited cells plus the boundary: small for ordered meshes.
  using Facet = std::array<std::int64_t, 4>;  // sorted vertices, -1 for unused entries
  struct FacetHash {
    std::size_t operator()(const Facet& f) const {
      std::size_t h = 0;
      for (std::int64_t v : f) h = h * 0x9E3779B97F4A7C15ull + static_cast<std::size_t>(v);
      return h;
    }
  };
  std::unordered_set<Facet, FacetHash> open;
  const int nv = num_vertices(mesh.cell_type);
  const CellFacts& cell = facts(mesh.cell_type);
  for (std::int64_t c = 0; c < mesh.num_cells(); ++c)
    for (int f = 0; f < cell.num_facets; ++f) {
      const FacetVertices& local = cell.facets[f];
      Facet facet{-1, -1, -1, -1};
      for (int i = 0; i < local.size; ++i) facet[i] = mesh.cells[c * nv + local.vertices[i]];
      std::sort(facet.begin(), facet.end());
      if (auto [it, inserted] = open.insert(facet); !inserted) open.erase(it);
    }
  std::vector<std::uint8_t> on_boundary(mesh.num_vertices(), 0);
  for (const Facet& facet : open)
    for (std::int64_t v : facet)
      if (v >= 0) on_boundary[v] = 1;
  return on_boundary;
}

}  // namespace neomesh
