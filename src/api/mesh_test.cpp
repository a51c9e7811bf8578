// The public Mesh's whole-mesh functions: gather (the inverse of from_arrays), per-cell quality,
// volume and the distance between boundaries.
#include <neomesh/mesh.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>
#include <petscdm.h>

#include <neomesh/error.hpp>
#include <neomesh/generate.hpp>
#include <neomesh/optimizer.hpp>
#include <neomesh/result.hpp>

#include "core/testing/test_data.hpp"

namespace neomesh {
namespace {

// [0,1]² as a quad (cell 0) and [1,3]×[0,1] as two triangles, the vertices numbered out of
// geometric order so that a gather that ignored the numbering would show:
//   3 ---- 0 ------------ 4
//   |  0   |    1     /   |
//   |      |     /    2   |
//   1 ---- 2 ------------ 5
MeshArrays square_and_triangles() {
  MeshArrays mesh;
  mesh.dim = 2;
  mesh.coordinates = {1, 1, 0, 0, 1, 0, 0, 1, 3, 1, 3, 0};
  mesh.cells = {1, 2, 0, 3, /**/ 2, 4, 0, /**/ 2, 5, 4};
  mesh.types = {CellType::Quadrilateral, CellType::Triangle, CellType::Triangle};
  return mesh;
}

Mesh build(const MeshArrays& a, InvertedCells inverted = InvertedCells::Refuse) {
  return Mesh::from_arrays(MPI_COMM_WORLD, a.dim, a.coordinates, a.cells, a.types, "test mesh",
                           inverted);
}

const std::vector<double>& field(const std::vector<Field>& fields, const std::string& name) {
  const auto it =
      std::find_if(fields.begin(), fields.end(), [&](const Field& f) { return f.name == name; });
  if (it == fields.end()) throw std::runtime_error("no field " + name);
  return it->values;
}

// Per local cell, its number's value in `by_number`.
std::vector<double> by_local_cell(const Mesh& mesh, const std::vector<double>& by_number) {
  std::vector<double> out;
  for (std::int64_t c : mesh.cell_numbers()) out.push_back(by_number[c]);
  return out;
}

TEST(MeshGather, GivesBackTheArraysOfFromArrays) {
  const MeshArrays input = square_and_triangles();
  const Mesh mesh = build(input);
  const MeshArrays out = mesh.gather();
  EXPECT_EQ(out.dim, 2);
  EXPECT_EQ(out.coordinates, input.coordinates);
  EXPECT_EQ(out.cells, input.cells);
  EXPECT_EQ(out.types, input.types);
  EXPECT_TRUE(out.cell_fields.empty());
}

TEST(MeshGather, GivesFieldsByCellNumber) {
  const Mesh mesh = build(square_and_triangles());
  const std::vector<double> by_number = {10, 11, 12};
  const std::vector<double> twice = {20, 21, 22, 23, 24, 25};  // two components
  std::vector<double> local_twice;
  for (std::int64_t c : mesh.cell_numbers())
    local_twice.insert(local_twice.end(), {twice[2 * c], twice[2 * c + 1]});
  const MeshArrays out =
      mesh.gather({{"number", by_local_cell(mesh, by_number)}, {"pair", local_twice, 2}});
  ASSERT_EQ(out.cell_fields.size(), 2u);
  EXPECT_EQ(out.cell_fields[0].name, "number");
  EXPECT_EQ(out.cell_fields[0].values, by_number);
  EXPECT_EQ(out.cell_fields[1].components, 2);
  EXPECT_EQ(out.cell_fields[1].values, twice);
  // The volumes of quality_by_cell(), gathered: the quad is 1, the triangles 1 each.
  const MeshArrays volumes = mesh.gather({{"volume", field(mesh.quality_by_cell(), "volume")}});
  for (double v : volumes.cell_fields[0].values) EXPECT_NEAR(v, 1.0, 1e-14);
}

TEST(MeshGather, FieldOfTheWrongSizeIsAnError) {
  const Mesh mesh = build(square_and_triangles());
  EXPECT_THROW(mesh.gather({{"short", {1.0, 2.0}}}), Error);
}

TEST(MeshGather, FollowsTheCoordinates) {
  Mesh mesh = build(square_and_triangles());
  std::vector<double> x = mesh.coordinates();
  for (double& c : x) c *= 2;
  mesh.set_coordinates(x);
  const MeshArrays out = mesh.gather();
  const MeshArrays input = square_and_triangles();
  for (std::size_t i = 0; i < input.coordinates.size(); ++i)
    EXPECT_EQ(out.coordinates[i], 2 * input.coordinates[i]);
}

// The quality is computed once per set of coordinates (Mesh::cell_quality): after a move,
// every view of it is the moved mesh's.
TEST(MeshQuality, FollowsTheCoordinates) {
  Mesh mesh = build(square_and_triangles());
  const QualitySummary before = mesh.quality();
  std::vector<double> x = mesh.coordinates();
  for (double& c : x) c *= 2;
  mesh.set_coordinates(x);
  EXPECT_DOUBLE_EQ(mesh.quality().volume.mean, 4 * before.volume.mean);
  const std::vector<Field> fields = mesh.quality_by_cell();
  for (double v : field(fields, "volume")) EXPECT_NEAR(v, 4.0, 1e-14);
  EXPECT_DOUBLE_EQ(mesh.volume(), 4 * before.volume.mean * before.cells);
}

// The DMPlex a caller gets has the coordinates the mesh has now, not those it was built with.
TEST(MeshDm, HasTheCurrentCoordinates) {
  Mesh mesh = build(square_and_triangles());
  std::vector<double> x = mesh.coordinates();
  for (double& c : x) c = 2 * c + 1;
  mesh.set_coordinates(x);
  Vec local = nullptr;
  ASSERT_EQ(DMGetCoordinatesLocal(mesh.dm(), &local), 0);
  const PetscScalar* values = nullptr;
  PetscInt n = 0;
  ASSERT_EQ(VecGetLocalSize(local, &n), 0);
  ASSERT_EQ(VecGetArrayRead(local, &values), 0);
  std::vector<double> in_dm(values, values + n);
  ASSERT_EQ(VecRestoreArrayRead(local, &values), 0);
  // Serial: every vertex is local; the DM may order them its own way.
  std::sort(in_dm.begin(), in_dm.end());
  std::sort(x.begin(), x.end());
  EXPECT_EQ(in_dm, x);
}

TEST(MeshQualityByCell, MarksTheInvertedCell) {
  MeshArrays input = square_and_triangles();
  input.coordinates[0] = input.coordinates[1] = 0.2;  // vertex 0: the quad's corner turns reflex
  const Mesh mesh = build(input, InvertedCells::Keep);
  const std::vector<Field> quality = mesh.quality_by_cell();
  std::vector<std::string> names;
  for (const Field& f : quality) names.push_back(f.name);
  EXPECT_EQ(names, (std::vector<std::string>{"volume", "scaled_jacobian", "min_angle", "max_angle",
                                             "edge_ratio", "inverse_mean_ratio", "inverted"}));
  EXPECT_EQ(field(quality, "inverted"), by_local_cell(mesh, {1, 0, 0}));
  EXPECT_EQ(mesh.quality().inverted, 1);
  const std::vector<double>& volume = field(quality, "volume");
  EXPECT_NEAR(std::accumulate(volume.begin(), volume.end(), 0.0), mesh.volume(), 1e-14);
}

TEST(MeshVolume, OfBoxesAndOfAScaledMesh) {
  EXPECT_NEAR(Mesh::generate({.name = "box-hex", .size = 3}).volume(), 8.0, 1e-12);
  EXPECT_NEAR(Mesh::generate({.name = "box-tet", .size = 2}).volume(), 8.0, 1e-12);
  EXPECT_NEAR(Mesh::generate({.name = "box-tri", .size = 4, .rotate_degrees = 30}).volume(), 4.0,
              1e-12);
  Mesh mesh = build(square_and_triangles());
  EXPECT_NEAR(mesh.volume(), 3.0, 1e-14);
  std::vector<double> x = mesh.coordinates();
  for (double& c : x) c *= 3;
  mesh.set_coordinates(x);
  EXPECT_NEAR(mesh.volume(), 27.0, 1e-12);
}

TEST(MeshBoundaryDistance, HowFarTheBoundaryMoved) {
  const Mesh reference = build(square_and_triangles());
  Mesh mesh = build(square_and_triangles());
  EXPECT_NEAR(mesh.max_boundary_distance(reference), 0.0, 1e-14);
  // Vertex 4 at (3, 1) moves up by 0.25: 0.25 from the top edge, further from the others.
  std::vector<double> x = mesh.coordinates();
  const std::vector<std::int64_t> numbers = mesh.vertex_numbers();
  const auto at = std::find(numbers.begin(), numbers.end(), 4) - numbers.begin();
  x[2 * at + 1] += 0.25;
  mesh.set_coordinates(x);
  EXPECT_NEAR(mesh.max_boundary_distance(reference), 0.25, 1e-12);
  EXPECT_THROW(mesh.max_boundary_distance(Mesh::generate({.name = "box-hex", .size = 1})), Error);
}

// A surface mesh: n × n quads on the parabolic patch z = x² over [0, 1]², open, its interior
// vertices jittered in x and y (then lifted onto the patch) so that smoothing moves them.
MeshArrays parabolic_patch(int n) {
  MeshArrays mesh;
  mesh.dim = 2;
  mesh.coordinate_dim = 3;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool interior = i > 0 && i < n && j > 0 && j < n;
      const double x = (i + (interior ? 0.3 * std::sin(7.0 * j + i) : 0.0)) / n;
      const double y = (j + (interior ? 0.3 * std::cos(5.0 * i + j) : 0.0)) / n;
      mesh.coordinates.insert(mesh.coordinates.end(), {x, y, x * x});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::int64_t v = j * (n + 1) + i;
      mesh.cells.insert(mesh.cells.end(), {v, v + 1, v + n + 2, v + n + 1});
      mesh.types.push_back(CellType::Quadrilateral);
    }
  return mesh;
}

Mesh build_surface(const MeshArrays& a) {
  return Mesh::from_arrays(MPI_COMM_WORLD, a.coordinate_dim, a.coordinates, a.cells, a.types,
                           "parabolic patch");
}

TEST(SurfaceArrays, ThreeCoordinatesPerVertexInAndOut) {
  const MeshArrays input = parabolic_patch(4);
  Mesh mesh = build_surface(input);
  EXPECT_EQ(mesh.dim(), 2);
  EXPECT_EQ(mesh.coordinate_dim(), 3);
  std::vector<double> by_number(input.coordinates.size());
  const std::vector<double> x = mesh.coordinates();
  const std::vector<std::int64_t> numbers = mesh.vertex_numbers();
  ASSERT_EQ(x.size(), 3 * numbers.size());
  for (std::size_t i = 0; i < numbers.size(); ++i)
    for (int j = 0; j < 3; ++j) by_number[3 * numbers[i] + j] = x[3 * i + j];
  EXPECT_EQ(by_number, input.coordinates);
  const MeshArrays out = mesh.gather();
  EXPECT_EQ(out.dim, 2);
  EXPECT_EQ(out.coordinate_dim, 3);
  EXPECT_EQ(out.coordinates, input.coordinates);
  EXPECT_EQ(out.cells, input.cells);
  EXPECT_EQ(out.types, input.types);
  // Moved as given, 3 values per vertex.
  std::vector<double> moved = x;
  for (double& c : moved) c *= 2;
  mesh.set_coordinates(moved);
  EXPECT_EQ(mesh.coordinates(), moved);
  EXPECT_THROW(mesh.set_coordinates(std::vector<double>(2 * numbers.size(), 0.0)), Error);
}

TEST(SurfaceArrays, TwoDimensionalCellsInOnePlaneNeedTwoCoordinates) {
  MeshArrays flat = parabolic_patch(2);
  for (std::size_t v = 0; v < flat.coordinates.size() / 3; ++v) flat.coordinates[3 * v + 2] = 1;
  EXPECT_THROW(build_surface(flat), Error);
}

// The smallest z of the mesh's vertices.
double lowest(const Mesh& mesh) {
  double z = std::numeric_limits<double>::infinity();
  const std::vector<double> x = mesh.coordinates();
  for (std::size_t i = 2; i < x.size(); i += 3) z = std::min(z, x[i]);
  return z;
}

// A surface moved by set_coordinates (the patch lifted by 1, as a shell moves in a time loop)
// is the surface its vertices slide on from then on, also for an Optimizer that smoothed it
// before: smoothing improves the lifted mesh and leaves it where it was put.
TEST(SurfaceArrays, SetCoordinatesMovesTheSurface) {
  Mesh mesh = build_surface(parabolic_patch(6));
  Optimizer optimizer(mesh);
  optimizer.smooth();
  EXPECT_GE(lowest(mesh), 0.0);
  std::vector<double> x = mesh.coordinates();
  for (std::size_t i = 2; i < x.size(); i += 3) x[i] += 1.0;
  for (std::size_t i = 0; i < x.size(); i += 3) x[i] += 0.02 * std::sin(3.0 * i);  // jitter
  mesh.set_coordinates(x);
  const double min_before = mesh.quality().scaled_jacobian.min;
  const Result result = optimizer.smooth();
  EXPECT_GE(lowest(mesh), 1.0 - 1e-12);
  EXPECT_LT(result.boundary_distance, 1e-12);  // from the cells where this call started
  EXPECT_GT(mesh.quality().scaled_jacobian.min, min_before);
}

}  // namespace
}  // namespace neomesh

