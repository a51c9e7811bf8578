#include "mesh/surface_defects.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

namespace neomesh {
namespace {

InputMesh surface() {
  InputMesh mesh;
  mesh.dim = 2;
  mesh.surface = true;
  return mesh;
}

PetscInt add_point(InputMesh& mesh, double x, double y, double z) {
  mesh.coords.insert(mesh.coords.end(), {x, y, z});
  return mesh.num_vertices() - 1;
}

void add_triangle(InputMesh& mesh, PetscInt a, PetscInt b, PetscInt c) {
  const PetscInt v[] = {a, b, c};
  mesh.add_cell(CellType::Triangle, v, 0);
}

// The quadrilateral whose cycle is a b c d (tensor order a b d c).
void add_quad(InputMesh& mesh, PetscInt a, PetscInt b, PetscInt c, PetscInt d) {
  const PetscInt v[] = {a, b, d, c};
  mesh.add_cell(CellType::Quadrilateral, v, 0);
}

// A sphere of radius r about `centre`: `rings` rings of `segments` vertices between the poles,
// triangles at the poles and quadrilaterals between, all facing outwards. Cell j of the north
// fan (cell j) has the vertices north, ring 1 at j, ring 1 at j + 1.
void add_sphere(InputMesh& mesh, std::array<double, 3> centre, double r, int rings, int segments) {
  const auto at = [&](double theta, double phi) {
    return add_point(mesh, centre[0] + r * std::sin(theta) * std::cos(phi),
                     centre[1] + r * std::sin(theta) * std::sin(phi),
                     centre[2] + r * std::cos(theta));
  };
  const PetscInt north = at(0, 0);
  const PetscInt first = mesh.num_vertices();
  for (int i = 1; i <= rings; ++i)
    for (int j = 0; j < segments; ++j)
      at(std::numbers::pi * i / (rings + 1), 2 * std::numbers::pi * j / segments);
  const PetscInt south = at(std::numbers::pi, 0);
  const auto ring = [&](int i, int j) { return first + (i - 1) * segments + j % segments; };
  for (int j = 0; j < segments; ++j) add_triangle(mesh, north, ring(1, j), ring(1, j + 1));
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j)
      add_quad(mesh, ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1));
  for (int j = 0; j < segments; ++j) add_triangle(mesh, ring(rings, j), south, ring(rings, j + 1));
}

