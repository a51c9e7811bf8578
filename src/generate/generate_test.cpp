#include "generate/generate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "generate/serial_view.hpp"
#include "mesh/validate.hpp"

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

TEST(CubeMidpoint, Level3MeshHas4096HexesAndTheMovedMidpoint) {
  const MeshData m = cube_midpoint(16);
  EXPECT_EQ(m.cell_type, CellType::Hexahedron);
  EXPECT_EQ(m.num_cells(), 4096);
  EXPECT_GE(find_vertex(m, {1.2, 1.2, 1.2}), 0);
  EXPECT_LT(find_vertex(m, {1.0, 1.0, 1.0}), 0);
  EXPECT_GT(min_corner_det(m), 0.0);
  const auto on_boundary = boundary_vertices(m);
  for (std::int64_t v = 0; v < m.num_vertices(); ++v) {
    bool on_cube = false;
    for (int d = 0; d < 3; ++d) on_cube |= coord(m, v, d) == 0.0 || coord(m, v, d) == 2.0;
    EXPECT_EQ(on_boundary[v] != 0, on_cube);
  }
  EXPECT_EQ(m.boundary_parts.size(), 6u);
  for (std::int64_t v : part(m, "back").vertices) EXPECT_EQ(coord(m, v, 2), 2.0);
  expect_parts_cover_boundary(m);
}

TEST(SquareRandom, DisplacesOnlyInteriorVerticesWithinTheAmplitude) {
  const int n = 10;
  const double amplitude = 0.2, h = 1.0 / n;
  const MeshData m = square_random(n, amplitude, 42);
  const MeshData uniform = box(CellType::Quadrilateral, n);  // [-1,1]²: same lattice, scaled
  const auto on_boundary = boundary_vertices(m);
  int moved = 0;
  for (std::int64_t v = 0; v < m.num_vertices(); ++v)
    for (int d = 0; d < 2; ++d) {
      const double grid = 0.5 * (coord(uniform, v, d) + 1.0);
      const double shift = std::abs(coord(m, v, d) - grid);
      if (on_boundary[v]) {
        EXPECT_NEAR(shift, 0.0, 1e-15);
      }
      EXPECT_LE(shift, amplitude * h + 1e-15);
      moved += shift > 1e-3 * h;
    }
  EXPECT_GT(moved, 100);  // of 2·81 interior coordinates
  EXPECT_GT(min_corner_det(m), 0.0);
}

TEST(SquareRandom, IsDeterministicPerSeed) {
  EXPECT_EQ(square_random(8, 0.2, 7).coords, square_random(8, 0.2, 7).coords);
  EXPECT_NE(square_random(8, 0.2, 7).coords, square_random(8, 0.2, 8).coords);
  // std::mt19937 is fully specified: seeded with 5489 its first output is 3499211612, which
  // moves the only interior vertex (4) of a 2×2 grid first.
  const MeshData m = square_random(2, 0.2, 5489);
  const double first = 0.2 * 0.5 * (2.0 * 3499211612.0 * 0x1p-32 - 1.0);
  EXPECT_DOUBLE_EQ(coord(m, 4, 0), 0.5 + first);
  EXPECT_THROW(square_random(8, 1.0, 1), Error);
}

TEST(Jitter, MovesInteriorVerticesOfEveryCellTypeWithinTheAmplitude) {
  const int n = 6;
  const double amplitude = 0.24, h = 2.0 / n;
  for (CellType type :
       {CellType::Triangle, CellType::Quadrilateral, CellType::Tetrahedron, CellType::Hexahedron}) {
    const MeshData grid = box(type, n);
    MeshData m = grid;
    jitter(m, h, amplitude, 3);
    const auto on_boundary = boundary_vertices(grid);
    int moved = 0;
    for (std::int64_t v = 0; v < m.num_vertices(); ++v)
      for (int d = 0; d < m.dim; ++d) {
        const double shift = std::abs(coord(m, v, d) - coord(grid, v, d));
        EXPECT_LE(shift, on_boundary[v] ? 0.0 : amplitude * h) << name(type);
        moved += shift > 0.0;
      }
    EXPECT_GT(moved, m.dim * std::pow(n - 1, m.dim) / 2) << name(type);
    if (m.dim == 2) {
      EXPECT_GT(min_corner_det(m), 0.0) << name(type);
    }
  }
  // square_random is the unit-square lattice jittered in the same vertex order.
  MeshData unit = box(CellType::Quadrilateral, 4);
  for (double& x : unit.coords) x = (x + 1.0) / 2.0;
  jitter(unit, 0.25, 0.2, 9);
  EXPECT_EQ(unit.coords, square_random(4, 0.2, 9).coords);
}