namespace neomesh {
namespace {

// Mesh::read and Mesh::write carry the file's point and cell data: after moving the vertices,
// the written .vtu holds the input's arrays unchanged beside the quality fields, and a
// quality field whose name the input has ("volume") is written as "neomesh_volume".
TEST(MeshData, ReadAndWriteCarryTheInputsData) {
  const auto dir = testing::scratch_dir("MeshData");
  std::ofstream(dir / "in.vtk") << "# vtk DataFile Version 3.0\nt\nASCII\n"
                                   "DATASET UNSTRUCTURED_GRID\n"
                                   "POINTS 4 double\n0 0 0 1 0 0 1 1 0 0 1 0\n"
                                   "CELLS 2 8\n3 0 1 2\n3 0 2 3\nCELL_TYPES 2\n5 5\n"
                                   "CELL_DATA 2\nSCALARS volume int\nLOOKUP_TABLE default\n7 9\n"
                                   "POINT_DATA 4\nSCALARS T double\nLOOKUP_TABLE default\n"
                                   "0.25 1.5 2.75 3\n";
  Mesh mesh = Mesh::read(dir / "in.vtk");
  std::vector<double> x = mesh.coordinates();
  for (double& c : x) c *= 2;
  mesh.set_coordinates(x);
  mesh.write(dir / "out.vtk");
  const std::string text = testing::read_file(dir / "out.vtk");
  EXPECT_NE(text.find("volume 1 2 int\n7 9"), std::string::npos) << text;
  EXPECT_NE(text.find("T 1 4 double\n0.25 1.5 2.75 3"), std::string::npos) << text;
  EXPECT_NE(text.find("neomesh_volume 1 2 double\n2 2"), std::string::npos) << text;
  EXPECT_NE(text.find("2 2 0"), std::string::npos) << text;  // the moved vertex
}

}  // namespace
}  // namespace neomesh
