// `adapt --fit`: an adapted mesh fitted to the zero set of a level set (docs/adaptivity.md).
// The interface's vertices (boundary/interface.hpp) slide on levels of φ that are lowered to
// zero in stages; after each stage the whole mesh is optimized (a Picard adaptation), so the
// cells around the interface make room before its vertices go further. A stage that would
// invert a cell is undone and retried with half the step.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "adapt/picard.hpp"
#include "boundary/interface.hpp"

namespace neomesh {

struct FitOptions {
  int max_halvings = 6;  // of the stage step: the smallest step is 1/64 of the way
  // Iterations of a stage before the last: enough for the cells around the interface to make
  // room for the next stage; the last stage converges.
  int stage_iterations = 4;
};

struct FitResult {
  PicardResult picard;        // the iterations of every stage, in order
  int stages = 0;             // stage steps taken
  int retries = 0;            // stage steps undone because a cell would have inverted
  double max_distance = 0.0;  // of an interface vertex from the zero set, at the end
  Interface interface;
  std::shared_ptr<InterfaceConstraint> constraint;  // held by the functional too
};

// What the fit needs from the owner of the functional.
struct FitHooks {
  // The functional of the problem with these vertices sliding too (none: the boundary's
  // alone), its targets kept; lives until the next call of a hook.
  std::function<const Functional&(SlidingVertices)> constrain;
  TargetsAt targets;
  SetTargets set_targets;
};

// Fits x (global coordinate Vec laid out by `dofs`) to the zero set of `phi` at its current
// time: finds the interface, then lowers its vertices' levels to zero, adapting after each
// stage; the last stage adapts with `last_stage`. Throws Error if there is no interface (see
// find_interface) or a stage 1/2^max_halvings of the way inverts a cell.
FitResult fit_interface(const MeshView& view, const DofMap& dofs, Vec x,
                        const LevelSetFunction& phi, const FitHooks& hooks,
                        const PicardOptions& last_stage, const QuasiNewtonOptions& method,
                        const FitOptions& options = {}, const Observer& observe = {});

}  // namespace neomesh
