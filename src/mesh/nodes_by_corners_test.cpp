// Finding a curved mesh's edge and face nodes by their corners, in whichever order a cell lists
// them.
#include "mesh/nodes_by_corners.hpp"

#include <gtest/gtest.h>

#include <array>
#include <numeric>
#include <vector>

namespace neomesh {
namespace {

TEST(NodesByCorners, FindsANodeByItsCornersInAnyOrderAndKeepsTheFirst) {
  NodesByCorners nodes;
  EXPECT_TRUE(nodes.empty());
  EXPECT_EQ(nodes.add(std::array<PetscInt, 2>{7, 3}, 20), 20);
  EXPECT_EQ(nodes.add(std::array<PetscInt, 2>{3, 7}, 21), 20);  // the edge has its node
  EXPECT_EQ(nodes.add(std::array<PetscInt, 4>{9, 3, 7, 1}, 22), 22);
  EXPECT_EQ(nodes.find(std::array<PetscInt, 2>{3, 7}), 20);
  EXPECT_EQ(nodes.find(std::array<PetscInt, 4>{1, 7, 9, 3}), 22);
  // Other corners, or some of a face's, are another entity.
  EXPECT_EQ(nodes.find(std::array<PetscInt, 2>{3, 9}), -1);
  EXPECT_EQ(nodes.find(std::array<PetscInt, 3>{1, 7, 9}), -1);
  EXPECT_FALSE(nodes.empty());
}

TEST(NodesByCorners, ACellsEdgeAndFaceNodesAreFoundByTheirCorners) {
  // A hexahedron27 with points numbered backwards, so that the corners' order and the points'
  // differ: each of its edge and face nodes, in Gmsh's order, by its corners reversed.
  std::array<PetscInt, 27> points;
  std::iota(points.rbegin(), points.rend(), 100);
  NodesByCorners nodes;
  nodes.add_cell(CurvedType::Hexahedron27, points.data());
  const CurvedFacts& f = facts(CurvedType::Hexahedron27);
  int node = 8;
  for (const CurvedEdge& e : f.edges)
    EXPECT_EQ(nodes.find(std::array{points[e[1]], points[e[0]]}), points[node++]);
  for (const CurvedFace& q : f.faces)
    EXPECT_EQ(nodes.find(std::array{points[q[3]], points[q[2]], points[q[1]], points[q[0]]}),
              points[node++]);
  EXPECT_EQ(node, 26);
  // The centre is no edge's or face's.
  EXPECT_EQ(nodes.find(std::span(points.data(), 8)), -1);
}

}  // namespace
}  // namespace neomesh
