// Untangling (docs/untangling.md): moves the vertices of a mesh with inverted cells until
// none is inverted, by the quasi-Newton method of quasi_newton.hpp on the untangling energy
// (energy/regularized_neo_hooke.hpp) with a decreasing regularization ε, as in Garanzha et
// al. 2021. The Neo-Hookean phase then starts from the untangled mesh. Boundary handling
// (fixed or sliding) is the Functional's, as in the Neo-Hookean phase.
#pragma once

#include <functional>
#include <vector>

#include "energy/functional.hpp"
#include "solver/quasi_newton.hpp"

namespace neomesh {

struct UntangleOptions {
  int max_rounds = 60;      // values of ε before giving up
  int steps_per_round = 8;  // quasi-Newton steps per ε, at most
  // Give up early when this many rounds in a row neither reduced the number of inverted
  // cells nor raised the smallest det G by 1% (a boundary that folds over).
  int stalled_rounds = 10;
  // ε₀ = initial_epsilon · |min det G| (Garanzha et al.: 0.2); min det G is in units of the
  // optimal cell (1 = the desired volume).
  double initial_epsilon = 0.2;
  // A cell counts as tangled while det G ≤ this at a sample point: 0 for inverted cells; > 0
  // lifts nearly flat ones (the worst-cell phase, worst_cells.hpp), starting from ε₀ = it.
  double tangled_below = 0.0;
};

struct UntangleResult {
  std::vector<IterationRecord> history;
  Inversion before, after;  // after.count > 0: the mesh could not be untangled
  int rounds = 0;
  double seconds = 0.0;
};

// Untangles x in place if it has inverted cells (else returns at once with no history), on
// `functional`'s problem with the untangling energy. `observe` sees every iteration. Collective.
UntangleResult untangle(const Functional& functional, Vec x, const QuasiNewtonOptions& options,
                        Vec cell_size, const UntangleOptions& untangle_options = {},
                        const std::function<void(const IterationRecord&)>& observe = {});

}  // namespace neomesh
