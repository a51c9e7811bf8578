#include "mesh/generate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "mesh/serial_view.hpp"

namespace neomesh {

namespace {

double coord(const MeshData& m, std::int64_t v, int d) {
  return m.coords[m.dim * v + d];
}

// Smallest determinant of the corner Jacobians (edge vectors along the reference axes at each
// Q1 corner; the edge matrix for simplices), over all cells.
double min_corner_det(const MeshData& m) {
  const int nv = num_vertices(m.cell_type), dim = m.dim;
  double smallest = INFINITY;
  for (std::int64_t c = 0; c < m.num_cells(); ++c) {
    const std::int64_t* cell = m.cells.data() + c * nv;
    for (int corner = 0; corner < (is_simplex(m.cell_type) ? 1 : nv); ++corner) {
      double e[3][3];
      for (int j = 0; j < dim; ++j) {
        // Simplex: columns x_{j+1} - x_0. Q1: from the corner to its neighbour along axis j,
        // signed so that the columns point in the reference axes' directions.
        const int a = is_simplex(m.cell_type) ? 0 : corner;
        const int b = is_simplex(m.cell_type) ? j + 1 : corner ^ (1 << j);
        const double sign = (!is_simplex(m.cell_type) && ((corner >> j) & 1)) ? -1.0 : 1.0;
        for (int d = 0; d < dim; ++d)
          e[d][j] = sign * (coord(m, cell[b], d) - coord(m, cell[a], d));
      }
      const double det = dim == 2 ? e[0][0] * e[1][1] - e[0][1] * e[1][0]
                                  : e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                                        e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                                        e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
      smallest = std::min(smallest, det);
    }
  }
  return smallest;
}

std::int64_t find_vertex(const MeshData& m, std::initializer_list<double> x) {
  for (std::int64_t v = 0; v < m.num_vertices(); ++v) {
    double dist = 0;
    int d = 0;
    for (double xd : x) dist += std::abs(coord(m, v, d++) - xd);
    if (dist < 1e-12) return v;
  }
  return -1;
}

const VertexSet& part(const MeshData& m, const std::string& name) {
  for (const auto& p : m.boundary_parts)
    if (p.name == name) return p;
  throw std::runtime_error("no boundary part " + name);
}

// Every vertex flagged by boundary_vertices is in some part, and every part vertex is flagged.
void expect_parts_cover_boundary(const MeshData& m) {
  const auto on_boundary = boundary_vertices(m);
  std::vector<int> in_part(m.num_vertices(), 0);
  for (const auto& p : m.boundary_parts)
    for (std::int64_t v : p.vertices) in_part[v] = 1;
  for (std::int64_t v = 0; v < m.num_vertices(); ++v)
    EXPECT_EQ(in_part[v], on_boundary[v]) << "vertex " << v;
}

}  // namespace

TEST(SquareMidpoint, Table51MeshHas256QuadsAndTheMovedMidpoint) {
  const MeshData m = square_midpoint(16);
  EXPECT_EQ(m.cell_type, CellType::Quadrilateral);
  EXPECT_EQ(m.num_cells(), 256);
  EXPECT_EQ(m.num_vertices(), 289);
  EXPECT_GE(find_vertex(m, {0.26, 0.26}), 0);
  EXPECT_LT(find_vertex(m, {0.5, 0.5}), 0);
  EXPECT_GT(min_corner_det(m), 0.0);
  // Coarse edge midpoints stay; the fine grid is bilinear in each coarse quad.
  EXPECT_GE(find_vertex(m, {0.5, 0.0}), 0);
  EXPECT_GE(find_vertex(m, {0.19, 0.19}), 0);  // (4, 4): mean of the coarse corners
  // Vertex (12, 4): in the coarse quad [centre, (1, 0.5)] at s = (1/2, 1/2).
  EXPECT_GE(find_vertex(m, {(0.26 + 0.5 + 1.0 + 1.0) / 4, (0.26 + 0.0 + 0.5 + 0.0) / 4}), 0);
}

TEST(SquareMidpoint, BoundaryVerticesLieOnTheSquare) {
  const MeshData m = square_midpoint(8);
  const auto on_boundary = boundary_vertices(m);
  int count = 0;
  for (std::int64_t v = 0; v < m.num_vertices(); ++v) {
    const double x = coord(m, v, 0), y = coord(m, v, 1);
    const bool on_square = x == 0.0 || x == 1.0 || y == 0.0 || y == 1.0;
    EXPECT_EQ(on_boundary[v] != 0, on_square) << x << " " << y;
    count += on_boundary[v];
  }
  EXPECT_EQ(count, 32);
  for (std::int64_t v : part(m, "left").vertices) EXPECT_EQ(coord(m, v, 0), 0.0);
  for (std::int64_t v : part(m, "top").vertices) EXPECT_EQ(coord(m, v, 1), 1.0);
  expect_parts_cover_boundary(m);
}

TEST(SquareMidpoint, RejectsOddCellCounts) {
  EXPECT_THROW(square_midpoint(3), Error);
}

TEST(SerialView, HoldsTheWholeMeshWithBoundaryParts) {
  const MeshData m = square_midpoint(4);
  const MeshView view = serial_view(m);
  EXPECT_EQ(view.num_cells, 16);
  EXPECT_EQ(view.num_vertices, 25);
  ASSERT_EQ(view.blocks.size(), 1u);
  EXPECT_EQ(view.blocks[0].size(), 16);
  EXPECT_EQ(view.blocks[0].cell(5)[3], m.cells[5 * 4 + 3]);
  EXPECT_EQ(view.coords, m.coords);
  EXPECT_EQ(std::count(view.owned.begin(), view.owned.end(), 1), 25);
  EXPECT_EQ(std::count(view.on_boundary.begin(), view.on_boundary.end(), 1), 16);
  ASSERT_EQ(view.parts.size(), 4u);
  EXPECT_EQ(view.parts[0].name, "left");
  const std::int64_t corner = find_vertex(m, {0.0, 0.0});
  EXPECT_EQ(view.part_count[corner], 2);
  EXPECT_EQ(view.boundary_part[corner], 0);
  EXPECT_EQ(view.boundary_part[find_vertex(m, {0.26, 0.26})], -1);
  EXPECT_EQ(view.global_cell[7], 7);
}

}  // namespace neomesh
