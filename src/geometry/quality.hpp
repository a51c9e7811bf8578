// Cell quality metrics: what a user looks at before and after smoothing.
//
// Conventions (the same for every cell type, so that 1 and 90° read alike everywhere):
// - Jacobians are taken with respect to the unit reference cell: at a corner, the columns
//   are the corner's edge vectors (the corner frames of the cell-type table: along the
//   reference axes for Q1 cells, so the unit square has det 1 at every corner; for a pyramid
//   also the apex with three consecutive base vertices); at a Gauss point, 2^d times the
//   Jacobian from [-1,1]^d (wedges and pyramids: see measure_wedge_or_pyramid); for a
//   simplex, the edge matrix [x1-x0, x2-x0(, x3-x0)].
// - Scaled Jacobian: minimum over the corners of det J / (product of the lengths of the
//   corner's d edges), divided by its value on the optimal cell where that is not 1: the
//   equilateral triangle and the wedge (√3/2), the regular tetrahedron and the pyramid with
//   equilateral side faces (√2/2). 1 for the ideal cell, ≤ 0 for inverted ones.
// - Angles, in degrees: triangles and quads, the interior angle at each corner (a quad
//   corner with det J ≤ 0 counts as reflex, 360° minus the angle between its edges);
//   hexahedra, the angles between the edges at each corner (ideal 90°); tetrahedra, the six
//   dihedral angles (ideal arccos(1/3) ≈ 70.53°), which reveal slivers where face angles
//   do not; wedges and pyramids, the interior angles of their faces (ideal 60° and 90°).
// - Edge ratio: longest over shortest edge; +∞ for a zero-length edge.
// - Inverse mean ratio (IMR, Mesquite's and TMOP's shape metric): |T|²_F / (d det(T)^(2/d))
//   with T = J W⁻¹ the corner Jacobian relative to the optimal cell's, averaged over the
//   corners; 1 for the ideal shape (any size), larger for worse, +∞ for an inverted corner.
//   Its mean over the cells is what Mesquite reports as the mesh's quality.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <mpi.h>

#include <neomesh/field.hpp>
#include <neomesh/quality.hpp>

#include "mesh/cell_type.hpp"
#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

// Per cell of a MeshView (its cell order), for the coordinates given.
struct CellQuality {
  std::vector<CellType> type;
  std::vector<double> volume;           // signed (negative for inverted simplices)
  std::vector<double> min_corner_det;   // min det J over the corners
  std::vector<double> min_gauss_det;    // min det J over 3^d Gauss points (simplex: the constant)
  std::vector<double> scaled_jacobian;  // see above
  std::vector<double> min_angle, max_angle;
  std::vector<double> edge_ratio;
  std::vector<double> inverse_mean_ratio;  // see above

  std::size_t size() const { return volume.size(); }
};

// `coords` holds view.num_vertices × view.dim values in the view's local vertex order (e.g.
// view.coords, or the current coordinates of a run). A surface mesh's cells are measured along
// their reference normals (surface_orientation.hpp), for which `dofs` sums over ranks (null: a
// whole mesh on one process); other meshes need no `dofs`.
CellQuality cell_quality(const MeshView& view, std::span<const double> coords,
                         const DofMap* dofs = nullptr);
// One metric of cell_quality alone, at a fraction of its cost (no angles, edge ratios or
// inverse mean ratios): for the desired volumes and the quality guard, which need no more.
std::vector<double> cell_volumes(const MeshView& view, std::span<const double> coords,
                                 const DofMap* dofs = nullptr);
std::vector<double> cell_scaled_jacobians(const MeshView& view, std::span<const double> coords,
                                          const DofMap* dofs = nullptr);
std::vector<double> cell_inverse_mean_ratios(const MeshView& view, std::span<const double> coords,
                                             const DofMap* dofs = nullptr);
