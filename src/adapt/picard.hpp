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

#include "adapt/size_field.hpp"
#include "energy/functional.hpp"
#include "solver/quasi_newton.hpp"

namespace neomesh {

struct PicardOptions {
  int min_updates = 6;            // Y: updates before the run may stop (the thesis made 7)
  int update_every = 8;           // X: iterations after which the volumes are updated anyway
  double update_move = 1e-3;      // update when the step moved no vertex more than this · h
  double update_step_norm = 0.0;  // thesis: update when σ‖δ‖ < this (0: not used)
  // Under-relaxation ω of an update: v ← (1−ω) v_old + ω v(centroids). 1 is the thesis.
  double relaxation = 1.0;
};

struct PicardResult {
  QuasiNewtonResult run;  // all iterations, over all sets of desired volumes
  // The iterations (IterationRecord::k) after which the desired volumes were updated.
  std::vector<int> update_iterations;
};

struct PicardObserver {
  std::function<void(const IterationRecord&)> iteration;
  // After iteration k the desired volumes were updated for the `update`-th time.
  std::function<void(int k, int update)> update;
};

// Adapts x (a global coordinate Vec laid out by functional.dofs()) to the volumes that
// `target_volumes(x)` computes (absolute, summing to the mesh volume). `set_volumes` hands
// new desired volumes to `functional` (the owner of the functional may keep more in step).
// QuasiNewtonOptions::max_iterations caps the total number of iterations.
PicardResult picard(const Functional& functional, const MeshView& view, Vec x,
                    const std::function<std::vector<double>(Vec x)>& target_volumes,
                    const std::function<void(const std::vector<double>&)>& set_volumes,
                    const PicardOptions& options, const QuasiNewtonOptions& method,
                    const PicardObserver& observe = {});

// target_volumes for picard(): the size field's desired volumes at the centroids of x,
// summing to `total`. Keeps references to its arguments.
std::function<std::vector<double>(Vec x)> size_field_volumes(const SizeField& field,
                                                             const SizeFieldOptions& options,
                                                             const MeshView& view,
                                                             const DofMap& dofs, double total);

}  // namespace neomesh
