// Mesh::from_dm on 2 processes: a distributed DMPlex that PETSc built comes in with its cells,
// coordinates and vertex numbers.
#include <petscdmda.h>
#include <petscdmplex.h>

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include <neomesh/neomesh.hpp>

#include "core/petsc.hpp"

namespace neomesh {
namespace {

// A box mesh of [0,1]^dim, interpolated and distributed over PETSC_COMM_WORLD: PETSc's own
// for quadrilaterals and hexahedra; triangles (this PETSc has no generator) from a grid of
// squares cut along a diagonal, given by rank 0 in PETSc's (counter-clockwise) order.
DM box(int dim, bool simplex, PetscInt cells) {
  DM dm = nullptr;
  const PetscInt faces[3] = {cells, cells, cells};
  if (!simplex) {
    NM_PETSC(DMPlexCreateBoxMesh(PETSC_COMM_WORLD, dim, PETSC_FALSE, faces, nullptr, nullptr,
                                 nullptr, PETSC_TRUE, &dm));
  } else {
    std::vector<PetscInt> triangles;
    std::vector<PetscReal> coords;
    int rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (rank == 0) {
      for (PetscInt j = 0; j <= cells; ++j)
        for (PetscInt i = 0; i <= cells; ++i)
          coords.insert(coords.end(), {PetscReal(i) / cells, PetscReal(j) / cells});
      for (PetscInt j = 0; j < cells; ++j)
        for (PetscInt i = 0; i < cells; ++i) {
          const PetscInt v = j * (cells + 1) + i, w = v + cells + 1;
          triangles.insert(triangles.end(), {v, v + 1, w + 1, v, w + 1, w});
        }
    }
    NM_PETSC(DMPlexCreateFromCellListPetsc(PETSC_COMM_WORLD, 2,
                                           static_cast<PetscInt>(triangles.size() / 3),
                                           static_cast<PetscInt>(coords.size() / 2), 3, PETSC_TRUE,
                                           triangles.data(), 2, coords.data(), &dm));
  }
  DM distributed = nullptr;
  NM_PETSC(DMPlexDistribute(dm, 0, nullptr, &distributed));
  if (distributed) {
    NM_PETSC(DMDestroy(&dm));
    dm = distributed;
  }
  return dm;
}

struct Case {
  int dim;
  bool simplex;
  std::int64_t cells_per_cube;
};

class FromDm : public ::testing::TestWithParam<Case> {};

TEST_P(FromDm, TakesTheCellsCoordinatesAndVertexNumbers) {
  const Case c = GetParam();
  const PetscInt n = 4;
  DM dm = box(c.dim, c.simplex, n);
  const Mesh mesh = Mesh::from_dm(dm, "box");
  const std::int64_t cubes = c.dim == 2 ? n * n : n * n * n;
  EXPECT_EQ(mesh.num_cells(), c.cells_per_cube * cubes);
  EXPECT_EQ(mesh.num_vertices(), c.dim == 2 ? (n + 1) * (n + 1) : (n + 1) * (n + 1) * (n + 1));
  // Every cell as PETSc built it: valid, and the cubes' volumes sum to 1.
  const QualitySummary q = mesh.quality();
  EXPECT_EQ(q.inverted, 0);
  EXPECT_EQ(q.degenerate, 0);
  EXPECT_NEAR(q.volume.mean * q.cells, 1.0, 1e-12);
  if (!c.simplex) {
    EXPECT_NEAR(q.scaled_jacobian.min, 1.0, 1e-12);
  }

  // Vertex numbers are the DM's: its coordinates of each owned vertex match.
  IS numbering = nullptr;
  NM_PETSC(DMPlexGetVertexNumbering(dm, &numbering));
  const PetscInt* number = nullptr;
  NM_PETSC(ISGetIndices(numbering, &number));
  PetscInt vStart, vEnd;
  NM_PETSC(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  Vec x = nullptr;
  NM_PETSC(DMGetCoordinatesLocal(dm, &x));
  const PetscScalar* coords = nullptr;
  NM_PETSC(VecGetArrayRead(x, &coords));
  std::vector<double> expected(static_cast<std::size_t>(mesh.num_vertices() * c.dim), 0.0);
  for (PetscInt v = vStart; v < vEnd; ++v) {
    const PetscInt g = number[v - vStart] < 0 ? -(number[v - vStart] + 1) : number[v - vStart];
    for (int j = 0; j < c.dim; ++j) expected[g * c.dim + j] = coords[(v - vStart) * c.dim + j];
  }
  NM_PETSC(VecRestoreArrayRead(x, &coords));
  NM_PETSC(ISRestoreIndices(numbering, &number));
  MPI_Allreduce(MPI_IN_PLACE, expected.data(), static_cast<int>(expected.size()), MPI_DOUBLE,
                MPI_MAX, PETSC_COMM_WORLD);  // coordinates are ≥ 0: the owner's value wins
  const std::vector<std::int64_t> numbers = mesh.vertex_numbers();
  const std::vector<double> got = mesh.coordinates();
  for (std::size_t i = 0; i < numbers.size(); ++i)
    for (int j = 0; j < c.dim; ++j)
      EXPECT_DOUBLE_EQ(got[i * c.dim + j], expected[numbers[i] * c.dim + j]);
  NM_PETSC(DMDestroy(&dm));
}

INSTANTIATE_TEST_SUITE_P(EveryBox, FromDm,
                         ::testing::Values(Case{2, false, 1}, Case{2, true, 2}, Case{3, false, 1}));

TEST(FromDm, RefusesWhatItCannotUse) {
  DM da = nullptr;
  NM_PETSC(DMDACreate1d(PETSC_COMM_WORLD, DM_BOUNDARY_NONE, 8, 1, 1, nullptr, &da));
  NM_PETSC(DMSetUp(da));
  EXPECT_THROW(Mesh::from_dm(da, "a DMDA"), Error);
  NM_PETSC(DMDestroy(&da));
  EXPECT_THROW(Mesh::from_dm(nullptr, "nothing"), Error);
}

}  // namespace
}  // namespace neomesh
