#include "solver/testing/thesis_problem.hpp"

namespace neomesh {

ThesisProblem::ThesisProblem(MeshData mesh_data, EnergyOptions energy_options,
                             BoundaryMode boundary)
    : ThesisProblem(std::move(mesh_data), energy_options, BoundaryOptions(boundary)) {}

ThesisProblem::ThesisProblem(MeshData mesh_data, EnergyOptions energy_options,
                             const BoundaryOptions& boundary_options)
    : data(std::move(mesh_data)),
      view(serial_view(data)),
      dofs(DofMap::serial(view.dim, view.num_vertices)),
      energy(energy_options),
      boundary(std::make_unique<Boundary>(view, dofs, boundary_options)) {
  functional = std::make_unique<Functional>(
      energy, Problem(view, dofs, boundary->fixed_dofs(), boundary->sliding_vertices()));
  x = dofs.create_global_vector();
  {
    VecWriteView out(x);
    for (PetscInt i = 0; i < out.size(); ++i) out[i] = view.coords[i];
  }
  boundary->project(x);  // onto given shapes (they pass through the vertices to 1e-6 h)
  volume = mesh_volume(view, dofs, x);
  const std::vector<double> volumes(view.num_cells, volume / view.num_cells);
  set_desired_volumes(volumes);
  cell_size = local_cell_size(view, dofs, volumes);
}

const Functional& ThesisProblem::set_desired_volumes(std::span<const double> volumes) {
  functional =
      std::make_unique<Functional>(energy, functional->problem().with_desired_volumes(volumes));
  return *functional;
}

QuasiNewtonOptions ThesisProblem::thesis_options() const {
  QuasiNewtonOptions o;
  o.linear_solver = LinearSolverKind::Direct;
  o.advanced.kmin = 0;
  o.advanced.alpha0 = QuasiNewtonOptions::Advanced::kThesisAlpha0;
  o.riesz_rtol = QuasiNewtonOptions::kThesisRieszRtol;
  o.advanced.hessian_forcing_max = 0.0;
  o.advanced.max_trial_move = 0.0;
  o.advanced.lazy_riesz = false;
  o.practical = false;
  o.advanced.rejected_direction = RejectedDirection::Antigradient;
  o.defect_atol = 1e-10;
  o.defect_rtol = 0.0;
  o.energy_roundoff = energy_roundoff(energy, view.dim, volume);
  return o;
}

SolverRun ThesisProblem::minimize(const QuasiNewtonOptions& options) {
  return neomesh::minimize(*functional, x, options, cell_size);
}

}  // namespace neomesh
