// Size fields for r-adaptivity (thesis §6, docs/method.md §5; the words are those of
// targets/cell_targets.hpp): a relative volume per cell from the position of its centroid,
//   v_K = floor + d(c_K)^p,
// where d is the distance to a target surface (circle/sphere, plane, the surface of an
// axis-aligned box, or |φ| of a level-set expression φ(x, y, z)), or per-cell values read
// from a file (used as v_K directly); or, for an anisotropic field, a metric M(x). The thesis
// uses floor = 1e-8, p = 1.
//
// desired_volumes_from_field() turns the relative volumes into desired volumes (absolute,
// summing to the mesh volume) and can make them geometrically consistent first, as the field
// options ask (SizeFieldOptions, docs/adaptivity.md): a bound on the ratio of the largest to the
// smallest volume and neighbour smoothing of log v.
#pragma once

#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <neomesh/size_field.hpp>

#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"
#include "targets/cell_targets.hpp"

namespace neomesh {

// The arguments of a circle/sphere and of a line/plane, for SizeField and LevelSet alike:
// throws Error unless the centre (point) has 2 or 3 coordinates, the normal as many, the
// radius is positive and finite and the normal not zero.
void check_sphere(const std::vector<double>& centre, double radius);
void check_plane(const std::vector<double>& point, const std::vector<double>& normal);

// Centroid (vertex mean) of every local cell: num_cells × dim values.
std::vector<double> cell_centroids(const MeshView& view, std::span<const double> coords);

// Relative volume v_K of every local cell of `view` (MeshView order) at the coordinates
// `coords` (num_vertices × dim, the view's local vertex order); of an anisotropic field
// det(M)^(-1/2) at the centroid, whatever `field_options` say. Throws Error if
// the field does not fit the mesh or is not a positive finite number somewhere. Collective
// (the per-cell values are checked against the global number of cells).
std::vector<double> relative_volumes(const SizeField& field, const MeshView& view,
                                     std::span<const double> coords,
                                     const SizeFieldOptions& field_options, MPI_Comm comm);

// Desired volumes: the field's relative volumes at `coords`, made consistent as
// `field_options` asks, scaled to sum to `total` (the mesh volume). Collective.
std::vector<double> desired_volumes_from_field(const SizeField& field,
                                               const SizeFieldOptions& field_options,
                                               const MeshView& view, const DofMap& dofs,
                                               std::span<const double> coords, double total);

// The target shape of every local cell at `coords` for an anisotropic field, M^(-1/2) at its
// centroid turned by the cell's rotation: S = M^(-1/2) R with R from the polar decomposition
// J = R U of a Jacobian of the cell (`jacobians`: Functional::cell_jacobians, dim² per cell). The
// energy sees only SᵀS, the target in the cell's reference frame (docs/method.md §9), so
// M^(-1/2) alone would ask for the stretch along the reference cell's axes, whatever way the
// cell lies (a triangle's are arbitrary): with R it asks for the cell's physical stretch
// V = J Rᵀ to be M^(-1/2), the unit ball of M. (Column-major, the Functional scales it to det 1.)
// Empty for an isotropic field. Throws Error naming a cell where M is not symmetric positive
// definite.
std::vector<double> target_shapes(const SizeField& field, const MeshView& view,
                                  std::span<const double> coords,
                                  std::span<const double> jacobians);

// The field's targets at `coords` (adaptation's; build_targets in targets/cell_targets.hpp is
// the entry point): desired volumes summing to `total` and, for a metric, target shapes oriented
// by `jacobians`. Collective.
CellTargets field_targets(const SizeField& field, const SizeFieldOptions& field_options,
                          const MeshView& view, const DofMap& dofs, std::span<const double> coords,
                          std::span<const double> jacobians, double total);

}  // namespace neomesh
