// The Functional on a surface mesh: triangles and quadrilaterals in space, each cell's energy the
// surface kernel's in the cell's frame, fixed with the targets (docs/method.md, "Surface cells").
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "energy/functional.hpp"
#include "energy/functional_test_util.hpp"
#include "generate/generate.hpp"
#include "generate/serial_view.hpp"
#include "geometry/quality.hpp"

namespace neomesh {
namespace {

using testing::entry;

// A jittered box [-1,1]² of `type` lifted onto z = height · (1 − x²/2 − y²/3) (a curved
// surface), boundary vertices fixed, desired areas spread by ±40 %.
struct SurfaceCase {
  MeshData data;
  MeshView view;
  DofMap dofs;
  Functional functional;
  OwnedVec x;

  SurfaceCase(CellType type, double height, unsigned seed)
      : data(lifted_box(type, seed)),
        view(surface_view(data, height)),
        dofs(DofMap::serial(3, view.num_vertices)),
        functional(EnergyOptions{}, problem(view, dofs, seed)),
        x(dofs.create_global_vector()) {
    VecWriteView out(x);
    for (std::size_t i = 0; i < view.coords.size(); ++i)
      out[static_cast<PetscInt>(i)] = view.coords[i];
  }
  SurfaceCase(const SurfaceCase&) = delete;

