#include "solver/quality_guard.hpp"

#include <gtest/gtest.h>

#include "generate/generate.hpp"
#include "generate/serial_view.hpp"
#include "geometry/quality.hpp"
#include "solver/testing/coordinates.hpp"

namespace neomesh {
namespace {

using testing::vector_of;

double min_scaled_jacobian(const MeshView& view, Vec x) {
  VecReadView xv(x);
  const std::vector<double> sj =
      cell_quality(view, std::span<const double>(xv.data(), xv.size())).scaled_jacobian;
  return *std::min_element(sj.begin(), sj.end());
}

// Input: a jittered 6×6 grid. "Optimized": the uniform grid, except that vertex 8 (interior)
// went too far and made its cells worse than the input's worst.
TEST(QualityGuard, PullsBackOnlyTheVerticesOfCellsWorseThanTheInputsWorst) {
  const MeshData jittered = square_random(6, 0.2, 3);
  MeshData uniform = square_random(6, 0.0, 3);
  const PetscInt bad_vertex = 8;
  uniform.coords[2 * bad_vertex] += 0.14;
  uniform.coords[2 * bad_vertex + 1] += 0.06;
  const MeshView view = serial_view(jittered);
  const DofMap dofs = DofMap::serial(2, view.num_vertices);
  OwnedVec input = vector_of(dofs, jittered.coords), x = vector_of(dofs, uniform.coords);
  const double input_min = min_scaled_jacobian(view, input);
  ASSERT_LT(min_scaled_jacobian(view, x), input_min) << "the setup must make a cell worse";

  const QualityGuardResult r = guard_worst_quality(view, dofs, input, x);

  EXPECT_DOUBLE_EQ(r.input_min, input_min);
  EXPECT_GE(min_scaled_jacobian(view, x), input_min);
  EXPECT_GE(r.min_after, input_min);
  EXPECT_GE(r.vertices_moved, 1);
  EXPECT_LE(r.vertices_moved, 9) << "only the bad vertex and its neighbours";
  // A vertex far from the bad one keeps its optimized (uniform-grid) position.
  VecReadView xv(x);
  const PetscInt far = 40;  // (4, 5) in the 7×7 vertex lattice
  EXPECT_DOUBLE_EQ(xv[2 * far], uniform.coords[2 * far]);
  EXPECT_DOUBLE_EQ(xv[2 * far + 1], uniform.coords[2 * far + 1]);
}

TEST(QualityGuard, LeavesAMeshThatIsNoWorseUntouched) {
  const MeshData jittered = square_random(6, 0.2, 3);
  const MeshData uniform = square_random(6, 0.0, 3);
  const MeshView view = serial_view(jittered);
  const DofMap dofs = DofMap::serial(2, view.num_vertices);
  OwnedVec input = vector_of(dofs, jittered.coords), x = vector_of(dofs, uniform.coords);
  const QualityGuardResult r = guard_worst_quality(view, dofs, input, x);
  EXPECT_EQ(r.vertices_moved, 0);
  EXPECT_EQ(r.rounds, 0);
  EXPECT_DOUBLE_EQ(r.min_after, 1.0);
}

}  // namespace
}  // namespace neomesh
