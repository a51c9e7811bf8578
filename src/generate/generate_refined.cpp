// Generators that start from a coarse 2D mesh and refine it uniformly (the transition
// element, the disc, the two triangle meshes), moving new boundary vertices onto curved
// boundaries after each refinement as the thesis' meshes were made (thesis §5.6, §5.7).
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <utility>

#include "core/error.hpp"
#include "generate/generate.hpp"

namespace neomesh {

namespace {

using Edge = std::pair<std::int64_t, std::int64_t>;  // (smaller, larger) vertex

// Side names and tags shared with the lattice generators (generate.cpp).
VertexSet side(const char* name, std::vector<std::int64_t> vertices) {
  static const std::map<std::string, int> tags = {
      {"left", 1}, {"right", 2}, {"bottom", 3}, {"top", 4}, {"circle", 1}};
  return {name, tags.at(name), std::move(vertices), {}};
}

MeshData coarse_mesh(CellType type, std::vector<double> coords, std::vector<std::int64_t> cells,
                     std::vector<VertexSet> parts) {
  MeshData mesh;
  mesh.dim = 2;
  mesh.cell_type = type;
  mesh.coords = std::move(coords);
  mesh.cells = std::move(cells);
  mesh.boundary_parts = std::move(parts);
  return mesh;
}

// One uniform refinement of a triangle or quad mesh: edge midpoints, and cell centres (mean of
// the corners) for quads; children keep the parent's orientation. A new vertex on a boundary
// edge joins every boundary part that holds both ends of the edge. Returns the parent edge of
// each new vertex (in order, starting at the old vertex count; {-1, -1} for cell centres).
std::vector<Edge> refine(MeshData& mesh) {
  const bool quad = mesh.cell_type == CellType::Quadrilateral;
  const int nv = quad ? 4 : 3;
  const std::vector<std::array<int, 2>> local_edges =
      quad ? std::vector<std::array<int, 2>>{{0, 1}, {2, 3}, {0, 2}, {1, 3}}
           : std::vector<std::array<int, 2>>{{0, 1}, {1, 2}, {0, 2}};
  const std::int64_t old_vertices = mesh.num_vertices(), old_cells = mesh.num_cells();

  struct Midpoint {
    std::int64_t vertex;
    int cells;
  };
  std::map<Edge, Midpoint> midpoints;
  std::vector<Edge> parents;
  auto midpoint = [&](std::int64_t a, std::int64_t b) -> std::int64_t {
    const Edge edge = std::minmax(a, b);
    auto [it, inserted] = midpoints.try_emplace(edge, Midpoint{-1, 0});
    if (inserted) {
      it->second.vertex = old_vertices + static_cast<std::int64_t>(parents.size());
      parents.push_back(edge);
      for (int d = 0; d < 2; ++d)
        mesh.coords.push_back(0.5 * (mesh.coords[2 * a + d] + mesh.coords[2 * b + d]));
    }
    ++it->second.cells;
    return it->second.vertex;
  };

  std::vector<std::int64_t> children;
  for (std::int64_t c = 0; c < old_cells; ++c) {
    const std::array<std::int64_t, 4> v = {mesh.cells[c * nv], mesh.cells[c * nv + 1],
                                           mesh.cells[c * nv + 2],
                                           quad ? mesh.cells[c * nv + 3] : -1};
    std::array<std::int64_t, 4> m{};
    for (std::size_t e = 0; e < local_edges.size(); ++e)
      m[e] = midpoint(v[local_edges[e][0]], v[local_edges[e][1]]);
    if (quad) {
      const std::int64_t centre = old_vertices + static_cast<std::int64_t>(parents.size());
      parents.push_back({-1, -1});
      for (int d = 0; d < 2; ++d) {
        double sum = 0.0;
        for (int i = 0; i < 4; ++i) sum += mesh.coords[2 * v[i] + d];
        mesh.coords.push_back(0.25 * sum);
      }
      // m = bottom (0-1), top (2-3), left (0-2), right (1-3); children in tensor order.
      children.insert(children.end(), {v[0], m[0], m[2], centre, m[0], v[1], centre, m[3], m[2],
                                       centre, v[2], m[1], centre, m[3], m[1], v[3]});
    } else {
      // m = (0-1), (1-2), (0-2); the middle child is the parent turned by 180°.
      children.insert(children.end(),
                      {v[0], m[0], m[2], m[0], v[1], m[1], m[2], m[1], v[2], m[0], m[1], m[2]});
    }
  }
  mesh.cells = std::move(children);

  for (VertexSet& part : mesh.boundary_parts) {
    std::vector<std::uint8_t> in_part(old_vertices, 0);
    for (std::int64_t v : part.vertices) in_part[v] = 1;
    for (const auto& [edge, mid] : midpoints)
      if (mid.cells == 1 && in_part[edge.first] && in_part[edge.second])
        part.vertices.push_back(mid.vertex);
  }
  return parents;
}

void check_refinements(int refinements) {
  if (refinements < 0 || refinements > 12)
    fail("the number of refinements must be in 0..12 (got {})", refinements);
}

// Cubic Bézier curve from p0 to p3 with control points p1, p2.
struct Bezier {
  std::array<double, 2> p0, p1, p2, p3;
  std::array<double, 2> operator()(double t) const {
    const double s = 1.0 - t;
    std::array<double, 2> x{};
    for (int d = 0; d < 2; ++d)
      x[d] = s * s * s * p0[d] + 3 * s * s * t * p1[d] + 3 * s * t * t * p2[d] + t * t * t * p3[d];
    return x;
  }
};

}  // namespace

MeshData transition(int refinements) {
  check_refinements(refinements);
  // Outer corners 0-3, inner corners 4-7; the inner quad and the bottom, top, left and right
  // trapezoids, each in tensor order.
  MeshData mesh = coarse_mesh(
      CellType::Quadrilateral,
      {0, 0, 1, 0, 0, 1, 1, 1, 0.25, 0.25, 0.75, 0.25, 0.25, 0.75, 0.75, 0.75},
      {4, 5, 6, 7, 0, 1, 4, 5, 6, 7, 2, 3, 0, 4, 2, 6, 5, 1, 7, 3},
      {side("left", {0, 2}), side("right", {1, 3}), side("bottom", {0, 1}), side("top", {2, 3})});
  for (int r = 0; r < refinements; ++r) refine(mesh);
  return mesh;
}

MeshData circle_quad(int refinements) {
  check_refinements(refinements);
  // FEAT3's unit-circle-quad: outer vertices 0-3 on the circle, the core's corners 4-7.
  MeshData mesh = coarse_mesh(
      CellType::Quadrilateral, {1, 0, 0, 1, -1, 0, 0, -1, 0.5, 0, 0, 0.5, -0.5, 0, 0, -0.5},
      {0, 1, 4, 5, 1, 2, 5, 6, 2, 3, 6, 7, 3, 0, 7, 4, 4, 5, 7, 6}, {side("circle", {0, 1, 2, 3})});
  for (int r = 0; r < refinements; ++r) {
    refine(mesh);
    for (std::int64_t v : mesh.boundary_parts[0].vertices) {
      const double radius = std::hypot(mesh.coords[2 * v], mesh.coords[2 * v + 1]);
      mesh.coords[2 * v] /= radius;
      mesh.coords[2 * v + 1] /= radius;
    }
  }
  return mesh;
}

MeshData triangle_equilateral(int refinements, unsigned seed) {
  check_refinements(refinements);
  MeshData mesh =
      coarse_mesh(CellType::Triangle, {0, 0, 1, 0, 0.5, std::sqrt(3.0) / 2}, {0, 1, 2},
                  {side("bottom", {0, 1}), side("right", {1, 2}), side("left", {2, 0})});
  for (int r = 0; r < refinements; ++r) refine(mesh);

  // Each interior vertex: one draw decides whether it moves, two give the displacement (drawn
  // either way, so the pattern of one vertex does not shift the others'). Moves of at most
  // h/5 per coordinate keep every triangle well inside positive orientation.
  std::mt19937 random(seed);
  auto uniform01 = [&random] { return random() * 0x1p-32; };
  const double step = 0.2 * std::ldexp(1.0, -refinements);
  const auto on_boundary = boundary_vertices(mesh);
  for (std::int64_t v = 0; v < mesh.num_vertices(); ++v) {
    if (on_boundary[v]) continue;
    const bool moves = uniform01() < 0.5;
    const double dx = step * (2 * uniform01() - 1), dy = step * (2 * uniform01() - 1);
    if (!moves) continue;
    mesh.coords[2 * v] += dx;
    mesh.coords[2 * v + 1] += dy;
  }
  return mesh;
}

MeshData triangle_curved(int refinements) {
  check_refinements(refinements);
  // FEAT3's unit-axe-tria: corners 0-3 of [0,1]², side midpoints 4-7, centre 8.
  MeshData mesh = coarse_mesh(
      CellType::Triangle, {0, 0, 1, 0, 0, 1, 1, 1, 0.5, 0, 0.5, 1, 0, 0.5, 1, 0.5, 0.5, 0.5},
      {0, 4, 6, 1, 7, 4, 3, 5, 7, 2, 6, 5, 4, 8, 6, 4, 7, 8, 5, 8, 7, 5, 6, 8},
      {side("bottom", {0, 4, 1}), side("right", {1, 7, 3}), side("top", {3, 5, 2}),
       side("left", {2, 6, 0})});
  const std::array<Bezier, 4> curves = {Bezier{{0, 0}, {0.25, -0.25}, {0.75, -0.25}, {1, 0}},
                                        Bezier{{1, 0}, {0.75, 0.25}, {0.75, 0.75}, {1, 1}},
                                        Bezier{{1, 1}, {0.75, 1.25}, {0.25, 1.25}, {0, 1}},
                                        Bezier{{0, 1}, {0.25, 0.75}, {0.25, 0.25}, {0, 0}}};
  // Per side, each vertex's parameter on that side's curve (NaN when not on it).
  const double none = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::vector<double>> param(4, std::vector<double>(mesh.num_vertices(), none));
  auto place = [&](int s, std::int64_t v) {
    const auto x = curves[s](param[s][v]);
    mesh.coords[2 * v] = x[0];
    mesh.coords[2 * v + 1] = x[1];
  };
  for (int s = 0; s < 4; ++s)
    for (int i = 0; i < 3; ++i) {
      const std::int64_t v = mesh.boundary_parts[s].vertices[i];
      param[s][v] = 0.5 * i;
      place(s, v);
    }
  for (int r = 0; r < refinements; ++r) {
    const std::int64_t old_vertices = mesh.num_vertices();
    const std::vector<Edge> parents = refine(mesh);
    for (int s = 0; s < 4; ++s) {
      param[s].resize(mesh.num_vertices(), none);
      for (std::int64_t v : mesh.boundary_parts[s].vertices) {
        if (v < old_vertices) continue;
        const Edge& edge = parents[v - old_vertices];
        param[s][v] = 0.5 * (param[s][edge.first] + param[s][edge.second]);
        place(s, v);
      }
    }
  }
  return mesh;
}

}  // namespace neomesh