TEST(Transition, OneQuadRefinedIntoFiveThenUniformly) {
  for (int r = 0; r <= 3; ++r) EXPECT_EQ(transition(r).num_cells(), 5 << (2 * r));
  const MeshData m = transition(2);
  EXPECT_GT(min_corner_det(m), 0.0);
  EXPECT_GE(find_vertex(m, {0.25, 0.25}), 0);
  EXPECT_GE(find_vertex(m, {0.75, 0.75}), 0);
  const auto on_boundary = boundary_vertices(m);
  for (std::int64_t v = 0; v < m.num_vertices(); ++v) {
    const double x = coord(m, v, 0), y = coord(m, v, 1);
    EXPECT_EQ(on_boundary[v] != 0, x == 0.0 || x == 1.0 || y == 0.0 || y == 1.0);
  }
  for (std::int64_t v : part(m, "right").vertices) EXPECT_EQ(coord(m, v, 0), 1.0);
  EXPECT_EQ(part(m, "bottom").vertices.size(), 5u);
  expect_parts_cover_boundary(m);
}

TEST(CircleQuad, BoundaryVerticesLieOnTheUnitCircle) {
  for (int r = 0; r <= 3; ++r) EXPECT_EQ(circle_quad(r).num_cells(), 5 << (2 * r));
  const MeshData m = circle_quad(3);
  EXPECT_GT(min_corner_det(m), 0.0);
  const auto on_boundary = boundary_vertices(m);
  int count = 0;
  for (std::int64_t v = 0; v < m.num_vertices(); ++v) {
    const double radius = std::hypot(coord(m, v, 0), coord(m, v, 1));
    if (on_boundary[v])
      EXPECT_NEAR(radius, 1.0, 1e-14);
    else
      EXPECT_LT(radius, 1.0 - 1e-3);
    count += on_boundary[v];
  }
  EXPECT_EQ(count, 32);
  EXPECT_EQ(part(m, "circle").vertices.size(), 32u);
  expect_parts_cover_boundary(m);
  // Point symmetric about the origin.
  for (std::int64_t v = 0; v < m.num_vertices(); ++v)
    EXPECT_GE(find_vertex(m, {-coord(m, v, 0), -coord(m, v, 1)}), 0);
}

TEST(TriangleEquilateral, RefinesIntoEquilateralTrianglesAndMovesSomeInteriorVertices) {
  for (int r = 0; r <= 3; ++r) EXPECT_EQ(triangle_equilateral(r, 1).num_cells(), 1 << (2 * r));
  const int r = 3;
  const MeshData m = triangle_equilateral(r, 1);
  EXPECT_GT(min_corner_det(m), 0.0);
  const double s3 = std::sqrt(3.0);
  const auto on_boundary = boundary_vertices(m);
  int interior = 0, moved = 0;
  for (std::int64_t v = 0; v < m.num_vertices(); ++v) {
    const double x = coord(m, v, 0), y = coord(m, v, 1);
    // Distances to the sides y = 0, √3 x - y = 0, √3 (1 - x) - y = 0.
    const double to_side = std::min({y, (s3 * x - y) / 2, (s3 * (1 - x) - y) / 2});
    if (on_boundary[v]) {
      EXPECT_NEAR(to_side, 0.0, 1e-15);
      continue;
    }
    ++interior;
    // Lattice points have y = k·(√3/2)·h and x = (i + k/2)·h.
    const double h = 1.0 / (1 << r), k = y / (s3 / 2 * h), i = x / h - k / 2;
    moved += std::abs(k - std::round(k)) > 1e-9 || std::abs(i - std::round(i)) > 1e-9;
  }
  EXPECT_EQ(interior, 21);
  EXPECT_GT(moved, 0);
  EXPECT_LT(moved, interior);
  EXPECT_EQ(triangle_equilateral(r, 1).coords, m.coords);
  EXPECT_NE(triangle_equilateral(r, 2).coords, m.coords);
  expect_parts_cover_boundary(m);
}

TEST(TriangleCurved, BoundaryFollowsTheCurvesAndTheMeshIsPointSymmetric) {
  for (int r = 0; r <= 3; ++r) EXPECT_EQ(triangle_curved(r).num_cells(), 8 << (2 * r));
  const MeshData m = triangle_curved(3);
  EXPECT_GT(min_corner_det(m), 0.0);
  // Mid points of the bottom (bulging out) and the right side (bulging in).
  EXPECT_GE(find_vertex(m, {0.5, -0.1875}), 0);
  EXPECT_GE(find_vertex(m, {0.8125, 0.5}), 0);
  for (std::int64_t v : part(m, "bottom").vertices) EXPECT_LE(coord(m, v, 1), 0.0);
  for (std::int64_t v : part(m, "left").vertices) EXPECT_GE(coord(m, v, 0), 0.0);
  for (std::int64_t v = 0; v < m.num_vertices(); ++v)
    EXPECT_GE(find_vertex(m, {1.0 - coord(m, v, 0), 1.0 - coord(m, v, 1)}), 0);
  EXPECT_EQ(part(m, "top").vertices.size(), 17u);
  expect_parts_cover_boundary(m);
}

