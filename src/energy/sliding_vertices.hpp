// Vertices that slide on a curved or oblique boundary move only within the tangent space of
// their boundary — a line or plane that turns as they move — and are put back onto the
// boundary after every step (docs/boundary.md). The Functional restricts its derivatives to
// these spaces: with P the block-diagonal orthogonal projector, the gradient is P g and the
// matrices are P A P + (I − P) (H(α) with α times the boundary's curvature term), so every
// direction the solvers produce is tangent and the normal part of each system is the
// identity. The solver projects each trial point.
// (Coordinates that never move — corners, the thesis' fixed boundary, axis-aligned planes —
// are FixedDofs instead: exact and cheaper.) boundary/boundary.hpp fills this in.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include <petscvec.h>

namespace neomesh {

struct SlidingVertices {
  // Local vertices (MeshView numbering) that slide, ascending.
  std::vector<PetscInt> vertices;
  // For each of `vertices`, in order, at the local coordinates `x` (dim values per local
  // vertex, ghosts included), writes dim² + dim + dim² values:
  // - P: the projector onto the directions the vertex may move in (row-major, symmetric);
  // - w and M: how the boundary bends a tangent step u, to second order: the vertex lands at
  //   u + ½ (uᵀ M u) w (surfaces: w = −n, M = ∇n; curves: w = dt/ds, M = t tᵀ; 0 where flat).
  //   With the force g on the vertex this adds (g·w) M to the second derivative of F along
  //   the boundary — the curvature term Newton's method needs on a curved boundary.
  // Every rank computes the same values for a vertex it shares.
  std::function<void(std::span<const double> x, std::span<double> out)> tangent_spaces;
  // Moves the owned sliding vertices of the global coordinate Vec `x` onto the boundary.
  std::function<void(Vec x)> project;
};

// Values per vertex that SlidingVertices::tangent_spaces writes.
constexpr int tangent_space_size(int dim) {
  return 2 * dim * dim + dim;
}

}  // namespace neomesh