  static MeshData lifted_box(CellType type, unsigned seed) {
    MeshData mesh = box(type, 4);
    jitter(mesh, 0.5, 0.2, seed);
    return mesh;
  }
  static MeshView surface_view(const MeshData& planar, double height) {
    MeshView view = serial_view(planar);
    view.dim = 3;
    view.surface = true;
    view.coords.clear();
    for (std::int64_t v = 0; v < planar.num_vertices(); ++v) {
      const double px = planar.coords[2 * v], py = planar.coords[2 * v + 1];
      view.coords.insert(view.coords.end(), {px, py, height * (1.0 - px * px / 2 - py * py / 3)});
    }
    return view;
  }
  static Problem problem(const MeshView& view, const DofMap& dofs, unsigned seed) {
    std::vector<std::uint8_t> fixed = view.on_boundary;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.6, 1.4);
    std::vector<double> volumes(view.num_cells);
    for (double& v : volumes) v = 0.25 * u(rng);
    return Problem(view, dofs, fixed).with_targets(volumes);
  }
  bool free(PetscInt dof) const { return !view.on_boundary[dof / 3]; }
};

class SurfaceFunctionalTest : public ::testing::TestWithParam<CellType> {};

INSTANTIATE_TEST_SUITE_P(SurfaceCells, SurfaceFunctionalTest,
                         ::testing::Values(CellType::Triangle, CellType::Quadrilateral),
                         [](const auto& info) { return std::string(name(info.param)); });

TEST_P(SurfaceFunctionalTest, GradientMatchesFiniteDifferencesOfValue) {
  SurfaceCase p(GetParam(), 0.6, 31);
  testing::expect_gradient_matches_differences(p.functional, p.x,
                                               [&p](PetscInt i) { return p.free(i); });
}

TEST_P(SurfaceFunctionalTest, HessianMatchesFiniteDifferencesOfGradient) {
  SurfaceCase p(GetParam(), 0.6, 33);
  testing::expect_hessian_matches_differences(p.functional, p.x,
                                              [&p](PetscInt i) { return p.free(i); });
}

// A flat surface in z = 0 is the 2D mesh: the same energy and, in x and y, the same gradient.
TEST_P(SurfaceFunctionalTest, AFlatSurfaceHasThePlanarMeshsEnergyAndGradient) {
  SurfaceCase p(GetParam(), 0.0, 35);
  const MeshView planar = serial_view(p.data);
  const DofMap dofs2 = DofMap::serial(2, planar.num_vertices);
  const Functional flat(EnergyOptions{},
                        Problem(planar, dofs2, planar.on_boundary)
                            .with_targets(p.functional.problem().desired_volumes()));
  OwnedVec x2 = dofs2.create_global_vector(), g2 = dofs2.create_global_vector();
  {
    VecWriteView out(x2);
    for (std::size_t i = 0; i < p.data.coords.size(); ++i)
      out[static_cast<PetscInt>(i)] = p.data.coords[i];
  }
  OwnedVec g3 = p.dofs.create_global_vector();
  const double f2 = flat.value_and_gradient(x2, g2), f3 = p.functional.value_and_gradient(p.x, g3);
  EXPECT_NEAR(f3, f2, 1e-12 * f2);
  for (PetscInt v = 0; v < planar.num_vertices; ++v) {
    EXPECT_NEAR(entry(g3, 3 * v), entry(g2, 2 * v), 1e-10) << v;
    EXPECT_NEAR(entry(g3, 3 * v + 1), entry(g2, 2 * v + 1), 1e-10) << v;
    EXPECT_NEAR(entry(g3, 3 * v + 2), 0.0, 1e-12) << v;
  }
  EXPECT_NEAR(mesh_volume(p.view, p.dofs, p.x), mesh_volume(planar, dofs2, x2), 1e-13);
}

// Refreshed frames follow the cells: a surface turned as a whole in space has, in the frames
// taken where it is, the energy it had; in the frames of where it was, it has another.
TEST_P(SurfaceFunctionalTest, RefreshedFramesFollowTheCellsAsTheyTurn) {
  SurfaceCase p(GetParam(), 0.6, 37);
  const double before = p.functional.value(p.x);
  {
    VecWriteView x(p.x);
    const double c = std::cos(0.3), s = std::sin(0.3);
    for (PetscInt v = 0; v < p.view.num_vertices; ++v) {  // turn by 0.3 about the x axis
      const double y = x[3 * v + 1], z = x[3 * v + 2];
      x[3 * v + 1] = c * y - s * z;
      x[3 * v + 2] = s * y + c * z;
    }
  }
  EXPECT_GT(std::abs(p.functional.value(p.x) - before), 1e-3 * before);
  EXPECT_TRUE(p.functional.refresh_frames(p.x));
  EXPECT_NEAR(p.functional.value(p.x), before, 1e-12 * before);
}

// The quality of a surface cell is taken along its own reference normal: on the lifted surface
// as surface_cell_scaled_jacobian says, on a flat one as the planar cell's.
TEST_P(SurfaceFunctionalTest, QualityIsTakenAlongEachCellsOwnNormal) {
  for (const double height : {0.6, 0.0}) {
    SurfaceCase p(GetParam(), height, 39);
    const std::vector<double> sj = cell_scaled_jacobians(p.view, p.view.coords);
    const std::vector<double> planar = cell_scaled_jacobians(serial_view(p.data), p.data.coords);
    const CellBlock& block = p.view.blocks[0];
    const int n = num_vertices(block.type);
    for (PetscInt c = 0; c < block.size(); ++c) {
      Eigen::Matrix<double, 3, 4> x;
      for (int i = 0; i < n; ++i)
        x.col(i) = Eigen::Map<const Vector<3>>(p.view.coords.data() + 3 * block.cell(c)[i]);
      const Vector<3> normal =
          block.type == CellType::Triangle
              ? (x.col(1) - x.col(0)).cross(x.col(2) - x.col(0)).normalized().eval()
              : (x.col(3) - x.col(0)).cross(x.col(2) - x.col(1)).normalized().eval();
      EXPECT_DOUBLE_EQ(sj[c], surface_cell_scaled_jacobian(block.type, x.data(), normal.data()));
      if (height == 0.0) {
        EXPECT_NEAR(sj[c], planar[c], 1e-14);
      }
    }
  }
}

// With the frames taken where it is, a triangle mesh's gradient is that of the energy of its
// cells as they lie (each in the frame of its own plane, taken again at every point): the
// frame's derivative does not change it (docs/method.md, "Surface cells").
TEST(SurfaceFunctional, TheGradientInRefreshedFramesIsThatOfTheCellsAsTheyLie) {
  SurfaceCase p(CellType::Triangle, 0.6, 41);
  OwnedVec gradient = p.dofs.create_global_vector();
  ASSERT_TRUE(p.functional.refresh_frames(p.x));
  p.functional.value_and_gradient(p.x, gradient);
  const auto as_they_lie = [&p] {
    p.functional.refresh_frames(p.x);
    return p.functional.value(p.x);
  };
  const double step = 1e-7;
  double error = 0.0, size = 0.0;
  for (PetscInt i = 0; i < p.dofs.num_global_dofs(); ++i) {
    if (!p.free(i)) continue;
    const double saved = entry(p.x, i);
    testing::set_entry(p.x, i, saved + step);
    const double plus = as_they_lie();
    testing::set_entry(p.x, i, saved - step);
    const double minus = as_they_lie();
    testing::set_entry(p.x, i, saved);
    error += std::pow((plus - minus) / (2 * step) - entry(gradient, i), 2);
    size += std::pow(entry(gradient, i), 2);
  }
  EXPECT_LT(std::sqrt(error), testing::kFdTolerance * std::sqrt(size));
}

}  // namespace
}  // namespace neomesh
