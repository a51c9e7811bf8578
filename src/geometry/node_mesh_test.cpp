#include "geometry/node_mesh.hpp"

#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "geometry/curved_cell.hpp"
#include "geometry/quality.hpp"
#include "geometry/testing/curved_types.hpp"

namespace neomesh {

namespace {

using neomesh::testing::for_each_curved_type;

// One curved cell `x` (Gmsh's node order) as a mesh: its corners are vertices 0, 1, ... in
// Gmsh's order, its other nodes the high-order nodes.
template <CurvedType Type>
InputMesh one_cell(const typename CurvedTraits<Type>::Nodes& x) {
  using Traits = CurvedTraits<Type>;
  InputMesh mesh;
  mesh.dim = Traits::dim;
  for (int k = 0; k < Traits::corners; ++k)
    for (int j = 0; j < Traits::dim; ++j) mesh.coords.push_back(x(j, k));
  std::array<PetscInt, Traits::corners> canonical;
  for (int i = 0; i < Traits::corners; ++i) canonical[i] = linear_corners<Type>()[i];
  mesh.add_cell(Traits::linear, canonical.data(), 5);
  std::vector<PetscInt> nodes;
  for (int i = Traits::corners; i < Traits::nodes; ++i) {
    nodes.push_back(i - Traits::corners);
    for (int j = 0; j < 3; ++j) mesh.high_order.xyz.push_back(j < Traits::dim ? x(j, i) : 0.0);
  }
  mesh.high_order.add(Type, nodes.data());
  return mesh;
}

// A cell with bent edges: the straight cell of a skewed map, every higher-order node moved.
template <CurvedType Type>
typename CurvedTraits<Type>::Nodes bent_cell() {
  using Traits = CurvedTraits<Type>;
  Matrix<Traits::dim> a = Matrix<Traits::dim>::Identity();
  a(0, 1) = 0.3;
  Eigen::Matrix<double, Traits::dim, Traits::corners> corners;
  const auto order = linear_corners<Type>();
  for (int i = 0; i < Traits::corners; ++i) corners.col(i) = a * reference_node<Type>(order[i]);
  typename Traits::Nodes x = straight_curved_cell<Type>(corners);
  for (int i = Traits::corners; i < Traits::nodes; ++i)
    for (int j = 0; j < Traits::dim; ++j) x(j, i) += 0.03 * ((i * 7 + j * 3) % 5 - 2);
  return x;
}

TEST(NodeMesh, EveryNodeIsAVertexAndTheSubcellsTileTheCell) {
  for_each_curved_type([]<CurvedType Type>() {
    using Traits = CurvedTraits<Type>;
    const auto x = bent_cell<Type>();
    const InputMesh curved = one_cell<Type>(x);
    const NodeMesh nodes = node_mesh(curved);
    const InputMesh& m = nodes.mesh;
    EXPECT_EQ(nodes.points, Traits::nodes);
    // The serendipity cells' missing lattice points: the centre, and a hexahedron's 6 faces';
    // a wedge15's 3 quadrilateral faces'.
    const int virtual_vertices = Type == CurvedType::Quadrilateral8 ? 1
                                 : Type == CurvedType::Hexahedron20 ? 7
                                 : Type == CurvedType::Wedge15      ? 3
                                                                    : 0;
    EXPECT_EQ(m.num_vertices(), Traits::nodes + virtual_vertices);
    ASSERT_EQ(m.num_cells(), 1 << Traits::dim);
    std::set<PetscInt> used;
    double volume = 0.0;
    for (PetscInt c = 0; c < m.num_cells(); ++c) {
      EXPECT_EQ(m.cell_types[c], Traits::linear);
      EXPECT_EQ(m.cell_tags[c], 5);
      std::vector<double> coords;
      for (PetscInt k = m.cell_offsets[c]; k < m.cell_offsets[c + 1]; ++k) {
        used.insert(m.cell_vertices[k]);
        for (int j = 0; j < Traits::dim; ++j)
          coords.push_back(m.coords[Traits::dim * m.cell_vertices[k] + j]);
      }
      EXPECT_GT(cell_scaled_jacobian(Traits::linear, coords.data()), 0.0) << "sub-cell " << c;
      // The straight sub-cell's volume, as a view of it alone measures it.
      MeshView view;
      view.dim = Traits::dim;
      view.num_vertices = static_cast<PetscInt>(coords.size()) / Traits::dim;
      view.num_cells = 1;
      CellBlock block{Traits::linear, 0, {}};
      for (PetscInt i = 0; i < view.num_vertices; ++i) block.vertices.push_back(i);
      view.blocks.push_back(block);
      volume += cell_volumes(view, coords)[0];
    }
    EXPECT_EQ(static_cast<PetscInt>(used.size()), m.num_vertices());
    // The sub-cells are straight, the cell curved: they cover about the same region.
    EXPECT_NEAR(volume, curved_volume<Type>(x), 0.05 * volume);
  });
}

TEST(NodeMesh, TheCurvedVolumeIsTheStraightCellsForAStraightCell) {
  for_each_curved_type([]<CurvedType Type>() {
    using Traits = CurvedTraits<Type>;
    Eigen::Matrix<double, Traits::dim, Traits::corners> corners;
    const auto order = linear_corners<Type>();
    for (int i = 0; i < Traits::corners; ++i)
      corners.col(i) = 2.0 * reference_node<Type>(order[i]) + Vector<Traits::dim>::Constant(0.1);
    const double reference = Traits::simplex ? (Traits::dim == 2 ? 0.5 : 1.0 / 6)
                             : Traits::wedge ? 1.0
                                             : 1 << Traits::dim;
    EXPECT_NEAR(curved_volume<Type>(straight_curved_cell<Type>(corners)),
                reference * (1 << Traits::dim), 1e-12);
  });
}

TEST(NodeMesh, BoundaryFacetsInGroupsAreSplitAtTheirNodes) {
  // Two quadrilateral9 side by side; the left edge of the left one in a group.
  const auto x = bent_cell<CurvedType::Quadrilateral9>();
  InputMesh curved = one_cell<CurvedType::Quadrilateral9>(x);
  const PetscInt edge[2] = {0, 3};  // Gmsh corners 0 and 3: the side x = −1
  curved.facets.add(edge, 2, 9);
  curved.groups.push_back({1, 9, "left"});
  const NodeMesh nodes = node_mesh(curved);
  ASSERT_EQ(nodes.mesh.facets.size(), 2);
  // Gmsh's quadrilateral9 node 7, the mid-node of the edge (3, 0), is point 7 (the corners, then
  // the other nodes).
  const PetscInt mid = 7;
  for (PetscInt f = 0; f < 2; ++f) {
    EXPECT_EQ(nodes.mesh.facets.tags[f], 9);
    const PetscInt* v = nodes.mesh.facets.vertices.data() + nodes.mesh.facets.offsets[f];
    EXPECT_TRUE(v[0] == mid || v[1] == mid);
  }
}

}  // namespace

}  // namespace neomesh
