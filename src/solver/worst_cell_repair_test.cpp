#include "solver/worst_cell_repair.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "generate/generate.hpp"
#include "generate/serial_view.hpp"
#include "geometry/quality.hpp"
#include "solver/testing/coordinates.hpp"

namespace neomesh {
namespace {

using testing::vector_of;

std::vector<double> scaled_jacobians(const MeshView& view, Vec x) {
  VecReadView xv(x);
  return cell_scaled_jacobians(view, std::span<const double>(xv.data(), xv.size()));
}

// A uniform 6×6 grid with one interior vertex pushed towards a neighbour: its four cells are
// the worst; moving it (and its neighbours) back lifts them, boundary vertices stay.
TEST(WorstCellRepair, LiftsTheWorstCellsAndNeverLowersTheMinimum) {
  MeshData grid = square_random(6, 0.0, 3);
  const PetscInt bad_vertex = 8;
  grid.coords[2 * bad_vertex] += 0.12;
  grid.coords[2 * bad_vertex + 1] += 0.05;
  const MeshView view = serial_view(grid);
  const DofMap dofs = DofMap::serial(2, view.num_vertices);
  OwnedVec x = vector_of(dofs, grid.coords);
  const std::vector<double> before = scaled_jacobians(view, x);
  const double worst_before = *std::min_element(before.begin(), before.end());
  ASSERT_LT(worst_before, 0.8) << "the setup must make a bad cell";
  RepairFreedom freedom{.fixed = std::vector<std::uint8_t>(2 * view.num_vertices),
                        .geometry = std::vector<int>(view.num_vertices, -1),
                        .project = {}};
  for (PetscInt v = 0; v < view.num_vertices; ++v)
    freedom.fixed[2 * v] = freedom.fixed[2 * v + 1] = view.on_boundary[v];

  const WorstCellRepair r = repair_worst_cells(view, dofs, freedom, x);

  const std::vector<double> after = scaled_jacobians(view, x);
  const double worst_after = *std::min_element(after.begin(), after.end());
  EXPECT_DOUBLE_EQ(r.min_before, worst_before);
  EXPECT_DOUBLE_EQ(r.min_after, worst_after);
  EXPECT_GT(worst_after, 0.95) << "the grid's own cells are squares";
  EXPECT_GE(r.vertices_moved, 1);
  EXPECT_GE(r.sweeps, 1);
  VecReadView xv(x);
  for (PetscInt v = 0; v < view.num_vertices; ++v)
    if (view.on_boundary[v]) {
      EXPECT_EQ(xv[2 * v], grid.coords[2 * v]) << "boundary vertex " << v;
      EXPECT_EQ(xv[2 * v + 1], grid.coords[2 * v + 1]) << "boundary vertex " << v;
    }
}

// Boundary vertices slide: one on the bottom side pushed along it comes back along it, kept on
// its geometry (the line y = 0, by projection), and one on the left side pushed along it comes
// back with its fixed coordinate x untouched.
TEST(WorstCellRepair, SlidesBoundaryVerticesAlongTheirGeometry) {
  MeshData grid = square_random(6, 0.0, 3);
  auto vertex_at = [&grid](double x, double y) {
    for (std::size_t v = 0; 2 * v < grid.coords.size(); ++v)
      if (std::abs(grid.coords[2 * v] - x) < 1e-12 && std::abs(grid.coords[2 * v + 1] - y) < 1e-12)
        return static_cast<PetscInt>(v);
    ADD_FAILURE() << "no vertex at " << x << ", " << y;
    return PetscInt{0};
  };
  const PetscInt bottom = vertex_at(0.5, 0.0), left = vertex_at(0.0, 0.5);
  grid.coords[2 * bottom] += 0.12;
  grid.coords[2 * left + 1] += 0.12;
  const MeshView view = serial_view(grid);
  const DofMap dofs = DofMap::serial(2, view.num_vertices);
  OwnedVec x = vector_of(dofs, grid.coords);
  RepairFreedom freedom{.fixed = std::vector<std::uint8_t>(2 * view.num_vertices),
                        .geometry = std::vector<int>(view.num_vertices, -1),
                        .project = [](int g, std::span<double> p) {
                          ASSERT_EQ(g, 0);
                          p[1] = 0.0;
                        }};
  for (PetscInt v = 0; v < view.num_vertices; ++v)
    freedom.fixed[2 * v] = freedom.fixed[2 * v + 1] = view.on_boundary[v];
  freedom.fixed[2 * bottom] = freedom.fixed[2 * bottom + 1] = 0;
  freedom.geometry[bottom] = 0;
  freedom.fixed[2 * left + 1] = 0;

  const WorstCellRepair r = repair_worst_cells(view, dofs, freedom, x);

  EXPECT_LT(r.min_before, 0.85);
  EXPECT_GT(r.min_after, 0.95);
  VecReadView xv(x);
  EXPECT_LT(std::abs(xv[2 * bottom] - 0.5), 0.05) << "slid back towards its place";
  EXPECT_EQ(xv[2 * bottom + 1], 0.0) << "on its geometry";
  EXPECT_LT(std::abs(xv[2 * left + 1] - 0.5), 0.05) << "slid back towards its place";
  EXPECT_EQ(xv[2 * left], 0.0) << "its fixed coordinate";
}

double mean_inverse_mean_ratio(const MeshView& view, Vec x) {
  VecReadView xv(x);
  const std::vector<double> imr =
      cell_inverse_mean_ratios(view, std::span<const double>(xv.data(), xv.size()));
  double sum = 0.0;
  for (double q : imr) sum += q;
  return sum / static_cast<double>(imr.size());
}

// A grid of squares with a fixed boundary vertex pushed along its side: the repair lifts the
// two cells it skews by skewing their interior neighbours, so the mean inverse mean ratio
// rises. With a ceiling it ends at or below it, with -∞ no move raises it, and the worst cell
// is lifted all the same, less.
TEST(WorstCellRepair, KeepsTheMeanInverseMeanRatioBelowItsCeiling) {
  MeshData grid = square_random(6, 0.0, 3);
  for (std::size_t v = 0; 2 * v < grid.coords.size(); ++v)
    if (std::abs(grid.coords[2 * v] - 0.5) < 1e-12 && grid.coords[2 * v + 1] == 0.0)
      grid.coords[2 * v] += 0.12;
  const MeshView view = serial_view(grid);
  const DofMap dofs = DofMap::serial(2, view.num_vertices);
  RepairFreedom freedom{.fixed = std::vector<std::uint8_t>(2 * view.num_vertices),
                        .geometry = std::vector<int>(view.num_vertices, -1),
                        .project = {}};
  for (PetscInt v = 0; v < view.num_vertices; ++v)
    freedom.fixed[2 * v] = freedom.fixed[2 * v + 1] = view.on_boundary[v];
  OwnedVec start = vector_of(dofs, grid.coords);
  const double imr_before = mean_inverse_mean_ratio(view, start);
  constexpr double kNoFloor = -std::numeric_limits<double>::infinity();

  OwnedVec free = vector_of(dofs, grid.coords);
  const WorstCellRepair unbounded = repair_worst_cells(view, dofs, freedom, free);
  const double imr_free = mean_inverse_mean_ratio(view, free);
  ASSERT_GT(imr_free, imr_before) << "the setup must make the repair raise the mean";

  const double ceiling = 0.5 * (imr_before + imr_free);
  OwnedVec half = vector_of(dofs, grid.coords);
  const WorstCellRepair bounded = repair_worst_cells(view, dofs, freedom, half, kNoFloor, ceiling);
  EXPECT_LE(mean_inverse_mean_ratio(view, half), ceiling);
  EXPECT_GT(bounded.min_after, bounded.min_before);

  OwnedVec none = vector_of(dofs, grid.coords);
  const WorstCellRepair kept = repair_worst_cells(view, dofs, freedom, none, kNoFloor, kNoFloor);
  EXPECT_LE(mean_inverse_mean_ratio(view, none), imr_before);
  EXPECT_GT(kept.min_after, kept.min_before);
  EXPECT_LE(kept.min_after, unbounded.min_after);
}

TEST(WorstCellRepair, MovesNothingThatIsNotMovable) {
  MeshData grid = square_random(6, 0.0, 3);
  grid.coords[2 * 8] += 0.12;
  const MeshView view = serial_view(grid);
  const DofMap dofs = DofMap::serial(2, view.num_vertices);
  OwnedVec x = vector_of(dofs, grid.coords);
  const RepairFreedom freedom{.fixed = std::vector<std::uint8_t>(2 * view.num_vertices, 1),
                              .geometry = std::vector<int>(view.num_vertices, -1),
                              .project = {}};
  const WorstCellRepair r = repair_worst_cells(view, dofs, freedom, x);
  EXPECT_EQ(r.vertices_moved, 0);
  EXPECT_EQ(r.min_after, r.min_before);
  VecReadView xv(x);
  for (PetscInt i = 0; i < xv.size(); ++i) EXPECT_EQ(xv[i], grid.coords[i]);
}

}  // namespace
}  // namespace neomesh
