// Raising straight meshes to second order (mesh/raise_order.hpp) and putting their boundary on
// its geometry (curve_boundary.hpp); here because the certificate is geometry's.
#include "boundary/curve_boundary.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "core/error.hpp"
#include "generate/generate.hpp"
#include "geometry/curved_quality.hpp"
#include "geometry/quality.hpp"
#include "mesh/raise_order.hpp"

namespace neomesh {

namespace {

InputMesh raised(const MeshData& data) {
  InputMesh mesh = input_from_data(data);
  raise_to_second_order(mesh);
  return mesh;
}

// The box [-1,1]³ pushed out onto the unit sphere: each point scaled by |x|∞ / |x|₂.
MeshData ball(int n) {
  MeshData data = box(CellType::Tetrahedron, n);
  for (std::size_t i = 0; i < data.coords.size(); i += 3) {
    double* x = data.coords.data() + i;
    const double inf = std::max({std::abs(x[0]), std::abs(x[1]), std::abs(x[2])});
    const double two = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    if (two > 0)
      for (int j = 0; j < 3; ++j) x[j] *= inf / two;
  }
  return data;
}

// The distance of `p` (coord_dim values) from the origin.
double radius(const double* p, int dim) {
  double r = 0.0;
  for (int j = 0; j < dim; ++j) r += p[j] * p[j];
  return std::sqrt(r);
}

// The sides (2D: edges, 3D: faces) of the cells, as sorted corner points, and how many cells
// share each: those of one cell are the boundary.
std::map<std::vector<PetscInt>, int> sides(const InputMesh& mesh) {
  std::map<std::vector<PetscInt>, int> count;
  std::array<PetscInt, kMaxCurvedNodes> p{};
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    curved_cell_points(mesh, c, p.data());
    const CurvedFacts& f = facts(mesh.high_order.types[c]);
    std::vector<std::vector<PetscInt>> all;
    if (mesh.dim == 2)
      for (const CurvedEdge& e : f.edges) all.push_back({p[e[0]], p[e[1]]});
    else if (f.linear == CellType::Tetrahedron)
      all = {{p[0], p[1], p[2]}, {p[0], p[1], p[3]}, {p[0], p[2], p[3]}, {p[1], p[2], p[3]}};
    else
      for (const CurvedFace& k : f.faces) all.push_back({p[k[0]], p[k[1]], p[k[2]], p[k[3]]});
    for (auto& side : all) {
      std::sort(side.begin(), side.end());
      ++count[side];
    }
  }
  return count;
}

// Over every edge and (hexahedron27) face of the boundary whose corners all lie at distance R
// from the origin (dims = 2: from the z axis): the largest |r − R| of its node, and how many
// such nodes.
std::pair<double, int> off_radius(const InputMesh& mesh, double R, int dims) {
  const std::vector<double> x = curved_point_coordinates(mesh);
  const int cd = mesh.coord_dim();
  const auto off = [&](PetscInt point) { return std::abs(radius(&x[cd * point], dims) - R); };
  const auto all_on = [&](const std::vector<PetscInt>& corners) {
    return std::all_of(corners.begin(), corners.end(), [&](PetscInt v) { return off(v) < 1e-9; });
  };
  std::set<std::vector<PetscInt>> boundary;  // the boundary's sides and their edges
  for (const auto& [side, cells] : sides(mesh)) {
    if (cells != 1) continue;
    boundary.insert(side);
    for (std::size_t i = 0; i < side.size(); ++i)
      for (std::size_t j = i + 1; j < side.size(); ++j) boundary.insert({side[i], side[j]});
  }
  double worst = 0.0;
  std::set<PetscInt> nodes;
  std::array<PetscInt, kMaxCurvedNodes> p{};
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    curved_cell_points(mesh, c, p.data());
    const CurvedFacts& f = facts(mesh.high_order.types[c]);
    const int corners = num_vertices(f.linear);
    std::vector<std::pair<std::vector<PetscInt>, PetscInt>> entities;  // corners, node
    for (std::size_t e = 0; e < f.edges.size(); ++e)
      entities.push_back({{p[f.edges[e][0]], p[f.edges[e][1]]}, p[corners + e]});
    for (std::size_t k = 0; k < f.faces.size(); ++k)
      entities.push_back({{p[f.faces[k][0]], p[f.faces[k][1]], p[f.faces[k][2]], p[f.faces[k][3]]},
                          p[corners + f.edges.size() + k]});
    for (auto& [key, node] : entities) {
      std::sort(key.begin(), key.end());
      if (!boundary.count(key) || !all_on(key)) continue;
      worst = std::max(worst, off(node));
      nodes.insert(node);
    }
  }
  return {worst, static_cast<int>(nodes.size())};
}

}  // namespace

