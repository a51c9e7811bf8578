// The Picard iteration of thesis §6 (option ii, docs/method.md §5): the targets (desired volumes,
// and a metric's target shapes) stay fixed while the quasi-Newton method iterates; they are
// rebuilt at the current mesh's centroids when the method has (nearly) settled or every
// `update_every` iterations, and the method restarts (new F and g, new Riesz Laplacian, k_min
// antigradient steps again). The run ends when the Newton defect is below its tolerance and at
// least `min_updates` updates were made.
//
// When to update: after a quasi-Newton (not antigradient) step that moved no vertex by more
// than `update_move` times its local cell size — σ·max_i |δ_i| / h_i, the scale-free form of
// the thesis' "‖δ‖ below a threshold" — or, with `update_step_norm` > 0, when the Euclidean
// norm of the step taken, σ‖δ‖, is below it (the thesis' absolute criterion, which depends
// on the number of vertices and the size of the domain). The method's own stopping criteria
// (defect tolerance, practical criterion) also trigger an update while fewer than
// `min_updates` were made.
#pragma once

#include <functional>
#include <vector>

#include <neomesh/options.hpp>

#include "energy/functional.hpp"
#include "solver/quasi_newton.hpp"
#include "targets/cell_targets.hpp"

namespace neomesh {

struct PicardResult {
  SolverRun run;  // all iterations, over all sets of targets
  // The iterations (IterationRecord::k) after which the targets were updated.
  std::vector<int> update_iterations;
};

// What the Picard iteration asks at x for: the targets (targets/cell_targets.hpp: build_targets;
// desired volumes summing to the mesh volume, target shapes of a metric); and the Functional of
// the problem with those targets (of the same Constraints each time), which must live until the
// next call (its owner may keep more in step).
using TargetsAt = std::function<CellTargets(Vec x)>;
using SetTargets = std::function<const Functional&(const CellTargets&)>;

// Adapts x (a global coordinate Vec laid out by the functionals' dofs()) to the targets that
// `targets(x)` computes. An update under-relaxes the volumes (PicardOptions::relaxation) and
// takes the new shapes. QuasiNewtonOptions::max_iterations caps the total number of iterations.
PicardResult picard(const MeshView& view, Vec x, const TargetsAt& targets,
                    const SetTargets& set_targets, const PicardOptions& options,
                    const QuasiNewtonOptions& method, const Observer& observe = {});

}  // namespace neomesh
