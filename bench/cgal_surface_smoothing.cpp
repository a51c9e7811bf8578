// CGAL's surface smoothers on a triangle surface, for bench/surfaces.py's side by side with
// `neomesh smooth`. Reads IN (OFF, or any format CGAL::IO::read_polygon_mesh reads), smooths it
// with one of CGAL's Polygon_mesh_processing functions and writes OUT (OFF) with the same
// vertices and faces in the same order:
//
//   cgal_surface_smoothing IN OUT relax|angle-area [ITERATIONS]
//
//   relax       tangential_relaxation, one iteration at a time, each followed by a projection
//               of the moved vertices onto the input's triangles (closest point, AABB tree), as
//               CGAL's isotropic_remeshing does after its relaxation steps;
//   angle-area  angle_and_area_smoothing with its defaults (projection onto the input's
//               triangles, safety constraints; area smoothing needs CGAL built with Ceres) but
//               no Delaunay flips, so that the cells stay those of the input.
//
// Edges whose faces meet at more than 40° (neomesh's default --feature-angle) and border edges
// are constrained; their vertices do not move. Prints one JSON line:
// {"method": ..., "iterations": N, "smoothing_seconds": s, "total_seconds": t}, the smoothing
// alone and read + smoothing + write.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/angle_and_area_smoothing.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/tangential_relaxation.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Vertex = Mesh::Vertex_index;
using Edge = Mesh::Edge_index;
using Triangles = std::vector<Kernel::Triangle_3>;
using Tree = CGAL::AABB_tree<
    CGAL::AABB_traits<Kernel, CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>>>;
namespace PMP = CGAL::Polygon_mesh_processing;

// neomesh's default feature angle, so that both tools keep the same ridges.
constexpr double kFeatureAngleDegrees = 40.0;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Triangles triangles_of(const Mesh& mesh) {
  Triangles out;
  for (auto f : mesh.faces()) {
    const auto h = mesh.halfedge(f);
    out.emplace_back(mesh.point(mesh.source(h)), mesh.point(mesh.target(h)),
                     mesh.point(mesh.target(mesh.next(h))));
  }
  return out;
}

// tangential_relaxation moves vertices in their tangent planes; each iteration is followed by a
// projection onto the input's triangles, so that the vertices stay on the input surface.
void relax(Mesh& mesh, unsigned iterations, Mesh::Property_map<Edge, bool> sharp,
           Mesh::Property_map<Vertex, bool> fixed) {
  const Triangles input = triangles_of(mesh);
  Tree tree(input.begin(), input.end());
  tree.accelerate_distance_queries();
  for (unsigned i = 0; i < iterations; ++i) {
    PMP::tangential_relaxation(mesh, CGAL::parameters::number_of_iterations(1)
                                         .edge_is_constrained_map(sharp)
                                         .vertex_is_constrained_map(fixed));
    for (auto v : mesh.vertices())
      if (!fixed[v]) mesh.point(v) = tree.closest_point(mesh.point(v));
  }
}

void angle_and_area(Mesh& mesh, unsigned iterations, Mesh::Property_map<Edge, bool> sharp,
                    Mesh::Property_map<Vertex, bool> fixed) {
  PMP::angle_and_area_smoothing(mesh, CGAL::parameters::number_of_iterations(iterations)
                                          .use_Delaunay_flips(false)
                                          .edge_is_constrained_map(sharp)
                                          .vertex_is_constrained_map(fixed));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4 || argc > 5) {
    std::cerr << "usage: cgal_surface_smoothing IN OUT relax|angle-area [ITERATIONS]\n";
    return 2;
  }
  const std::string in = argv[1], out = argv[2], method = argv[3];
  const unsigned iterations = argc == 5 ? static_cast<unsigned>(std::atoi(argv[4])) : 10;
  if (method != "relax" && method != "angle-area") {
    std::cerr << "cgal_surface_smoothing: unknown method '" << method << "'\n";
    return 2;
  }
  const auto start = std::chrono::steady_clock::now();
  Mesh mesh;
  if (!PMP::IO::read_polygon_mesh(in, mesh) || !CGAL::is_triangle_mesh(mesh)) {
    std::cerr << "cgal_surface_smoothing: " << in << " is not a triangle surface CGAL reads\n";
    return 1;
  }
  auto sharp = mesh.add_property_map<Edge, bool>("e:sharp", false).first;
  auto fixed = mesh.add_property_map<Vertex, bool>("v:fixed", false).first;
  PMP::detect_sharp_edges(mesh, kFeatureAngleDegrees, sharp);
  for (auto e : mesh.edges()) {
    if (mesh.is_border(e)) sharp[e] = true;
    if (!sharp[e]) continue;
    fixed[mesh.vertex(e, 0)] = true;
    fixed[mesh.vertex(e, 1)] = true;
  }

  const auto smoothing_start = std::chrono::steady_clock::now();
  if (method == "relax")
    relax(mesh, iterations, sharp, fixed);
  else
    angle_and_area(mesh, iterations, sharp, fixed);
  const double smoothing = seconds_since(smoothing_start);

  if (!CGAL::IO::write_polygon_mesh(out, mesh, CGAL::parameters::stream_precision(17))) {
    std::cerr << "cgal_surface_smoothing: cannot write " << out << "\n";
    return 1;
  }
  std::printf(
      "{\"method\": \"%s\", \"iterations\": %u, \"smoothing_seconds\": %.6f, "
      "\"total_seconds\": %.6f}\n",
      method.c_str(), iterations, smoothing, seconds_since(start));
  return 0;
}