TEST(RaiseOrder, KeepsTheStraightMapOfEveryCellAndTheVertices) {
  for (CellType type : {CellType::Triangle, CellType::Quadrilateral, CellType::Tetrahedron,
                        CellType::Hexahedron, CellType::Wedge}) {
    MeshData data = box(type, 3);
    jitter(data, 2.0 / 3.0, 0.15, 7);
    const InputMesh straight = input_from_data(data);
    const InputMesh mesh = raised(data);
    EXPECT_EQ(mesh.coords, straight.coords) << name(type);
    const std::vector<double> x = curved_point_coordinates(mesh);
    const int d = mesh.dim;
    for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
      std::vector<double> corners;
      for (PetscInt i = mesh.cell_offsets[c]; i < mesh.cell_offsets[c + 1]; ++i)
        for (int j = 0; j < d; ++j) corners.push_back(mesh.coords[d * mesh.cell_vertices[i] + j]);
      const CurvedScaledJacobian q = curved_cell_quality(mesh, x, c);
      ASSERT_EQ(q.certificate.validity, Validity::Valid) << name(type) << " cell " << c;
      EXPECT_NEAR(q.scaled_jacobian, cell_scaled_jacobian(type, corners.data()), 1e-12)
          << name(type) << " cell " << c;
    }
  }
}

TEST(RaiseOrder, CreatesOneNodePerEdgeFaceAndCentreAsEulerCountsThem) {
  // 2D box of n² squares: V − E + F = 1.
  const int n = 3;
  const PetscInt v2 = (n + 1) * (n + 1);
  const InputMesh triangles = raised(box(CellType::Triangle, n));
  EXPECT_EQ(triangles.high_order.num_nodes(), v2 + 2 * n * n - 1);  // the edges
  const InputMesh quads = raised(box(CellType::Quadrilateral, n));
  EXPECT_EQ(quads.high_order.num_nodes(), (v2 + n * n - 1) + n * n);  // edges and centres
  // 3D: V − E + F − C = 1; the tetrahedra's faces are (4C + boundary faces) / 2, the box's
  // boundary 6 n² squares split in two.
  const PetscInt v3 = (n + 1) * (n + 1) * (n + 1);
  const PetscInt tets = 6 * n * n * n, tet_faces = (4 * tets + 12 * n * n) / 2;
  EXPECT_EQ(raised(box(CellType::Tetrahedron, n)).high_order.num_nodes(),
            v3 + tet_faces - tets - 1);
  const PetscInt hexes = n * n * n, hex_faces = (6 * hexes + 6 * n * n) / 2;
  const PetscInt hex_edges = v3 + hex_faces - hexes - 1;
  EXPECT_EQ(raised(box(CellType::Hexahedron, n)).high_order.num_nodes(),
            hex_edges + hex_faces + hexes);
}

