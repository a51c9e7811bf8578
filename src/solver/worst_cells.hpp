// The worst-cell phase of smoothing (docs/method.md, "Corners"). The thesis evaluates the
// energy of a Q1 cell, wedge or pyramid at Gauss points, and a cell is admissible only while
// every corner is positively oriented. Nothing in the energy holds a corner away from 0: where
// the optimum under the Gauss rule lies beyond that wall (untangled meshes, hexahedra in a
// sharp corner of the domain), the method stops against it with a corner nearly flat, min
// scaled Jacobian 1e-10 where the connectivity allows far more. Then smoothing goes on with the
// corners sampled too (Problem::corner_weight): the law's barrier −μ log det G acts
// there and keeps them open, after the untangling energy has lifted them off the wall.
#pragma once

#include <functional>
#include <optional>

#include <neomesh/result.hpp>

#include "energy/functional.hpp"
#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"
#include "solver/quasi_newton.hpp"

namespace neomesh {

// Below this minimum scaled Jacobian a cell other than a simplex counts as flattened.
constexpr double kFlatCellJacobian = 1e-2;
// The corner samples' share of the energy in the phase (OptimalCellQuadrature).
constexpr double kWorstCellCornerWeight = 0.5;
// The phase first lifts every sample's det G (in units of the desired volume) above this.
constexpr double kLiftedDet = 1e-2;
// ... in at most this many values of ε: a corner that the connectivity keeps flat (three
// vertices of a cell on one straight stretch of boundary) cannot be lifted, and must not cost
// long.
constexpr int kLiftRounds = 12;

// A nearly flat cell whose scaled Jacobian times its edge ratio is below this is flattened
// across its edges (a cap, a sliver: sheared), which no mesher designs; a boundary layer's
// needle (a right triangle or tetrahedron of aspect A: scaled Jacobian ≈ 1.15 / A, edge
// ratio ≈ A) has a product near 1.
constexpr double kCapShape = 0.25;

// Whether some cell at x has a scaled Jacobian below kFlatCellJacobian and is a cap
// (kCapShape). Collective.
bool flat_cap(const MeshView& view, const DofMap& dofs, Vec x);

// If some cell other than a simplex has a scaled Jacobian below kFlatCellJacobian at x,
// minimizes again from x with corner samples and returns what that did (its iterations go to
// `observe` and are appended to `run`'s, whose stop reason, final energy (the thesis' energy)
// and defect become the phase's); else nullopt. The phase's problems derive from
// `functional`'s. `least_jacobian` measures the worst cell at x instead (a curved mesh's least
// curved scaled Jacobian, whose simplices fold at their corners too). Collective.
std::optional<CornerPhaseSummary> lift_flat_corners(
    const Functional& functional, const MeshView& view, const DofMap& dofs, Vec x,
    const QuasiNewtonOptions& options, Vec cell_size, Result& run,
    const std::function<void(const IterationRecord&)>& observe = {},
    const std::function<double(Vec)>& least_jacobian = {});

}  // namespace neomesh
