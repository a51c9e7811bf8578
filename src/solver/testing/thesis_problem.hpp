// A thesis test case as a serial problem: a generated mesh, uniform desired volumes, fixed
// (or sliding) boundary vertices and the thesis' parameters (docs/cases.md: λ = 1, μ = 10,
// α₀ = 0.3, η = 0.6). Used by the solver tests and benchmarks.
#pragma once

#include <memory>
#include <span>

#include "boundary/boundary.hpp"
#include "energy/functional.hpp"
#include "generate/serial_view.hpp"
#include "mesh/dof_map.hpp"
#include "mesh/mesh_data.hpp"
#include "solver/quasi_newton.hpp"

namespace neomesh {

struct ThesisProblem {
  explicit ThesisProblem(MeshData mesh_data, EnergyOptions energy = {},
                         BoundaryMode boundary = BoundaryMode::Fixed);
  ThesisProblem(MeshData mesh_data, EnergyOptions energy, const BoundaryOptions& boundary);

  MeshData data;
  MeshView view;
  DofMap dofs;
  EnergyOptions energy;
  std::unique_ptr<Boundary> boundary;
  std::unique_ptr<Functional> functional;
  OwnedVec x;  // initial coordinates; minimize() moves them
  OwnedVec cell_size;
  double volume = 0.0;

  // The functional of the problem with these desired volumes (its constraints and shapes
  // kept), replacing the one before.
  const Functional& set_desired_volumes(std::span<const double> volumes);
  // The thesis' method options: direct solver, k_min = 0, no practical criterion.
  QuasiNewtonOptions thesis_options() const;
  SolverRun minimize(const QuasiNewtonOptions& options);
};

}  // namespace neomesh
