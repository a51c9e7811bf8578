// The Functional on curved cells (CellBlock::curved): its gradient and H(α) against finite
// differences, on cells that share nodes.
#include <gtest/gtest.h>

#include <random>

#include "energy/functional.hpp"
#include "energy/functional_test_util.hpp"
#include "geometry/curved_cell.hpp"
#include "geometry/node_mesh.hpp"

namespace neomesh {
namespace {

// Two quadrilateral9 side by side on [0, 2] × [0, 1], sharing the edge x = 1 (its corners and
// mid-node), every node moved by up to 4% of the edge.
MeshView two_bent_quadrilaterals() {
  MeshView view;
  view.dim = 2;
  view.num_vertices = 15;
  // Cell A's nodes 0–8 in Gmsh's order; B's corners 0 and 3 and its mid-node 7 are A's 1, 2, 5.
  const std::vector<PetscInt> a = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  const std::vector<PetscInt> b = {1, 9, 10, 2, 11, 12, 13, 5, 14};
  CellBlock block{CellType::Quadrilateral, 0, {}, CurvedType::Quadrilateral9};
  block.vertices.insert(block.vertices.end(), a.begin(), a.end());
  block.vertices.insert(block.vertices.end(), b.begin(), b.end());
  view.blocks.push_back(block);
  view.num_cells = 2;
  view.coords.assign(2 * 15, 0.0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.04, 0.04);
  for (int cell = 0; cell < 2; ++cell)
    for (int i = 0; i < 9; ++i) {
      const auto xi = reference_node<CurvedType::Quadrilateral9>(i);
      const PetscInt v = (cell == 0 ? a : b)[i];
      view.coords[2 * v] = 0.5 * (xi[0] + 1) + cell;
      view.coords[2 * v + 1] = 0.5 * (xi[1] + 1);
    }
  for (double& x : view.coords) x += u(rng);
  view.owned.assign(15, 1);
  view.on_boundary.assign(15, 0);
  view.global_cell = {0, 1};
  return view;
}

TEST(CurvedFunctional, GradientAndHessianMatchFiniteDifferences) {
  const MeshView view = two_bent_quadrilaterals();
  const DofMap dofs = DofMap::serial(2, view.num_vertices);
  // Desired volumes unlike the cells' so that the volume terms act too.
  const std::vector<double> volumes = {0.8, 1.3};
  const Functional f(EnergyOptions{},
                     Problem(view, dofs, std::vector<std::uint8_t>(15, 0)).with_targets(volumes));
  OwnedVec x = dofs.create_global_vector();
  {
    VecWriteView out(x);
    for (std::size_t i = 0; i < view.coords.size(); ++i)
      out[static_cast<PetscInt>(i)] = view.coords[i];
  }
  const auto every = [](PetscInt) { return true; };
  testing::expect_gradient_matches_differences(f, x, every);
  testing::expect_hessian_matches_differences(f, x, every);
  // The volumes the Functional measures are the cells' exact ones.
  const std::vector<double> exact = curved_cell_volumes(view, view.coords);
  const CellFields fields = f.cell_fields(x);
  for (int c = 0; c < 2; ++c)
    EXPECT_NEAR(fields.volume_ratio[c] * volumes[c], exact[c], 1e-12 * exact[c]);
  EXPECT_NEAR(mesh_volume(view, dofs, x), exact[0] + exact[1], 1e-12);
}

}  // namespace
}  // namespace neomesh
