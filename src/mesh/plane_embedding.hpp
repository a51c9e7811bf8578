// PlaneEmbedding: where a 2D mesh lies in 3D space.
//
// Gmsh (and VTK) files give every node three coordinates, and a 2D mesh need not lie in z = 0:
// a face of a 3D part, a plane at z = 5, a plane tilted out of xy. neomesh optimizes a 2D mesh in
// coordinates (u, v) of its own plane, x = origin + u a + v b with a, b orthonormal, and writes
// it back in 3D. A mesh of 2D cells that is not planar is a surface mesh, which keeps its 3D
// coordinates (input_mesh.hpp).
//
// Nothing the user did not ask to change changes: a vertex whose (u, v) are those it was read
// with is written back with the file's coordinates, bit for bit; the others lie on the plane.
// For a plane normal to an axis with one exact constant (z = 5), (u, v) are the file's other two
// coordinates unchanged and the constant is written back as it was.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace neomesh {

class PlaneEmbedding {
 public:
  // Relative to the mesh's size, how far the vertices of a planar 2D mesh may lie from their
  // best-fitting plane (files store few digits); beyond it the mesh is a surface mesh.
  static constexpr double kPlanarTolerance = 1e-6;

  // The plane z = 0 (u = x, v = y): nothing to map.
  PlaneEmbedding() = default;

  // The plane of the points `xyz` (3 values per point) and their coordinates in it (2 per
  // point, into `uv`); none (and `uv` unspecified) for points that do not lie in one plane: a
  // surface mesh. Throws Error naming `file` for a non-finite coordinate.
  static std::optional<PlaneEmbedding> fit(std::span<const double> xyz, std::vector<double>& uv,
                                           const std::string& file);

  // True for the plane z = 0 with u = x, v = y: 2D coordinates are 3D ones with z = 0.
  bool is_xy() const { return xy_; }

  // 3D coordinates (3 per vertex) of in-plane coordinates `uv` (2 per vertex, the vertices as
  // they were fitted).
  std::vector<double> to_space(std::span<const double> uv) const;

  // The in-plane coordinates of the point `xyz` (3 values) projected onto the plane: for a
  // plane normal to an axis, the other two coordinates as they are (as fit() gives them).
  std::array<double, 2> to_plane(const double* xyz) const;
  // The distance of the point `xyz` from the plane.
  double distance(const double* xyz) const;

  // "z = 5", "y = -5" or "through (1, 2, 3) with normal (0.6, 0, 0.8)", for messages.
  std::string describe() const;

 private:
  std::array<double, 3> origin_{0, 0, 0}, a_{1, 0, 0}, b_{0, 1, 0}, normal_{0, 0, 1};
  bool xy_ = true;
  // For a tilted plane: the file's coordinates and their (u, v) as first computed, so that a
  // vertex that has not moved is written back exactly as it was read.
  std::vector<double> input_xyz_, input_uv_;
};

}  // namespace neomesh
