// Untangling (solver/untangle.hpp) on jittered boxes whose interior vertices moved far enough
// to fold cells over, then the Neo-Hookean phase: no inverted cell at the end.
#include "solver/untangle.hpp"

#include <gtest/gtest.h>

#include "generate/generate.hpp"
#include "solver/testing/thesis_problem.hpp"

namespace neomesh {
namespace {

struct Outcome {
  UntangleResult untangling;
  SolverRun smoothing;
  PetscInt inverted_at_end = 0;
};

// [-1,1]^d with n cells per direction, interior vertices jittered by ±amplitude·h, fixed
// boundary; untangled, then smoothed with the default (not the thesis') options.
Outcome untangle_and_smooth(CellType type, int n, double amplitude, unsigned seed) {
  MeshData mesh = box(type, n);
  jitter(mesh, 2.0 / n, amplitude, seed);
  ThesisProblem p(std::move(mesh));
  QuasiNewtonOptions options;
  options.energy_roundoff = energy_roundoff(p.energy, p.view.dim, p.volume);
  Outcome o;
  o.untangling = untangle(*p.functional, p.x, options, p.cell_size);
  if (o.untangling.after.count == 0) o.smoothing = p.minimize(options);
  o.inverted_at_end = p.functional->inversion(p.x).count;
  return o;
}

void print(const char* name, const Outcome& o) {
  std::printf(
      "%s: %ld inverted -> %ld after %zu untangling iterations in %d rounds (%.2f s); "
      "then %zu iterations (%s)\n",
      name, long(o.untangling.before.count), long(o.untangling.after.count),
      o.untangling.history.size(), o.untangling.rounds, o.untangling.seconds,
      o.smoothing.history.size(), describe(o.smoothing.reason).c_str());
}

struct TangledBox {
  const char* name;
  CellType type;
  int cells_per_direction;
  double amplitude;  // jitter, in cell widths
  PetscInt at_least_inverted;
};

class UntangleBox : public ::testing::TestWithParam<TangledBox> {};

TEST_P(UntangleBox, ComesOutWithNoInvertedCell) {
  const TangledBox& c = GetParam();
  const Outcome o = untangle_and_smooth(c.type, c.cells_per_direction, c.amplitude, 1);
  print(c.name, o);
  EXPECT_GE(o.untangling.before.count, c.at_least_inverted) << "the case must be tangled";
  EXPECT_EQ(o.untangling.after.count, 0);
  EXPECT_EQ(o.inverted_at_end, 0);
  EXPECT_NE(o.smoothing.reason, StopReason::LineSearchFailed);
}

// The cases (quads 100² at ±0.5 h, hexes 20³ at ±0.4 h: several hundred inverted),
// and smaller triangle and tet cases.
INSTANTIATE_TEST_SUITE_P(
    JitteredBoxes, UntangleBox,
    ::testing::Values(TangledBox{"quads_100x100_half_h", CellType::Quadrilateral, 100, 0.5, 500},
                      TangledBox{"hexes_20x20x20_0_4h", CellType::Hexahedron, 20, 0.4, 500},
                      TangledBox{"triangles_40x40_half_h", CellType::Triangle, 40, 0.5, 50},
                      TangledBox{"tets_8x8x8_0_6h", CellType::Tetrahedron, 8, 0.6, 100}),
    [](const auto& info) { return std::string(info.param.name); });

// A moving boundary pushed through the cells: the bottom face of [-1,1]³ bulged up by
// 0.8 (1 − x²)(1 − y²), the cells above it left where they were. With the boundary fixed the
// cells above must move far and together: several rounds of ε, and the untangling energy
// changes sign on the way (which once made ε NaN).
TEST(Untangle, HexBoxWithItsBottomPushedThroughTheCells) {
  MeshData mesh = box(CellType::Hexahedron, 12);
  for (std::size_t v = 0; v < mesh.coords.size(); v += 3) {
    double* x = mesh.coords.data() + v;
    if (x[2] == -1.0) x[2] += 0.8 * (1 - x[0] * x[0]) * (1 - x[1] * x[1]);
  }
  ThesisProblem p(std::move(mesh));
  QuasiNewtonOptions options;
  options.energy_roundoff = energy_roundoff(p.energy, p.view.dim, p.volume);
  const UntangleResult r = untangle(*p.functional, p.x, options, p.cell_size);
  std::printf("bumped hex box: %ld inverted -> %ld in %zu iterations, %d rounds\n",
              long(r.before.count), long(r.after.count), r.history.size(), r.rounds);
  EXPECT_GE(r.before.count, 100);
  EXPECT_EQ(r.after.count, 0);
  EXPECT_GE(r.rounds, 2) << "the case must need more than one value of epsilon";
  EXPECT_NE(p.minimize(options).reason, StopReason::LineSearchFailed);
  EXPECT_EQ(p.functional->inversion(p.x).count, 0);
}

TEST(Untangle, ValidMeshIsLeftAlone) {
  MeshData mesh = box(CellType::Quadrilateral, 6);
  jitter(mesh, 2.0 / 6, 0.2, 5);
  ThesisProblem p(std::move(mesh));
  const UntangleResult r = untangle(*p.functional, p.x, QuasiNewtonOptions{}, p.cell_size);
  EXPECT_EQ(r.before.count, 0);
  EXPECT_TRUE(r.history.empty());
}

// Two quads, every vertex on the (fixed) boundary, one folded over the other: nothing can
// move, so the result names the folded cell.
TEST(Untangle, FixedBoundaryThatFoldsCannotBeUntangled) {
  MeshData mesh = box(CellType::Quadrilateral, 1);
  ThesisProblem p(std::move(mesh));
  {
    VecWriteView x(p.x);
    std::swap(x[0], x[2]);  // vertices 0 and 1 trade x: the quad is a bow tie
  }
  const UntangleResult r = untangle(*p.functional, p.x, QuasiNewtonOptions{}, p.cell_size,
                                    UntangleOptions{.max_rounds = 5});
  EXPECT_EQ(r.before.count, 1);
  EXPECT_EQ(r.after.count, 1);
  ASSERT_EQ(r.after.cells.size(), 1u);
  EXPECT_EQ(r.after.cells[0], 0);
}

}  // namespace
}  // namespace neomesh
