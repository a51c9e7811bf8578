// A metric given per vertex of a mesh (the background: the mesh where adaptation starts, read
// from its file's point data or from a file of one metric per vertex), at any point of the
// domain: linear over each simplex of the background's cells (quadrilaterals, hexahedra,
// wedges and pyramids split into triangles and tetrahedra) in log M, the log-Euclidean mean
// (Arsigny et al. 2006): the mean of positive definite matrices stays positive definite, and
// sizes are interpolated geometrically (the mean of sizes 0.001 and 0.1 is 0.01, not 0.05).
// The background stays where it is while the adapted mesh moves over it; every process holds
// all of it. A point outside it (a vertex sliding along a curved boundary, between the
// background's chords) takes the value at the nearest simplex's closest barycentric point.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <mpi.h>

#include <neomesh/cell_type.hpp>

namespace neomesh {

struct BackgroundMesh {
  int dim = 0;
  std::vector<double> coords;            // dim per vertex
  std::vector<CellType> types;           // per cell
  std::vector<std::int64_t> offsets{0};  // cell c has vertices [offsets[c], offsets[c + 1])
  std::vector<std::int64_t> vertices;    // canonical order (cell_type.hpp)
  std::vector<double> metrics;           // dim² per vertex (column-major), symmetric
};

// The metric of one vertex from the numbers a file or data array gives: 3 (2D: m11 m12 m22) or
// 6 (3D: m11 m12 m13 m22 m23 m33; the upper triangle, as Mmg's .sol files) or dim² (the whole
// matrix, which must be symmetric). Throws Error (naming `where`) for another count or a matrix
// that is not symmetric positive definite.
void unpack_metric(int dim, std::span<const double> numbers, std::span<double> m,
                   const std::string& where);

// Rank 0's background to every process of `comm`. Collective.
void broadcast(BackgroundMesh& mesh, MPI_Comm comm);

class BackgroundMetric {
 public:
  // `mesh.metrics` symmetric positive definite (unpack_metric checks them); builds the search
  // grid.
  explicit BackgroundMetric(BackgroundMesh mesh);
  // M at `point` (dim coordinates) into `m` (dim², column-major).
  void operator()(std::span<const double> point, std::span<double> m) const;
  int dim() const { return dim_; }

 private:
  // The simplex holding `point` (or the nearest) and the point's barycentric coordinates in it.
  std::int64_t locate(std::span<const double> point, std::span<double> barycentric) const;
  // Barycentric coordinates of `point` in simplex s; returns the smallest.
  double barycentric(std::int64_t s, std::span<const double> point, std::span<double> lambda) const;

  int dim_ = 0;
  std::vector<double> coords_;
  std::vector<std::int64_t> simplices_;  // dim + 1 vertices each
  std::vector<double> logs_;             // log M per vertex, dim² each
  // A uniform grid over the bounding box; each bucket lists the simplices whose bounding box
  // meets it.
  std::array<double, 3> lower_{}, width_{};
  std::array<int, 3> buckets_{1, 1, 1};
  std::vector<std::int64_t> bucket_start_, bucket_simplices_;
};

}  // namespace neomesh
