// Under `mpiexec -n 2`: a distributed mesh is the serial mesh, split.
#include <gtest/gtest.h>

#include <map>
#include <numeric>

#include "core/testing/test_data.hpp"
#include "formats/mesh_io.hpp"
#include "formats/mesh_test_util.hpp"
#include "mesh/gather.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh {
namespace {

using testing::data_path;
using testing::read_file;

using Point = std::array<double, 3>;

Point point(const MeshView& view, PetscInt v) {
  Point p{0, 0, 0};
  for (int d = 0; d < view.dim; ++d) p[d] = view.coords[v * view.dim + d];
  return p;
}

// Per vertex (by position): how many cells contain it.
std::map<Point, int> incidence(const MeshView& view) {
  std::map<Point, int> count;
  for (const CellBlock& block : view.blocks)
    for (PetscInt v : block.vertices) ++count[point(view, v)];
  return count;
}

class Distributed : public ::testing::TestWithParam<const char*> {};

TEST_P(Distributed, SplitsTheSerialMesh) {
  ASSERT_EQ(mpi_size(), 2);
  PlexMesh serial = load_mesh(data_path(GetParam()), PETSC_COMM_SELF);
  PlexMesh mesh = load_mesh(data_path(GetParam()));
  const MeshView& view = mesh.view();
  EXPECT_EQ(mesh.global_num_cells(), serial.global_num_cells());
  EXPECT_EQ(mesh.global_num_vertices(), serial.global_num_vertices());
  EXPECT_GT(view.num_cells, 0);  // both ranks got cells
  EXPECT_GT(testing::min_view_jacobian(view), 0.0);

  // Every cell in exactly one rank.
  const int n = static_cast<int>(view.num_cells);
  std::vector<int> counts(2), offsets(3, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, PETSC_COMM_WORLD);
  std::partial_sum(counts.begin(), counts.end(), offsets.begin() + 1);
  std::vector<PetscInt> all(offsets[2]);
  MPI_Allgatherv(view.global_cell.data(), n, MPIU_INT, all.data(), counts.data(), offsets.data(),
                 MPIU_INT, PETSC_COMM_WORLD);
  std::sort(all.begin(), all.end());
  std::vector<PetscInt> expected(serial.global_num_cells());
  std::iota(expected.begin(), expected.end(), PetscInt{0});
  EXPECT_EQ(all, expected);

  // Every vertex owned by exactly one rank.
  PetscInt owned = std::count(view.owned.begin(), view.owned.end(), 1), total = 0;
  MPI_Allreduce(&owned, &total, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
  EXPECT_EQ(total, serial.global_num_vertices());

  // Boundary flags and parts as in the serial mesh, ghosts included.
  const MeshView& whole = serial.view();
  std::map<Point, std::pair<int, int>> boundary;
  for (PetscInt v = 0; v < whole.num_vertices; ++v)
    boundary[point(whole, v)] = {whole.on_boundary[v], whole.part_count[v]};
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    const auto [on_boundary, parts] = boundary.at(point(view, v));
    EXPECT_EQ(view.on_boundary[v], on_boundary);
    EXPECT_EQ(view.part_count[v], parts);
  }
}

TEST_P(Distributed, DofMapSumsOverRanks) {
  PlexMesh serial = load_mesh(data_path(GetParam()), PETSC_COMM_SELF);
  PlexMesh mesh = load_mesh(data_path(GetParam()));
  const MeshView& view = mesh.view();
  const DofMap& dofs = mesh.dofs();
  // Each local cell adds 1 to every dof of its vertices.
  std::vector<double> local(dofs.num_local_dofs(), 0.0);
  for (const CellBlock& block : view.blocks)
    for (PetscInt v : block.vertices)
      for (int d = 0; d < view.dim; ++d) local[v * view.dim + d] += 1.0;
  OwnedVec global = dofs.create_global_vector();
  dofs.add_local_to_global(local, global);
  std::vector<double> back(dofs.num_local_dofs());
  dofs.global_to_local(global, back);
  const auto count = incidence(serial.view());
  for (PetscInt v = 0; v < view.num_vertices; ++v)
    for (int d = 0; d < view.dim; ++d) EXPECT_EQ(back[v * view.dim + d], count.at(point(view, v)));
  dofs.sum_over_ranks(local);  // the same round trip in one call
  EXPECT_EQ(local, back);
}

TEST_P(Distributed, CoordinatesRoundTripIncludingGhosts) {
  PlexMesh mesh = load_mesh(data_path(GetParam()));
  const std::vector<double> before = mesh.view().coords;
  OwnedVec x = mesh.coordinates();
  NM_PETSC(VecScale(x, 3.0));
  mesh.set_coordinates(x);
  for (std::size_t i = 0; i < before.size(); ++i)
    EXPECT_DOUBLE_EQ(mesh.view().coords[i], 3.0 * before[i]);
}

TEST_P(Distributed, WritesTheSameFileAsSerial) {
  const auto dir = testing::shared_scratch_dir("Distributed.WritesTheSameFileAsSerial");
  PlexMesh mesh = load_mesh(data_path(GetParam()));
  MeshFields fields;
  fields.cell.push_back({"input_cell", {}, 1});
  for (PetscInt c : mesh.view().global_cell) fields.cell[0].values.push_back(c);
  for (const char* ext : {".msh", ".vtu"}) write_mesh(mesh, dir / (std::string("p") + ext), fields);
  if (mpi_rank() == 0) {
    PlexMesh serial = load_mesh(data_path(GetParam()), PETSC_COMM_SELF);
    MeshFields serial_fields;
    serial_fields.cell.push_back({"input_cell", {}, 1});
    for (PetscInt c : serial.view().global_cell) serial_fields.cell[0].values.push_back(c);
    for (const char* ext : {".msh", ".vtu"}) {
      write_mesh(serial, dir / (std::string("s") + ext), serial_fields);
      EXPECT_EQ(read_file(dir / (std::string("p") + ext)),
                read_file(dir / (std::string("s") + ext)))
          << ext;
    }
  }
}

// The input's data follow the input numbering through a distributed read and write, in every
// format that keeps them: each vertex's "x" stays its x coordinate, each cell's "cx" the x of its
// centroid and (but in Exodus, which orders cells by block) "cell" its number.
TEST_P(Distributed, CarriesTheInputDataInItsNumbering) {
  const auto dir = testing::shared_scratch_dir("Distributed.CarriesTheInputData");
  if (mpi_rank() == 0) {
    PlexMesh serial = load_mesh(data_path(GetParam()), PETSC_COMM_SELF);
    const MeshView& view = serial.view();
    MeshFields fields;
    fields.cell.push_back({"cell", {view.global_cell.begin(), view.global_cell.end()}, 1});
    fields.cell.push_back({"cx", std::vector<double>(view.num_cells), 1});
    for (const CellBlock& block : view.blocks)
      for (PetscInt c = 0; c < block.size(); ++c) {
        double sum = 0;
        for (int i = 0; i < block.nodes(); ++i) sum += view.coords[block.cell(c)[i] * view.dim];
        fields.cell[1].values[block.first_cell + c] = sum / block.nodes();
      }
    fields.vertex.push_back({"x", {}, 1});
    for (PetscInt v = 0; v < view.num_vertices; ++v)
      fields.vertex[0].values.push_back(view.coords[v * view.dim]);
    write_mesh(serial, dir / "in.vtu", fields);
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  PlexMesh mesh = load_mesh(dir / "in.vtu");
  const std::vector<std::string> formats = {".vtu", ".vtk", ".exo"};
  for (const std::string& ext : formats) write_mesh(mesh, dir / ("p" + ext));
  if (mpi_rank() != 0) return;
  for (const std::string& ext : formats) {
    PlexMesh back = load_mesh(dir / ("p" + ext), PETSC_COMM_SELF);
    const GatheredMesh g = gather_mesh(back, {});
    ASSERT_EQ(g.mesh.point_data.size(), 1u) << ext;
    ASSERT_EQ(g.mesh.cell_data.size(), 2u) << ext;
    const std::vector<double>& x = g.mesh.point_data[0].values;
    ASSERT_EQ(x.size(), static_cast<std::size_t>(g.mesh.num_vertices())) << ext;
    for (PetscInt v = 0; v < g.mesh.num_vertices(); ++v)
      EXPECT_EQ(x[v], g.mesh.coords[v * g.mesh.dim]) << ext << " vertex " << v;
    const std::vector<double>& cell = g.mesh.cell_data[0].values;
    const std::vector<double>& cx = g.mesh.cell_data[1].values;
    ASSERT_EQ(cell.size(), static_cast<std::size_t>(g.mesh.num_cells())) << ext;
    for (PetscInt c = 0; c < g.mesh.num_cells(); ++c) {
      if (ext != ".exo") {
        EXPECT_EQ(cell[c], c) << ext;
      }
      double sum = 0;
      const PetscInt n = g.mesh.cell_offsets[c + 1] - g.mesh.cell_offsets[c];
      for (PetscInt i = g.mesh.cell_offsets[c]; i < g.mesh.cell_offsets[c + 1]; ++i)
        sum += g.mesh.coords[g.mesh.cell_vertices[i] * g.mesh.dim];
      EXPECT_NEAR(cx[c], sum / n, 1e-12) << ext << " cell " << c;
    }
  }
  // The same file as a serial run writes.
  PlexMesh serial = load_mesh(dir / "in.vtu", PETSC_COMM_SELF);
  write_mesh(serial, dir / "s.vtu");
  EXPECT_EQ(read_file(dir / "p.vtu"), read_file(dir / "s.vtu"));
}

INSTANTIATE_TEST_SUITE_P(Files, Distributed,
                         ::testing::Values("square_quad_v41.msh", "cube_tet_v41.msh",
                                           "mixed_tri_quad_v41.msh", "feat_square_quad.xml"),
                         [](const auto& info) {
                           std::string name = info.param;
                           return name.substr(0, name.find('.'));
                         });

TEST(DistributedErrors, BadFileThrowsOnEveryRank) {
  EXPECT_THROW(load_mesh(data_path("bad_inverted.msh")), Error);
  EXPECT_THROW(load_mesh(data_path("bad_mixed_dim.msh")), Error);
  EXPECT_THROW(load_mesh(data_path("bad_truncated.msh")), Error);
}

}  // namespace
}  // namespace neomesh
