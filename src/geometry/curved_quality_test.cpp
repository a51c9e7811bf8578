#include "geometry/curved_quality.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "formats/gmsh_reader.hpp"
#include "formats/vtk_reader.hpp"
#include "formats/vtu_reader.hpp"

namespace neomesh {

namespace {

// A smooth bending of space: the cells below are its images of the reference cell, so that
// every file lists the same curved cell whatever order it numbers the nodes in.
std::array<double, 3> bent(const std::array<double, 3>& p) {
  return {p[0] + 0.1 * std::sin(p[1] + 0.3 * p[2]), p[1] + 0.08 * p[0] * p[0],
          p[2] + 0.05 * p[0] * p[1]};
}

// VTK's parametric coordinates (in [0,1]) of the points of the triquadratic hexahedron (29)
// and the biquadratic quadrilateral (28), as vtkTriQuadraticHexahedron and vtkBiQuadraticQuad
// list them: independent of neomesh's tables.
std::vector<std::array<double, 3>> vtk_hexahedron27() {
  return {{0, 0, 0},   {1, 0, 0},   {1, 1, 0},   {0, 1, 0},   {0, 0, 1},   {1, 0, 1},   {1, 1, 1},
          {0, 1, 1},   {.5, 0, 0},  {1, .5, 0},  {.5, 1, 0},  {0, .5, 0},  {.5, 0, 1},  {1, .5, 1},
          {.5, 1, 1},  {0, .5, 1},  {0, 0, .5},  {1, 0, .5},  {1, 1, .5},  {0, 1, .5},  {0, .5, .5},
          {1, .5, .5}, {.5, 0, .5}, {.5, 1, .5}, {.5, .5, 0}, {.5, .5, 1}, {.5, .5, .5}};
}
std::vector<std::array<double, 3>> vtk_quadrilateral9() {
  return {{0, 0, 0},  {1, 0, 0},  {1, 1, 0},  {0, 1, 0},  {.5, 0, 0},
          {1, .5, 0}, {.5, 1, 0}, {0, .5, 0}, {.5, .5, 0}};
}

// The bent images of VTK's points (parametric [0,1] → reference [−1,1]).
std::vector<std::array<double, 3>> bent_vtk_points(std::vector<std::array<double, 3>> points,
                                                   int dim) {
  for (auto& p : points) {
    for (int d = 0; d < dim; ++d) p[d] = 2 * p[d] - 1;
    p = dim == 2 ? std::array{bent(p)[0], bent(p)[1], 0.0} : bent(p);
  }
  return points;
}

template <CurvedType Type>
std::string gmsh_file(const std::string& name) {
  constexpr int n = CurvedTraits<Type>::nodes, dim = CurvedTraits<Type>::dim;
  std::string text = fmt::format("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n{}\n", n);
  for (int i = 0; i < n; ++i) {
    std::array<double, 3> p{0, 0, 0};
    for (int d = 0; d < dim; ++d) p[d] = reference_node<Type>(i)[d];
    p = bent(p);
    text += fmt::format("{} {:.17g} {:.17g} {:.17g}\n", i + 1, p[0], p[1], dim == 2 ? 0.0 : p[2]);
  }
  text += fmt::format("$EndNodes\n$Elements\n1\n1 {} 2 1 1", facts(Type).gmsh);
  for (int i = 0; i < n; ++i) text += fmt::format(" {}", i + 1);
  text += "\n$EndElements\n";
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string vtk_file(const std::string& name, const std::vector<std::array<double, 3>>& points,
                     int type) {
  std::string text = fmt::format(
      "# vtk DataFile Version 4.2\ncurved\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS {} double\n",
      points.size());
  for (const auto& p : points) text += fmt::format("{:.17g} {:.17g} {:.17g}\n", p[0], p[1], p[2]);
  text += fmt::format("CELLS 1 {}\n{}", points.size() + 1, points.size());
  for (std::size_t i = 0; i < points.size(); ++i) text += fmt::format(" {}", i);
  text += fmt::format("\nCELL_TYPES 1\n{}\n", type);
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string vtu_file(const std::string& name, const std::vector<std::array<double, 3>>& points,
                     int type, const char* version) {
  std::string xyz, ids;
  for (const auto& p : points) xyz += fmt::format("{:.17g} {:.17g} {:.17g} ", p[0], p[1], p[2]);
  for (std::size_t i = 0; i < points.size(); ++i) ids += fmt::format("{} ", i);
  const std::string text = fmt::format(
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"{}\">\n"
      "<UnstructuredGrid><Piece NumberOfPoints=\"{}\" NumberOfCells=\"1\">\n"
      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">{}"
      "</DataArray></Points>\n<Cells>"
      "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">{}</DataArray>"
      "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">{}</DataArray>"
      "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">{}</DataArray>"
      "</Cells></Piece></UnstructuredGrid></VTKFile>\n",
      version, points.size(), xyz, ids, points.size(), type);
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

// det J of the one cell of `mesh` at a few points inside.
template <CurvedType Type>
std::vector<double> det_at_samples(const InputMesh& mesh) {
  constexpr int n = CurvedTraits<Type>::nodes, dim = CurvedTraits<Type>::dim;
  EXPECT_EQ(mesh.num_cells(), 1);
  EXPECT_EQ(mesh.high_order.types.at(0), Type);
  const std::vector<double> x = curved_point_coordinates(mesh);
  PetscInt points[kMaxCurvedNodes];
  EXPECT_EQ(curved_cell_points(mesh, 0, points), n);
  typename CurvedTraits<Type>::Nodes nodes;
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < dim; ++d) nodes(d, i) = x[points[i] * dim + d];
  std::vector<double> dets;
  for (const double s : {-0.7, -0.2, 0.4, 0.9}) {
    Vector<dim> xi;
    for (int d = 0; d < dim; ++d) xi[d] = d == 0 ? s : (d == 1 ? -0.5 * s : 0.3 - s * s);
    dets.push_back(curved_det<Type>(nodes, xi));
  }
  return dets;
}

template <CurvedType Type>
void expect_same_dets(const std::vector<double>& a, const std::vector<double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_NEAR(a[k], b[k], 1e-12) << "sample " << k;
}

}  // namespace

TEST(CurvedNodeOrders, AQuadrilateral9FromVtkHasTheGeometryOfItsGmshTwin) {
  constexpr auto Q9 = CurvedType::Quadrilateral9;
  const auto gmsh = det_at_samples<Q9>(read_gmsh(gmsh_file<Q9>("q9.msh")));
  const auto points = bent_vtk_points(vtk_quadrilateral9(), 2);
  expect_same_dets<Q9>(gmsh, det_at_samples<Q9>(read_vtk(vtk_file("q9.vtk", points, 28))));
  expect_same_dets<Q9>(gmsh, det_at_samples<Q9>(read_vtu(vtu_file("q9.vtu", points, 70, "1.0"))));
}

TEST(CurvedNodeOrders, AHexahedron27FromVtkHasTheGeometryOfItsGmshTwin) {
  constexpr auto H27 = CurvedType::Hexahedron27;
  const auto gmsh = det_at_samples<H27>(read_gmsh(gmsh_file<H27>("h27.msh")));
  auto points = bent_vtk_points(vtk_hexahedron27(), 3);
  expect_same_dets<H27>(gmsh, det_at_samples<H27>(read_vtk(vtk_file("h27.vtk", points, 29))));
  // A Lagrange hexahedron in a file of version 2.2: VTK's current order, the quadratic one's.
  expect_same_dets<H27>(gmsh,
                        det_at_samples<H27>(read_vtu(vtu_file("h27-new.vtu", points, 72, "2.2"))));
  // In an older file: the order before VTK 9.1, points 18 and 19 the other way round.
  std::swap(points[18], points[19]);
  expect_same_dets<H27>(gmsh,
                        det_at_samples<H27>(read_vtu(vtu_file("h27-old.vtu", points, 72, "1.0"))));
  // The check can fail: read in the wrong order, the geometry differs.
  const auto wrong = det_at_samples<H27>(read_vtu(vtu_file("h27-wrong.vtu", points, 72, "2.2")));
  double largest = 0;
  for (std::size_t k = 0; k < gmsh.size(); ++k)
    largest = std::max(largest, std::abs(wrong[k] - gmsh[k]));
  EXPECT_GT(largest, 1e-3);
}

}  // namespace neomesh
