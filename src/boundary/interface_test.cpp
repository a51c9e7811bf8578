#include "boundary/interface.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "core/error.hpp"
#include "generate/generate.hpp"
#include "generate/serial_view.hpp"

namespace neomesh {
namespace {

Interface find_serial(const MeshView& view, const LevelSetFunction& phi) {
  return find_interface(view, DofMap::serial(view.dim, view.num_vertices), view.coords, phi);
}

// How many interface facets hold each edge of the interface's facets (3D) or each vertex
// (2D): exactly 2 everywhere for a closed chain or surface without pinches.
std::map<std::pair<PetscInt, PetscInt>, int> ridge_counts(const Interface& in, int dim) {
  std::map<std::pair<PetscInt, PetscInt>, int> count;
  for (PetscInt f = 0; f < in.num_facets(); ++f) {
    const PetscInt begin = in.offsets[f], n = in.offsets[f + 1] - begin;
    for (PetscInt k = 0; k < n; ++k) {
      const PetscInt a = in.facet_vertices[begin + k];
      const PetscInt b = dim == 2 ? a : in.facet_vertices[begin + (k + 1) % n];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  }
  return count;
}

// The facets of the interface form one connected piece.
bool connected(const Interface& in) {
  std::map<PetscInt, std::vector<PetscInt>> facets_of;
  for (PetscInt f = 0; f < in.num_facets(); ++f)
    for (PetscInt k = in.offsets[f]; k < in.offsets[f + 1]; ++k)
      facets_of[in.facet_vertices[k]].push_back(f);
  std::set<PetscInt> seen = {0};
  std::vector<PetscInt> todo = {0};
  while (!todo.empty()) {
    const PetscInt f = todo.back();
    todo.pop_back();
    for (PetscInt k = in.offsets[f]; k < in.offsets[f + 1]; ++k)
      for (PetscInt g : facets_of[in.facet_vertices[k]])
        if (seen.insert(g).second) todo.push_back(g);
  }
  return static_cast<PetscInt>(seen.size()) == in.num_facets();
}

void expect_closed(CellType type, int n, const std::string& phi_expression) {
  const MeshData data = box(type, n);
  const MeshView view = serial_view(data);
  const LevelSetFunction phi(phi_expression, view.dim);
  const Interface in = find_serial(view, phi);
  ASSERT_GT(in.num_facets(), 0);
  for (const auto& [ridge, count] : ridge_counts(in, view.dim))
    EXPECT_EQ(count, 2) << name(type) << ": vertex/edge " << ridge.first << "-" << ridge.second;
  EXPECT_TRUE(connected(in)) << name(type);
  for (PetscInt u : in.vertices) EXPECT_FALSE(view.on_boundary[u]);
}

TEST(FindInterface, IsAClosedChainOfEdgesAroundACircle) {
  expect_closed(CellType::Quadrilateral, 32, "sqrt(x^2+y^2)-0.35");
  expect_closed(CellType::Triangle, 32, "sqrt(x^2+y^2)-0.35");
  expect_closed(CellType::Quadrilateral, 32, "sqrt(x^2+(y-0.3)^2)-0.2");
}

TEST(FindInterface, IsAClosedSurfaceOfFacesAroundASphere) {
  expect_closed(CellType::Hexahedron, 8, "sqrt(x^2+y^2+z^2)-0.6");
  expect_closed(CellType::Tetrahedron, 6, "sqrt(x^2+y^2+z^2)-0.6");
}

// A triangle with two edges on the interface would end with three vertices on the circle.
TEST(FindInterface, LeavesNoTriangleWithTwoInterfaceEdges) {
  const MeshData data = box(CellType::Triangle, 32);
  const MeshView view = serial_view(data);
  const Interface in = find_serial(view, LevelSetFunction("sqrt(x^2+y^2)-0.35", 2));
  std::set<std::pair<PetscInt, PetscInt>> edges;
  for (PetscInt f = 0; f < in.num_facets(); ++f) {
    const PetscInt a = in.facet_vertices[2 * f], b = in.facet_vertices[2 * f + 1];
    edges.insert({std::min(a, b), std::max(a, b)});
  }
  const CellBlock& block = view.blocks[0];
  for (PetscInt c = 0; c < block.size(); ++c) {
    int on = 0;
    for (int i = 0; i < 3; ++i) {
      const PetscInt a = block.cell(c)[i], b = block.cell(c)[(i + 1) % 3];
      on += edges.contains({std::min(a, b), std::max(a, b)});
    }
    EXPECT_LE(on, 1) << "triangle " << c;
  }
  EXPECT_GT(in.cells_flipped, 0);
}

TEST(FindInterface, NeedsBothSignsAndAnInterfaceInsideTheDomain) {
  const MeshData data = box(CellType::Quadrilateral, 8);
  const MeshView view = serial_view(data);
  EXPECT_THROW(find_serial(view, LevelSetFunction("x^2+y^2+1", 2)), Error);
  EXPECT_THROW(find_serial(view, LevelSetFunction("x-0.1", 2)), Error);
}

// Stage 0 moves nothing; stage 1 puts every interface vertex on the zero set.
TEST(InterfaceConstraint, PullsTheVerticesOntoTheZeroSetInStages) {
  const MeshData data = box(CellType::Quadrilateral, 16);
  const MeshView view = serial_view(data);
  const DofMap dofs = DofMap::serial(view.dim, view.num_vertices);
  const LevelSetFunction phi("sqrt(x^2+y^2)-0.5", 2);
  const Interface in = find_serial(view, phi);
  OwnedVec x = dofs.create_global_vector();
  {
    double* a = nullptr;
    VecGetArray(x, &a);
    std::copy(view.coords.begin(), view.coords.end(), a);
    VecRestoreArray(x, &a);
  }
  InterfaceConstraint constraint(view, dofs, phi, in.vertices, x);
  const double start = constraint.max_distance(x);
  constraint.project(x);
  EXPECT_NEAR(constraint.max_distance(x), start, 1e-12);
  constraint.set_stage(0.5);
  constraint.project(x);
  EXPECT_NEAR(constraint.max_distance(x), start / 2, 0.02 * start);
  constraint.set_stage(1.0);
  constraint.project(x);
  EXPECT_LT(constraint.max_distance(x), 1e-12);
}

TEST(JoinSlidingVertices, KeepsEachVertexsValuesInAscendingOrder) {
  auto fill = [](double base) {
    return [base](std::span<const double>, std::span<double> out) {
      for (std::size_t i = 0; i < out.size(); ++i) out[i] = base + static_cast<double>(i);
    };
  };
  SlidingVertices a{{1, 5}, fill(100), [](Vec) {}};
  SlidingVertices b{{2, 3, 9}, fill(200), [](Vec) {}};
  const SlidingVertices j = join(a, b);
  EXPECT_EQ(j.vertices, (std::vector<PetscInt>{1, 2, 3, 5, 9}));
  const int size = tangent_space_size(2);
  std::vector<double> out(5 * size);
  j.tangent_spaces({}, out);
  EXPECT_EQ(out[0], 100);     // vertex 1: a's first
  EXPECT_EQ(out[size], 200);  // vertex 2: b's first
  EXPECT_EQ(out[2 * size], 200 + size);
  EXPECT_EQ(out[3 * size], 100 + size);
  EXPECT_EQ(out[4 * size], 200 + 2 * size);
}

}  // namespace
}  // namespace neomesh