std::vector<double> cell_edge_ratios(const MeshView& view, std::span<const double> coords);
// The scaled Jacobian of one cell of `type` with vertex coordinates `coords` (dim values per
// vertex, in the cell's canonical order).
double cell_scaled_jacobian(CellType type, const double* coords);
// The same if it is above `bar`; otherwise some value at most `bar` (not the cell's), from the
// first corner that shows it is not above: for a search that only asks whether a cell beats a bar.
// With `corners` (bit K: corner K of the cell-type table; a simplex's corner K at its vertex K),
// the value over those corners alone (+∞ for none); the minimum over two sets is the value over
// their union, bit for bit.
inline constexpr std::uint32_t kAllCorners = ~std::uint32_t{0};
double cell_scaled_jacobian_above(CellType type, const double* coords, double bar,
                                  std::uint32_t corners = kAllCorners);
// The value over each corner alone, corner K's to out[K] (at most kMaxScaledJacobianCorners);
// returns their count. The least of them is the cell's value, and the least over some corners
// the value over those corners, bit for bit: a search can keep a cell's corners and re-evaluate
// only those a move changes.
inline constexpr int kMaxScaledJacobianCorners = 8;
int cell_scaled_jacobian_corners(CellType type, const double* coords, double* out);
// The corners whose value depends on the cell's vertex `vertex` (canonical index): its own and
// those with an edge to it (a simplex: all).
std::uint32_t scaled_jacobian_corners_at(CellType type, int vertex);
// Its longest over its shortest edge, and its inverse mean ratio, likewise.
double cell_edge_ratio(CellType type, const double* coords);
double cell_inverse_mean_ratio(CellType type, const double* coords);
// The length of the edge between points a and b (dim values each), as the edge ratios take it,
// bit for bit: so a search that moves one vertex can update a cell's edge ratio from the edges
// at that vertex alone (the worst-cell repair). Eigen's norm of a 2- or 3-vector sums the
// squares in this order (quality_test checks).
inline double edge_length(const double* a, const double* b, int dim) {
  double sum = 0.0;
  for (int k = 0; k < dim; ++k) {
    const double e = a[k] - b[k];
    sum += e * e;
  }
  return std::sqrt(sum);
}

// A surface cell: a triangle or quadrilateral whose vertices lie in space (a surface mesh),
// with its reference unit normal n, the side the cell faces (surface_orientation.hpp: the
// cell's own normal, reversed for a cell folded over the surface around it). Its measures are those
// above, taken in 3D: edge lengths and angles as they are in space, and every determinant the
// signed area seen along n, (j0 × j1) · n for a Jacobian with columns j0, j1. So a cell folded
// against n has a negative scaled Jacobian and counts as inverted; a cell in a plane normal to n
// measures exactly as its 2D image in that plane; and a cell tilted by θ against that plane
// has its determinants scaled by cos θ — one standing across the surface scores 0, as a
// flattened 2D cell does. This is the determinant the surface kernel's energy sees.
struct SurfaceCellMeasures {
  double area;  // signed, seen along n
  double min_corner_det, min_gauss_det;
  double scaled_jacobian;
  double min_angle, max_angle;  // degrees; a quad corner with det ≤ 0 counts as reflex
  double edge_ratio;
  double inverse_mean_ratio;
};
// `coords`: 3 values per vertex, in the cell's canonical order; `normal`: n, 3 values. Throws
// for a type other than triangle and quadrilateral.
SurfaceCellMeasures surface_cell_measures(CellType type, const double* coords,
                                          const double* normal);
// Its scaled Jacobian alone, at a fraction of the cost, and its inverse mean ratio; its edge
// ratio alone, which no normal changes.
double surface_cell_scaled_jacobian(CellType type, const double* coords, const double* normal);
double surface_cell_scaled_jacobian_above(CellType type, const double* coords, const double* normal,
                                          double bar, std::uint32_t corners = kAllCorners);
int surface_cell_scaled_jacobian_corners(CellType type, const double* coords, const double* normal,
                                         double* out);
double surface_cell_inverse_mean_ratio(CellType type, const double* coords, const double* normal);
double surface_cell_edge_ratio(CellType type, const double* coords);

// The metrics of `quality` as the per-cell fields of an output (.vtu), by the names the
// reports and `--picture-field` use.
std::vector<Field> quality_fields(const CellQuality& quality);

// Collective over `comm`: every rank passes the quality of its own cells.
QualitySummary summarize(const CellQuality& quality, MPI_Comm comm);

}  // namespace neomesh
