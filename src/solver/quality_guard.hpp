// "Never worse than the input" for the worst cell. The energy is a sum over cells, so its
// minimizer may trade a little of the worst cell's shape for a better average: on meshes
// Gmsh has already smoothed, the minimum scaled Jacobian drops slightly (plate with holes,
// triangles: 0.615 → 0.605) while the mean rises. Users judge a mesh by its worst cell, so
// after the optimization the guard pulls the vertices of every cell whose scaled Jacobian
// fell below the input's minimum back toward their input positions, halving their
// displacement round by round (and resetting them after the last round), until no cell is
// below it. Vertices of good cells keep their optimized positions. Cells that mix reset and
// optimized vertices can fall below it in turn (the input far from the optimum: Mesquite's
// shashkov_opt, an anisotropic mesh already optimized): their vertices are reset too, and in
// the end, if need be, all are: the output is then the input, which meets the threshold (at
// most the input's worst cell), so the guard always ends at or above it.
#pragma once

#include <functional>
#include <optional>

#include <neomesh/result.hpp>

#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

// `input` and `x` are global coordinate Vecs laid out by `dofs`; x is changed in place, and
// `project` (if given) puts sliding boundary vertices back onto the boundary after each round.
// `threshold`: a lower worst scaled Jacobian than `input`'s to hold, if given (the file's own,
// when `input` has vertices placed on their charts that lowered it: no cell can be pulled back
// above where the placement left it). Collective.
QualityGuardResult guard_worst_quality(const MeshView& view, const DofMap& dofs, Vec input, Vec x,
                                       const std::function<void(Vec)>& project = {},
                                       std::optional<double> threshold = {});

// The min scaled Jacobian at x (a global coordinate Vec laid out by `dofs`). Collective.
double min_scaled_jacobian(const MeshView& view, const DofMap& dofs, Vec x);

// The mean scaled Jacobian at x (a global coordinate Vec laid out by `dofs`), as
// Mesh::quality() reports it, without moving the mesh there. Collective.
double mean_scaled_jacobian(const MeshView& view, const DofMap& dofs, Vec x);
// The mean inverse mean ratio at x, likewise.
double mean_inverse_mean_ratio(const MeshView& view, const DofMap& dofs, Vec x);

}  // namespace neomesh