// Wedge and pyramid boxes: every cell positive at every corner frame, and faces that match
// (no interior facet left unpaired, so only the surface counts as boundary).
TEST(Box, WedgesAndPyramidsArePositiveAndConforming) {
  const int n = 3;
  for (const auto& [type, cells] :
       {std::pair{CellType::Wedge, 54}, std::pair{CellType::Pyramid, 162}}) {
    const MeshData m = box(type, n);
    ASSERT_EQ(m.cell_type, type);
    EXPECT_EQ(m.num_cells(), cells);
    const int nv = num_vertices(type);
    for (std::int64_t c = 0; c < m.num_cells(); ++c) {
      double x[8 * 3];
      for (int i = 0; i < nv; ++i)
        for (int d = 0; d < 3; ++d) x[3 * i + d] = coord(m, m.cells[c * nv + i], d);
      EXPECT_GT(min_scaled_corner_jacobian(type, x), 0.1) << name(type) << " cell " << c;
    }
    const auto on_boundary = boundary_vertices(m);
    EXPECT_EQ(std::count(on_boundary.begin(), on_boundary.end(), 1),
              (n + 1) * (n + 1) * (n + 1) - (n - 1) * (n - 1) * (n - 1))
        << name(type);
  }
}

// Cells of the lattice generators (box, quarter_annulus) at n = 4 per direction.
const std::vector<std::pair<CellType, int>> kLatticeCells = {{CellType::Quadrilateral, 16},
                                                             {CellType::Triangle, 32},
                                                             {CellType::Hexahedron, 64},
                                                             {CellType::Tetrahedron, 384}};

TEST(Box, CountsOrientationAndConformingDiagonals) {
  const int n = 4;
  for (const auto& [type, cells] : kLatticeCells) {
    const MeshData m = box(type, n);
    EXPECT_EQ(m.cell_type, type);
    EXPECT_EQ(m.num_cells(), cells);
    EXPECT_GT(min_corner_det(m), 0.0) << name(type);
    // Matching diagonals leave no interior facet unpaired: boundary = surface vertices.
    const auto on_boundary = boundary_vertices(m);
    const int d = m.dim;
    const int surface = d == 2 ? 4 * n : (n + 1) * (n + 1) * (n + 1) - (n - 1) * (n - 1) * (n - 1);
    EXPECT_EQ(std::count(on_boundary.begin(), on_boundary.end(), 1), surface) << name(type);
    for (std::int64_t v = 0; v < m.num_vertices(); ++v) {
      double largest = 0.0;
      for (int j = 0; j < d; ++j) largest = std::max(largest, std::abs(coord(m, v, j)));
      EXPECT_EQ(on_boundary[v] != 0, largest == 1.0);
    }
    expect_parts_cover_boundary(m);
  }
}

TEST(QuarterAnnulus, CountsOrientationAndTheArcs) {
  const int n = 4;
  for (const auto& [type, cells] : kLatticeCells) {
    const MeshData m = quarter_annulus(type, n);
    EXPECT_EQ(m.num_cells(), cells) << name(type);
    EXPECT_GT(min_corner_det(m), 0.0) << name(type);
    expect_parts_cover_boundary(m);
    // The arcs at r = 1 and r = 2, the straight sides on the axes.
    for (const auto& [arc, radius] : {std::pair{"inner", 1.0}, std::pair{"outer", 2.0}})
      for (std::int64_t v : part(m, arc).vertices)
        EXPECT_NEAR(std::hypot(coord(m, v, 0), coord(m, v, 1)), radius, 1e-14);
    for (std::int64_t v : part(m, "start").vertices) EXPECT_EQ(coord(m, v, 1), 0.0);
    for (std::int64_t v : part(m, "end").vertices) EXPECT_NEAR(coord(m, v, 0), 0.0, 1e-15);
  }
  EXPECT_THROW(quarter_annulus(CellType::Wedge, n), Error);
}

TEST(Rotate, PreservesEdgeLengthsAndTurnsCounterClockwise) {
  MeshData m = square_midpoint(4);
  const MeshData before = m;
  rotate(m, 27.0);
  const double a = 27.0 * std::numbers::pi / 180.0;
  const std::int64_t v = find_vertex(before, {1.0, 0.0});
  EXPECT_NEAR(coord(m, v, 0), std::cos(a), 1e-15);
  EXPECT_NEAR(coord(m, v, 1), std::sin(a), 1e-15);
  auto length = [](const MeshData& mesh, std::int64_t p, std::int64_t q) {
    double sum = 0.0;
    for (int d = 0; d < mesh.dim; ++d) sum += std::pow(coord(mesh, p, d) - coord(mesh, q, d), 2);
    return std::sqrt(sum);
  };
  for (std::int64_t c = 0; c < m.num_cells(); ++c)
    for (auto [i, j] : {std::pair{0, 1}, {2, 3}, {0, 2}, {1, 3}}) {
      const std::int64_t p = m.cells[4 * c + i], q = m.cells[4 * c + j];
      EXPECT_NEAR(length(m, p, q), length(before, p, q), 1e-14);
    }
  MeshData cube = cube_midpoint(2);
  rotate(cube, 90.0);
  const std::int64_t top = find_vertex(cube_midpoint(2), {2.0, 0.0, 2.0});
  EXPECT_NEAR(coord(cube, top, 0), 0.0, 1e-15);
  EXPECT_NEAR(coord(cube, top, 1), 2.0, 1e-15);
  EXPECT_EQ(coord(cube, top, 2), 2.0);
}

}  // namespace neomesh
