// The node orders of curved_type.hpp against the files' own tables, written out here as the
// manuals give them: each node of a format's list must be the Gmsh node on the same corners.
#include "mesh/curved_type.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <vector>

#include <gtest/gtest.h>

namespace neomesh {
namespace {

using Corners = std::set<int>;

// Per node after the corners, the corners of its edge or face (all corners: the centre).
std::vector<Corners> gmsh_nodes(CurvedType t) {
  const CurvedFacts& f = facts(t);
  std::vector<Corners> out;
  for (const CurvedEdge& e : f.edges) out.push_back({e[0], e[1]});
  for (const CurvedFace& face : f.faces) out.push_back(Corners(face.begin(), face.end()));
  Corners all;
  for (int i = 0; i < num_vertices(f.linear); ++i) all.insert(i);
  while (static_cast<int>(out.size()) < f.nodes - num_vertices(f.linear)) out.push_back(all);
  return out;
}

void expect_order(CurvedType t, const std::array<std::uint8_t, kMaxCurvedNodes>& order,
                  const std::map<int, Corners>& manual, const char* format) {
  const int corners = num_vertices(facts(t).linear);
  const std::vector<Corners> gmsh = gmsh_nodes(t);
  ASSERT_EQ(static_cast<int>(manual.size()), facts(t).nodes - corners) << name(t) << format;
  for (int p = 0; p < corners; ++p) EXPECT_EQ(order[p], p) << name(t) << " " << format;
  for (const auto& [p, on] : manual)
    EXPECT_EQ(gmsh[order[p] - corners], on) << name(t) << " " << format << " node " << p;
  std::vector<int> sorted(order.begin(), order.begin() + facts(t).nodes);
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < facts(t).nodes; ++i) EXPECT_EQ(sorted[i], i) << name(t) << format;
}

const Corners kHexahedron = {0, 1, 2, 3, 4, 5, 6, 7};
const Corners kQuadrilateral = {0, 1, 2, 3};

// Exodus II: Ioss' element topologies (edge_node_order, face_node_order), 0-based.
TEST(CurvedType, ExodusOrdersAreIossTopologies) {
  const std::map<int, Corners> triangle = {{3, {0, 1}}, {4, {1, 2}}, {5, {2, 0}}};
  std::map<int, Corners> quadrilateral = {{4, {0, 1}}, {5, {1, 2}}, {6, {2, 3}}, {7, {3, 0}}};
  const std::map<int, Corners> tetrahedron = {{4, {0, 1}}, {5, {1, 2}}, {6, {2, 0}},
                                              {7, {0, 3}}, {8, {1, 3}}, {9, {2, 3}}};
  std::map<int, Corners> hexahedron = {{8, {0, 1}},  {9, {1, 2}},  {10, {2, 3}}, {11, {3, 0}},
                                       {12, {0, 4}}, {13, {1, 5}}, {14, {2, 6}}, {15, {3, 7}},
                                       {16, {4, 5}}, {17, {5, 6}}, {18, {6, 7}}, {19, {7, 4}}};
  expect_order(CurvedType::Triangle6, facts(CurvedType::Triangle6).exodus_order, triangle, "exo");
  expect_order(CurvedType::Quadrilateral8, facts(CurvedType::Quadrilateral8).exodus_order,
               quadrilateral, "exo");
  expect_order(CurvedType::Tetrahedron10, facts(CurvedType::Tetrahedron10).exodus_order,
               tetrahedron, "exo");
  expect_order(CurvedType::Hexahedron20, facts(CurvedType::Hexahedron20).exodus_order, hexahedron,
               "exo");
  quadrilateral[8] = kQuadrilateral;
  expect_order(CurvedType::Quadrilateral9, facts(CurvedType::Quadrilateral9).exodus_order,
               quadrilateral, "exo");
  hexahedron.insert({{20, kHexahedron},
                     {21, {0, 3, 2, 1}},
                     {22, {4, 5, 6, 7}},
                     {23, {0, 4, 7, 3}},
                     {24, {1, 2, 6, 5}},
                     {25, {0, 1, 5, 4}},
                     {26, {2, 3, 7, 6}}});
  expect_order(CurvedType::Hexahedron27, facts(CurvedType::Hexahedron27).exodus_order, hexahedron,
               "exo");
  std::map<int, Corners> wedge = {{6, {0, 1}},  {7, {1, 2}},  {8, {2, 0}},
                                  {9, {0, 3}},  {10, {1, 4}}, {11, {2, 5}},
                                  {12, {3, 4}}, {13, {4, 5}}, {14, {5, 3}}};
  expect_order(CurvedType::Wedge15, facts(CurvedType::Wedge15).exodus_order, wedge, "exo");
  wedge.insert({{15, {0, 1, 4, 3}}, {16, {1, 2, 5, 4}}, {17, {0, 3, 5, 2}}});
  expect_order(CurvedType::Wedge18, facts(CurvedType::Wedge18).exodus_order, wedge, "exo");
}

// CGNS: SIDS, "Unstructured Grid Element Numbering Conventions" (1-based there).
TEST(CurvedType, CgnsOrdersAreTheSids) {
  const std::map<int, Corners> tetrahedron = {{4, {0, 1}}, {5, {1, 2}}, {6, {2, 0}},
                                              {7, {0, 3}}, {8, {1, 3}}, {9, {2, 3}}};
  std::map<int, Corners> hexahedron = {{8, {0, 1}},  {9, {1, 2}},  {10, {2, 3}}, {11, {3, 0}},
                                       {12, {0, 4}}, {13, {1, 5}}, {14, {2, 6}}, {15, {3, 7}},
                                       {16, {4, 5}}, {17, {5, 6}}, {18, {6, 7}}, {19, {7, 4}}};
  expect_order(CurvedType::Tetrahedron10, facts(CurvedType::Tetrahedron10).cgns_order, tetrahedron,
               "cgns");
  expect_order(CurvedType::Hexahedron20, facts(CurvedType::Hexahedron20).cgns_order, hexahedron,
               "cgns");
  hexahedron.insert({{20, {0, 1, 2, 3}},
                     {21, {0, 1, 5, 4}},
                     {22, {1, 2, 6, 5}},
                     {23, {2, 3, 7, 6}},
                     {24, {0, 4, 7, 3}},
                     {25, {4, 5, 6, 7}},
                     {26, kHexahedron}});
  expect_order(CurvedType::Hexahedron27, facts(CurvedType::Hexahedron27).cgns_order, hexahedron,
               "cgns");
  // PENTA_15/18: the bottom triangle's edges, the vertical ones, the top triangle's, then the
  // faces (1,2,5,4) (2,3,6,5) (3,1,4,6) (1-based): Ioss' order.
  for (CurvedType t : {CurvedType::Triangle6, CurvedType::Quadrilateral8,
                       CurvedType::Quadrilateral9, CurvedType::Wedge15, CurvedType::Wedge18})
    EXPECT_EQ(facts(t).cgns_order, facts(t).exodus_order) << name(t);
}

// VTK's (vtkQuadraticTetra, vtkTriQuadraticHexahedron), which the readers already rely on.
TEST(CurvedType, VtkOrdersPlaceEachNodeOnItsEdgeOrFace) {
  std::map<int, Corners> hexahedron = {
      {8, {0, 1}},        {9, {1, 2}},        {10, {2, 3}},       {11, {3, 0}},
      {12, {4, 5}},       {13, {5, 6}},       {14, {6, 7}},       {15, {7, 4}},
      {16, {0, 4}},       {17, {1, 5}},       {18, {2, 6}},       {19, {3, 7}},
      {20, {0, 3, 7, 4}}, {21, {1, 2, 6, 5}}, {22, {0, 1, 5, 4}}, {23, {3, 2, 6, 7}},
      {24, {0, 1, 2, 3}}, {25, {4, 5, 6, 7}}, {26, kHexahedron}};
  expect_order(CurvedType::Hexahedron27, facts(CurvedType::Hexahedron27).vtk_order, hexahedron,
               "vtk");
  // vtkLagrangeWedge (PointIndexFromIJK at order 2): Gmsh's corners, the bottom and the top
  // triangle's cycles, the vertical edges, the faces y = 0, x + y = 1, x = 0.
  std::map<int, Corners> lagrange = {{6, {0, 1}},        {7, {1, 2}},        {8, {2, 0}},
                                     {9, {3, 4}},        {10, {4, 5}},       {11, {5, 3}},
                                     {12, {0, 3}},       {13, {1, 4}},       {14, {2, 5}},
                                     {15, {0, 1, 4, 3}}, {16, {1, 2, 5, 4}}, {17, {0, 2, 5, 3}}};
  expect_order(CurvedType::Wedge18, facts(CurvedType::Wedge18).lagrange_order, lagrange,
               "vtk lagrange");
  // vtkQuadraticWedge and vtkBiQuadraticQuadraticWedge: the same list in VTK's own corner
  // numbering, whose corners 1 and 2 (4 and 5) are Gmsh's 2 and 1 (5 and 4).
  constexpr std::array<int, 6> gmsh_corner = {0, 2, 1, 3, 5, 4};
  for (CurvedType t : {CurvedType::Wedge15, CurvedType::Wedge18}) {
    const auto& order = facts(t).vtk_order;
    for (int p = 0; p < 6; ++p) EXPECT_EQ(order[p], gmsh_corner[p]) << name(t);
    const std::vector<Corners> gmsh = gmsh_nodes(t);
    for (const auto& [p, on] : lagrange) {
      if (p >= facts(t).nodes) continue;
      Corners mapped;
      for (int c : on) mapped.insert(gmsh_corner[c]);
      EXPECT_EQ(gmsh[order[p] - 6], mapped) << name(t) << " vtk node " << p;
    }
  }
}

}  // namespace
}  // namespace neomesh