TEST(RaiseOrder, RefusesPyramidsAndCurvedMeshesInOneLine) {
  InputMesh pyramids = input_from_data(box(CellType::Pyramid, 2));
  try {
    raise_to_second_order(pyramids);
    ADD_FAILURE() << "pyramids raised";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("pyramid"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
  InputMesh twice = raised(box(CellType::Triangle, 2));
  EXPECT_THROW(raise_to_second_order(twice), Error);
}

TEST(CurveBoundary, PutsTheNodesOfArcsOnTheirCirclesAndLeavesStraightPartsStraight) {
  for (CellType type : {CellType::Triangle, CellType::Quadrilateral}) {
    InputMesh mesh = raised(quarter_annulus(type, 4));
    const CurvedBoundarySummary s =
        place_boundary_nodes(mesh, {{"inner", "circle:0,0,1"}, {"outer", "circle:0,0,2"}});
    const auto [inner_off, inner_nodes] = off_radius(mesh, 1.0, 2);
    const auto [outer_off, outer_nodes] = off_radius(mesh, 2.0, 2);
    EXPECT_LE(inner_off, 1e-12) << name(type);
    EXPECT_LE(outer_off, 1e-12) << name(type);
    EXPECT_EQ(inner_nodes, 4);
    EXPECT_EQ(outer_nodes, 4);
    EXPECT_EQ(s.nodes_on_geometry, 8);
    EXPECT_EQ(s.nodes_straight, 8);  // the 4 + 4 edges at θ = 0 and π/2
    EXPECT_LE(s.max_off_geometry, 1e-12);
    // A quarter annulus in 4 cells per arc bends gently: every cell stays valid.
    EXPECT_EQ(curved_quality(mesh).not_valid, 0) << name(type);
  }
}

TEST(CurveBoundary, PutsEdgeAndFaceNodesOnACylinderAndASphere) {
  InputMesh shell = raised(quarter_annulus(CellType::Hexahedron, 3));
  const CurvedBoundarySummary s = place_boundary_nodes(
      shell, {{"inner", "cylinder:0,0,0,0,0,1,1"}, {"outer", "cylinder:0,0,0,0,0,1,2"}});
  EXPECT_LE(off_radius(shell, 1.0, 2).first, 1e-12);
  EXPECT_LE(off_radius(shell, 2.0, 2).first, 1e-12);
  // Per arc face: 3 × 3 squares with 24 edges and 9 face nodes.
  EXPECT_EQ(s.nodes_on_geometry, 2 * (24 + 9));
  EXPECT_EQ(curved_quality(shell).not_valid, 0);

  InputMesh sphere = raised(ball(4));
  std::vector<std::pair<std::string, std::string>> shapes;
  for (const char* side : {"left", "right", "bottom", "top", "front", "back"})
    shapes.emplace_back(side, "sphere:0,0,0,1");
  const CurvedBoundarySummary t = place_boundary_nodes(sphere, shapes);
  const auto [off, nodes] = off_radius(sphere, 1.0, 3);
  EXPECT_LE(off, 1e-12);
  EXPECT_GT(nodes, 0);
  EXPECT_EQ(nodes, t.nodes_on_geometry);
  EXPECT_EQ(t.nodes_straight, 0);
  EXPECT_LE(t.max_off_geometry, 1e-12);
}

TEST(CurveBoundary, AThinLayerUnderACoarselyBentBoundaryBendsWithIt) {
  // With 6 cells around, the chords of the inner circle (r = 1/2, the domain outside it) pass
  // 0.5 (1 − cos π/6) ≈ 0.067 inside it; their nodes, put on it, push that far into layers
  // 0.0625 thick, past the straight centre nodes. Carried into the interior, that move bends
  // the layers with the circle, and no cell folds; the outer circle's nodes are on it.
  InputMesh mesh = raised(ring(CellType::Quadrilateral, 6, 8, 1.0));
  const std::vector<double> straight = curved_point_coordinates(mesh);
  place_boundary_nodes(mesh, {{"inner", "circle:0,0,0.5"}, {"outer", "circle:0,0,1"}});
  EXPECT_EQ(curved_quality(mesh).not_valid, 0);
  // The nodes moved by at most the outer circle's bulge, 1 − cos π/6 ≈ 0.134; inside, with the
  // circles' nodes.
  const std::vector<double> placed = curved_point_coordinates(mesh);
  double most = 0.0;
  for (std::size_t i = 0; i < placed.size(); ++i)
    most = std::max(most, std::abs(placed[i] - straight[i]));
  EXPECT_GT(most, 0.03);
  EXPECT_LT(most, 0.14);
}

TEST(CurveBoundary, RefusesAShapeOfNoPartAndOneThatMissesItsVertices) {
  InputMesh mesh = raised(quarter_annulus(CellType::Quadrilateral, 2));
  EXPECT_THROW(place_boundary_nodes(mesh, {{"hole", "circle:0,0,1"}}), Error);
  EXPECT_THROW(place_boundary_nodes(mesh, {{"inner", "circle:0,0,1.5"}}), Error);
}

}  // namespace neomesh
