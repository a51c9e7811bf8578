// Vertices that slide on a curved or oblique boundary move only within the tangent space of
// their boundary — a line or plane that turns as they move — and are put back onto the
// boundary after every step (docs/boundary.md). The Functional restricts its derivatives to
// these spaces: with P the block-diagonal orthogonal projector, the gradient is P g and the
// matrices are P A P + (I − P), so every direction the solvers produce is tangent and the
// normal part of each system is the identity. The solver projects each trial point.
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
  // Writes the dim × dim projector (row-major, symmetric) of each of `vertices`, in order, at
  // the local coordinates `x` (dim values per local vertex, ghosts included). Every rank
  // computes the same projector for a vertex it shares.
  std::function<void(std::span<const double> x, std::span<double> projectors)> tangent_projectors;
  // Moves the owned sliding vertices of the global coordinate Vec `x` onto the boundary.
  std::function<void(Vec x)> project;
};

}  // namespace neomesh