// An n × n grid of squares of side h, each split into two triangles, in the plane through
// `origin` spanned by the unit vectors u and v.
void add_flat_patch(InputMesh& mesh, std::array<double, 3> origin, std::array<double, 3> u,
                    std::array<double, 3> v, int n, double h) {
  const PetscInt first = mesh.num_vertices();
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      add_point(mesh, origin[0] + h * (i * u[0] + j * v[0]), origin[1] + h * (i * u[1] + j * v[1]),
                origin[2] + h * (i * u[2] + j * v[2]));
  const auto id = [&](int i, int j) { return first + i + (n + 1) * j; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      add_triangle(mesh, id(i, j), id(i + 1, j), id(i + 1, j + 1));
      add_triangle(mesh, id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(SurfaceDefects, AClosedSphereOfTrianglesAndQuadrilateralsHasNone) {
  InputMesh mesh = surface();
  add_sphere(mesh, {0, 0, 0}, 1, 7, 12);
  EXPECT_EQ(find_surface_edge_defect(mesh), "");
  EXPECT_EQ(find_surface_crossing(mesh), "");
}

TEST(SurfaceDefects, OpenBoundariesAndSeveralPiecesAreFine) {
  InputMesh mesh = surface();
  add_sphere(mesh, {0, 0, 0}, 1, 5, 8);
  add_sphere(mesh, {3, 0, 0}, 1, 5, 8);  // apart from the first
  // Open, and in a tilted plane: its cells are coplanar with cells that share no vertex.
  const double s = 1 / std::sqrt(3.0);
  add_flat_patch(mesh, {0, 0, 5}, {s, s, s}, {1 / std::sqrt(2.0), -1 / std::sqrt(2.0), 0}, 6, 0.1);
  EXPECT_EQ(find_surface_edge_defect(mesh), "");
  EXPECT_EQ(find_surface_crossing(mesh), "");
}

TEST(SurfaceDefects, AnEdgeOfThreeCellsIsNamedByItsVertices) {
  InputMesh mesh = surface();
  add_point(mesh, 0, 0, 0);
  add_point(mesh, 1, 0, 0);
  add_point(mesh, 0.5, 1, 0);
  add_point(mesh, 0.5, -1, 0);
  add_point(mesh, 0.5, 0, 1);
  add_triangle(mesh, 0, 1, 2);
  add_triangle(mesh, 1, 0, 3);
  add_triangle(mesh, 0, 1, 4);  // a fin on the edge 0–1
  mesh.element_tag = {10, 11, 12};
  const std::string defect = find_surface_edge_defect(mesh);
  EXPECT_TRUE(contains(defect, "between vertices 0 and 1 (0-based) is shared by 3 cells"))
      << defect;
  EXPECT_TRUE(contains(defect, "3 cells (0, 1 and 2, 0-based; elements 10, 11 and 12 of the file)"))
      << defect;
}

TEST(SurfaceDefects, AFlippedCellAndItsNeighbourAreNamed) {
  InputMesh mesh = surface();
  const int segments = 10;
  add_sphere(mesh, {0, 0, 0}, 1, 6, segments);
  ASSERT_EQ(find_surface_edge_defect(mesh), "");
  std::swap(mesh.cell_vertices[1], mesh.cell_vertices[2]);  // cell 0 now faces inwards
  const std::string defect = find_surface_edge_defect(mesh);
  // Its first edge by vertex numbers, ring 1 at 0 (1) – north (0), is cell 9's too, run the same
  // way.
  EXPECT_TRUE(contains(defect, fmt::format("not oriented alike: cell 0 (0-based) and cell {} "
                                           "(0-based) both run from vertex 1 to vertex 0",
                                           segments - 1)))
      << defect;
}

TEST(SurfaceDefects, TwoPatchesThatCrossAreNamed) {
  InputMesh mesh = surface();
  add_flat_patch(mesh, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1, 1);  // cells 0, 1 in z = 0
  // Cells 2, 3 in x = 0.5, through z = 0 over 0.25 ≤ y ≤ 0.75.
  add_flat_patch(mesh, {0.5, 0.25, -0.25}, {0, 1, 0}, {0, 0, 1}, 1, 0.5);
  EXPECT_EQ(find_surface_edge_defect(mesh), "");
  const std::string defect = find_surface_crossing(mesh);
  EXPECT_TRUE(contains(defect, "crosses itself: cell 0 (0-based) and cell ")) << defect;
  // Lifted so that its lower edge lies on z = 0, the second patch touches the first only.
  for (PetscInt v = 4; v < 8; ++v) mesh.coords[3 * v + 2] += 0.25;
  EXPECT_EQ(find_surface_crossing(mesh), "");
}

TEST(SurfaceDefects, OverlappingCellsInOnePlaneCross) {
  InputMesh mesh = surface();
  const std::array<double, 3> u = {0.6, 0.8, 0}, v = {0, 0, 1};
  add_flat_patch(mesh, {0, 0, 0}, u, v, 3, 1);
  EXPECT_EQ(find_surface_crossing(mesh), "");
  add_flat_patch(mesh, {0.3 * u[0], 0.3 * u[1], 0.4}, u, v, 1, 0.5);  // on top, in the plane
  EXPECT_TRUE(contains(find_surface_crossing(mesh), "crosses itself"))
      << find_surface_crossing(mesh);
}

TEST(SurfaceDefects, TwoSpheresThroughEachOtherCross) {
  InputMesh mesh = surface();
  add_sphere(mesh, {0, 0, 0}, 1, 9, 16);
  add_sphere(mesh, {0.7, 0.3, 0.1}, 1, 9, 16);
  EXPECT_EQ(find_surface_edge_defect(mesh), "");
  const std::string defect = find_surface_crossing(mesh);
  EXPECT_TRUE(contains(defect, "crosses itself")) << defect;
  // Apart, they do not.
  for (std::size_t i = 3 * (mesh.num_vertices() / 2); i < mesh.coords.size(); i += 3)
    mesh.coords[i] += 2;
  EXPECT_EQ(find_surface_crossing(mesh), "");
}

}  // namespace
}  // namespace neomesh
