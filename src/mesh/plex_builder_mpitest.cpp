// Under `mpiexec -n 2` (or more): distribute_plex makes the DM that DMPlexDistribute makes for
// the same parts, point for point, with the same migration.
#include "mesh/plex_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <span>
#include <utility>
#include <vector>

#include "mesh/facet_table.hpp"

namespace neomesh {
namespace {

// An n × n grid of quads, and triangles where every third square is split if `split`, on rank
// 0, its vertices numbered backwards so that cells and vertices are not in the same order.
InputMesh grid(int n, bool split) {
  InputMesh mesh;
  if (mpi_rank(MPI_COMM_WORLD) != 0) return mesh;
  const PetscInt nv = (n + 1) * (n + 1);
  mesh.coords.resize(2 * nv);
  auto number = [&](int i, int j) { return nv - 1 - (j * (n + 1) + i); };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      mesh.coords[2 * number(i, j)] = 1.0 * i / n;
      mesh.coords[2 * number(i, j) + 1] = 1.0 * j / n;
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const PetscInt a = number(i, j), b = number(i + 1, j), c = number(i + 1, j + 1),
                     d = number(i, j + 1);
      if (split && (i + 2 * j) % 3 == 0) {
        const PetscInt t1[3] = {a, b, c}, t2[3] = {a, c, d};
        mesh.add_cell(CellType::Triangle, t1, 0);
        mesh.add_cell(CellType::Triangle, t2, 0);
      } else {
        const PetscInt q[4] = {a, b, c, d};
        mesh.add_cell(CellType::Quadrilateral, q, 0);
      }
    }
  return mesh;
}

struct Graph {
  PetscInt roots = 0;
  std::vector<PetscInt> local;                        // per leaf, its point
  std::vector<std::pair<PetscInt, PetscInt>> remote;  // per leaf, its root's rank and point
};

Graph graph_of(PetscSF sf) {
  PetscInt roots = 0, leaves = 0;
  const PetscInt* local = nullptr;
  const PetscSFNode* remote = nullptr;
  NM_PETSC(PetscSFGetGraph(sf, &roots, &leaves, &local, &remote));
  Graph g{roots, {}, {}};
  for (PetscInt i = 0; i < leaves; ++i) {
    g.local.push_back(local ? local[i] : i);
    g.remote.emplace_back(remote[i].rank, remote[i].index);
  }
  return g;
}

// Per point of `dm`, its cone.
std::vector<std::vector<PetscInt>> cones(DM dm) {
  PetscInt start = 0, end = 0;
  NM_PETSC(DMPlexGetChart(dm, &start, &end));
  std::vector<std::vector<PetscInt>> all;
  for (PetscInt p = start; p < end; ++p) {
    PetscInt n = 0;
    const PetscInt* cone = nullptr;
    NM_PETSC(DMPlexGetConeSize(dm, p, &n));
    NM_PETSC(DMPlexGetCone(dm, p, &cone));
    all.emplace_back(cone, cone + n);
  }
  return all;
}

std::vector<double> coordinates(DM dm) {
  Vec local = nullptr;
  NM_PETSC(DMGetCoordinatesLocal(dm, &local));
  PetscInt n = 0;
  const PetscScalar* values = nullptr;
  NM_PETSC(VecGetLocalSize(local, &n));
  NM_PETSC(VecGetArrayRead(local, &values));
  std::vector<double> all(values, values + n);
  NM_PETSC(VecRestoreArrayRead(local, &values));
  return all;
}

// This rank's cells by their point in rank 0's mesh (from the migration).
std::vector<PetscInt> cells_of_rank(const Distributed& d) {
  const Graph migration = graph_of(d.migration);
  PetscInt cells = 0;
  NM_PETSC(DMPlexGetHeightStratum(d.dm, 0, nullptr, &cells));
  std::vector<PetscInt> mine;
  for (std::size_t i = 0; i < migration.local.size(); ++i)
    if (migration.local[i] < cells) mine.push_back(migration.remote[i].second);
  return mine;
}

// One cell type: the migration is made in DMPlex's order; several: it is stratified by type.
class DistributePlex : public testing::TestWithParam<bool> {};

TEST_P(DistributePlex, MakesWhatDMPlexDistributeMakesOfTheSameParts) {
  const InputMesh input = grid(12, /*split=*/GetParam());
  CellGraph cell_graph;
  if (mpi_rank(MPI_COMM_WORLD) == 0) cell_graph = FacetTable(input).cell_graph();
  OwnedDM ours_from = build_plex(MPI_COMM_WORLD, input);
  Distributed ours = distribute_plex(ours_from, cell_graph);
  ASSERT_TRUE(ours.dm);

  // The parts ours made (each rank's cells, from its migration), for DMPlexDistribute.
  const Graph migration = graph_of(ours.migration);
  const std::vector<PetscInt> mine = cells_of_rank(ours);
  EXPECT_FALSE(mine.empty());
  int size = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(size), displacements(size, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  for (int r = 1; r < size; ++r) displacements[r] = displacements[r - 1] + counts[r - 1];
  std::vector<PetscInt> points(mpi_rank(MPI_COMM_WORLD) == 0 ? displacements.back() + counts.back()
                                                             : 0);
  MPI_Gatherv(mine.data(), count, MPIU_INT, points.data(), counts.data(), displacements.data(),
              MPIU_INT, 0, MPI_COMM_WORLD);
  std::vector<PetscInt> sizes(counts.begin(), counts.end());
  if (mpi_rank(MPI_COMM_WORLD) != 0) std::fill(sizes.begin(), sizes.end(), 0);

  OwnedDM theirs_from = build_plex(MPI_COMM_WORLD, input);
  PetscOwner<PetscPartitioner, PetscPartitionerDestroy> shell;
  NM_PETSC(PetscPartitionerCreate(MPI_COMM_WORLD, shell.out()));
  NM_PETSC(PetscPartitionerSetType(shell, PETSCPARTITIONERSHELL));
  NM_PETSC(PetscPartitionerShellSetPartition(shell, size, sizes.data(), points.data()));
  NM_PETSC(DMPlexSetPartitioner(theirs_from, shell));
  OwnedDM theirs;
  OwnedSF their_migration;
  NM_PETSC(DMPlexDistribute(theirs_from, 0, their_migration.out(), theirs.out()));
  ASSERT_TRUE(theirs);

  // The same points, from the same roots, in the same order.
  const Graph their_graph = graph_of(their_migration);
  std::vector<PetscInt> ours_original(migration.local.size()), theirs_original(ours_original);
  ASSERT_EQ(their_graph.local.size(), migration.local.size());
  for (std::size_t i = 0; i < migration.local.size(); ++i) {
    ours_original[migration.local[i]] = migration.remote[i].second;
    theirs_original[their_graph.local[i]] = their_graph.remote[i].second;
  }
  EXPECT_EQ(ours_original, theirs_original);
  EXPECT_EQ(cones(ours.dm), cones(theirs));
  EXPECT_EQ(coordinates(ours.dm), coordinates(theirs));
  PetscSF ours_points = nullptr, their_points = nullptr;
  NM_PETSC(DMGetPointSF(ours.dm, &ours_points));
  NM_PETSC(DMGetPointSF(theirs, &their_points));
  const Graph a = graph_of(ours_points), b = graph_of(their_points);
  EXPECT_EQ(a.roots, b.roots);
  EXPECT_EQ(a.local, b.local);
  EXPECT_EQ(a.remote, b.remote);
  DMLabel ours_types = nullptr, their_types = nullptr;
  NM_PETSC(DMPlexGetCellTypeLabel(ours.dm, &ours_types));
  NM_PETSC(DMPlexGetCellTypeLabel(theirs, &their_types));
  PetscInt start = 0, end = 0;
  NM_PETSC(DMPlexGetChart(ours.dm, &start, &end));
  for (PetscInt p = start; p < end; ++p) {
    PetscInt x = -1, y = -1;
    NM_PETSC(DMLabelGetValue(ours_types, p, &x));
    NM_PETSC(DMLabelGetValue(their_types, p, &y));
    EXPECT_EQ(x, y) << "point " << p;
  }
}

INSTANTIATE_TEST_SUITE_P(CellTypes, DistributePlex, testing::Values(false, true));

// Per cell of rank 0's mesh, the rank it went to (on rank 0; empty elsewhere).
std::vector<int> rank_of_cells(const Distributed& d, PetscInt num_cells) {
  std::vector<int> rank(num_cells, -1), owner(num_cells, -1);
  for (PetscInt c : cells_of_rank(d)) rank[c] = mpi_rank(MPI_COMM_WORLD);
  MPI_Reduce(rank.data(), owner.data(), static_cast<int>(num_cells), MPI_INT, MPI_MAX, 0,
             MPI_COMM_WORLD);
  return mpi_rank(MPI_COMM_WORLD) == 0 ? owner : std::vector<int>{};
}

TEST(DistributePlexGroups, KeepEachGroupOnOneRank) {
  const InputMesh input = grid(12, /*split=*/true);
  PetscInt nc = input.num_cells();
  MPI_Bcast(&nc, 1, MPIU_INT, 0, MPI_COMM_WORLD);
  CellGraph cell_graph;
  std::vector<PetscInt> pairs, singles;  // groups of 2 consecutive cells; of 1
  if (mpi_rank(MPI_COMM_WORLD) == 0) {
    cell_graph = FacetTable(input).cell_graph();
    for (PetscInt c = 0; c < nc; c += 2) pairs.push_back(c);
    pairs.push_back(nc);
    for (PetscInt c = 0; c <= nc; ++c) singles.push_back(c);
  }
  const auto ranks = [&](std::span<const PetscInt> groups) {
    OwnedDM from = build_plex(MPI_COMM_WORLD, input);
    return rank_of_cells(distribute_plex(from, cell_graph, groups), nc);
  };
  const std::vector<int> grouped = ranks(pairs), alone = ranks(singles), plain = ranks({});
  if (mpi_rank(MPI_COMM_WORLD) != 0) return;
  for (PetscInt c = 0; c + 1 < nc; c += 2) EXPECT_EQ(grouped[c], grouped[c + 1]) << "cell " << c;
  EXPECT_EQ(std::count(grouped.begin(), grouped.end(), -1), 0);
  EXPECT_GT(std::count(grouped.begin(), grouped.end(), 1), nc / 4);
  EXPECT_GT(std::count(grouped.begin(), grouped.end(), 0), nc / 4);
  // Groups of one cell are the cells: the same graph, the same parts.
  EXPECT_EQ(alone, plain);
  EXPECT_NE(grouped, plain);
}

}  // namespace
}  // namespace neomesh
