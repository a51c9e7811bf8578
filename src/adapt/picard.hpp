// The Picard iteration of thesis §6 (option ii, docs/method.md §5): the desired volumes stay fixed
// while the quasi-Newton method iterates; they are recomputed from the current mesh's
// centroids when the method has (nearly) settled or every `update_every` iterations, and the
// method restarts (new F and g, new Riesz Laplacian, k_min antigradient steps again). The
// run ends when the Newton defect is below its tolerance and at least `min_updates` updates
// were made.
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

#include "adapt/size_field.hpp"
#include "energy/functional.hpp"
#include "solver/quasi_newton.hpp"

namespace neomesh {

struct PicardResult {
  SolverRun run;  // all iterations, over all sets of desired volumes
  // The iterations (IterationRecord::k) after which the desired volumes were updated.
  std::vector<int> update_iterations;
};

// What the Picard iteration asks at x for: the target cells (volumes absolute, summing to the
// mesh volume; shapes of an anisotropic field); and the Functional of the problem with those
// targets (of the same Constraints each time), which must live until the next call (its
// owner may keep more in step).
using TargetsAt = std::function<CellTargets(Vec x)>;
using SetTargets = std::function<const Functional&(const CellTargets&)>;

// Adapts x (a global coordinate Vec laid out by the functionals' dofs()) to the targets that
// `targets(x)` computes. An update under-relaxes the volumes (PicardOptions::relaxation) and
// takes the new shapes. QuasiNewtonOptions::max_iterations caps the total number of iterations.
PicardResult picard(const MeshView& view, Vec x, const TargetsAt& targets,
                    const SetTargets& set_targets, const PicardOptions& options,
                    const QuasiNewtonOptions& method, const Observer& observe = {});

// `targets` for picard(): the size field's targets at the centroids of x (adapt_targets),
// volumes summing to `total`. `orientations`: for an anisotropic field, the cells' Jacobians
// where the adaptation starts (Functional::cell_jacobians; empty otherwise). They stay fixed:
// taken from the moving cells, the targets would turn with them, and cells that shear away
// from the surface (a star of flat cells around a circle) would be their own fixed point.
// Keeps references to its other arguments.
TargetsAt size_field_targets(const SizeField& field, const SizeFieldOptions& options,
                             const MeshView& view, const DofMap& dofs, double total,
                             std::vector<double> orientations);

}  // namespace neomesh
