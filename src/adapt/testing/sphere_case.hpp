// Test helper for the chapter-6 cases of the thesis (docs/cases.md): [-1,1]^d adapted to the
// circle/sphere of radius 0.7 around the origin, with the numbers the issue judges them by.
// Used by picard_test.cpp and picard_longtest.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <fmt/format.h>

#include "adapt/picard.hpp"
#include "adapt/volume_ratio.hpp"
#include "generate/generate.hpp"
#include "geometry/quality.hpp"
#include "solver/testing/thesis_problem.hpp"
#include "targets/size_field.hpp"

namespace neomesh::testing {

constexpr double kRadius = 0.7;

struct SphereOutcome {
  PicardResult result;
  int armijo_steps = 0, rejected = 0;
  VolumeRatioStats q;
  double min_scaled_jacobian = 0.0;
  int inverted = 0;
  // Mean volume of the cells within 0.05 of the surface over that of the cells farther
  // than 0.5 (centroids of the adapted mesh).
  double near_far = 0.0;
  double seconds = 0.0;

  bool converged() const {
    const StopReason r = result.run.reason;
    return r == StopReason::DefectAbsolute || r == StopReason::DefectRelative ||
           r == StopReason::Practical;
  }
};

// neomesh's defaults for adapt (docs/adaptivity.md; AdaptOptions): λ = 4 μ, 2 Gauss points, sliding
// boundary vertices, desired volumes bounded (ratio 32, SizeFieldOptions) and smoothed once.
const EnergyOptions kAdaptEnergy = AdaptOptions().energy;

inline SphereOutcome adapt_to_sphere(CellType type, int n, const SizeFieldOptions& field_options,
                                     const PicardOptions& picard_options = {},
                                     const EnergyOptions& energy = {},
                                     BoundaryMode boundary = BoundaryMode::Fixed) {
  ThesisProblem p(box(type, n), energy, boundary);
  const int d = p.view.dim;
  const SizeField field = SizeField::sphere(std::vector<double>(d, 0.0), kRadius);
  QuasiNewtonOptions method;
  method.energy_roundoff = energy_roundoff(energy, d, p.volume);
  const double start = MPI_Wtime();
  SphereOutcome out;
  out.result = picard(
      p.view, p.x,
      [&](Vec x) {
        std::vector<double> coords(p.dofs.num_local_dofs());
        p.dofs.global_to_local(x, coords);
        return build_targets(AdaptationRequest{&field, field_options}, p.view, p.dofs,
                             {.coords = coords, .mesh_volume = p.volume});
      },
      [&](const CellTargets& t) -> const Functional& { return p.set_desired_volumes(t.volumes); },
      picard_options, method);
  out.seconds = MPI_Wtime() - start;
  for (const IterationRecord& r : out.result.run.history) {
    out.armijo_steps += r.armijo_steps;
    out.rejected += r.delta_solved && r.used_s;
  }
  out.q = volume_ratio_stats(p.functional->cell_fields(p.x).volume_ratio, PETSC_COMM_SELF);

  std::vector<double> coords(p.dofs.num_local_dofs());
  p.dofs.global_to_local(p.x, coords);
  const CellQuality quality = cell_quality(p.view, coords);
  out.min_scaled_jacobian =
      *std::min_element(quality.scaled_jacobian.begin(), quality.scaled_jacobian.end());
  const std::vector<double> centroids = cell_centroids(p.view, coords);
  double near = 0.0, far = 0.0;
  int near_cells = 0, far_cells = 0;
  for (PetscInt c = 0; c < p.view.num_cells; ++c) {
    out.inverted += quality.min_gauss_det[c] <= 0 || quality.min_corner_det[c] <= 0;
    double r2 = 0.0;
    for (int j = 0; j < d; ++j) r2 += centroids[c * d + j] * centroids[c * d + j];
    const double distance = std::abs(std::sqrt(r2) - kRadius);
    if (distance <= 0.05) near += quality.volume[c], ++near_cells;
    if (distance > 0.5) far += quality.volume[c], ++far_cells;
  }
  out.near_far = (near / near_cells) / (far / far_cells);
  std::string updates = fmt::format("{}", fmt::join(out.result.update_iterations, ", "));
  std::printf(
      "%s %d^%d, boundary %s: %zu iterations, %d Armijo steps, δ rejected %d times, updates "
      "after [%s], %s; Q in [0.5, 2]: %.1f%%, min %.3g, median %.3g, max %.3g; min scaled "
      "Jacobian %.3f; near/far volume %.3f; %.1f s\n",
      std::string(name(type)).c_str(), n, d, boundary == BoundaryMode::Slide ? "slide" : "fixed",
      out.result.run.history.size(), out.armijo_steps, out.rejected, updates.c_str(),
      describe(out.result.run.reason).c_str(), 100 * out.q.within, out.q.min, out.q.median,
      out.q.max, out.min_scaled_jacobian, out.near_far, out.seconds);
  return out;
}

}  // namespace neomesh::testing
