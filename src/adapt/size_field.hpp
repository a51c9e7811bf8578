// Size fields for r-adaptivity (thesis §6, docs/method.md §5): a desired *relative* volume per cell
// from the position of its centroid,
//   v_K = floor + d(c_K)^p,
// where d is the distance to a target surface (circle/sphere, plane, the surface of an
// axis-aligned box, or |φ| of a level-set expression φ(x, y, z)), or per-cell values read
// from a file (used as v_K directly). The thesis uses floor = 1e-8, p = 1.
//
// desired_volumes() turns the relative volumes into absolute ones summing to the mesh
// volume and can make them geometrically consistent first (docs/adaptivity.md): a bound on
// the ratio of the largest to the smallest volume and neighbour smoothing of log v.
#pragma once

#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <neomesh/size_field.hpp>

#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

// The arguments of a circle/sphere and of a line/plane, for SizeField and LevelSet alike:
// throws Error unless the centre (point) has 2 or 3 coordinates, the normal as many, the
// radius is positive and finite and the normal not zero.
void check_sphere(const std::vector<double>& centre, double radius);
void check_plane(const std::vector<double>& point, const std::vector<double>& normal);

// Centroid (vertex mean) of every local cell: num_cells × dim values.
std::vector<double> cell_centroids(const MeshView& view, std::span<const double> coords);

// Relative desired volume v_K of every local cell of `view` (MeshView order) at the
// coordinates `coords` (num_vertices × dim, the view's local vertex order). Throws Error if
// the field does not fit the mesh or is not a positive finite number somewhere. Collective
// (the per-cell values are checked against the global number of cells).
std::vector<double> relative_volumes(const SizeField& field, const MeshView& view,
                                     std::span<const double> coords,
                                     const SizeFieldOptions& options, MPI_Comm comm);

// Absolute desired volumes: the field's relative volumes at `coords`, made consistent as
// `options` asks, scaled to sum to `total` (the mesh volume). Collective.
std::vector<double> desired_volumes(const SizeField& field, const SizeFieldOptions& options,
                                    const MeshView& view, const DofMap& dofs,
                                    std::span<const double> coords, double total);

}  // namespace neomesh
