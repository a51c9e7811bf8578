// What an Optimizer holds (include/neomesh/optimizer.hpp), for the library and for the command
// line, which reaches further in than a user does: it prints the boundary's classification and
// fits interfaces (adapt --fit) with the same functional.
//
// One owner per piece of state: the Mesh owns the coordinates between calls; during a call
// they are the Vec x, which is handed back with finish(). The Impl owns the functional, the
// boundary classification, the desired volumes (inside the functional) and what derives from
// them (the cell size of the practical criterion, the round-off level of F).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <neomesh/optimizer.hpp>

#include "boundary/boundary.hpp"
#include "energy/functional.hpp"
#include "mesh/plex_mesh.hpp"
#include "solver/quasi_newton.hpp"

namespace neomesh {

struct Optimizer::Impl {
  explicit Impl(Mesh& mesh);

  const MeshView& view() const { return mesh.plex().view(); }
  const DofMap& dofs() const { return mesh.plex().dofs(); }

  // The mesh's quality where a call starts; throws Error if cells are inverted or degenerate
  // and `untangle` is false.
  QualitySummary input_quality(bool untangle) const;
  // Takes the mesh's coordinates into x and (re)builds the boundary classification and the
  // functional unless they were built for the same energy and boundary options (then the
  // desired volumes stay). Sliding vertices are projected onto their geometry.
  void start(const EnergyOptions& energy, const BoundaryOptions& boundary);
  // Absolute desired volumes per local cell (MeshView order), summing to mesh_volume.
  void set_desired_volumes(std::vector<double> volumes);
  // Rebuilds the functional with `extra` vertices sliding besides the boundary's (an interface
  // fitted to a level set; none: the boundary's alone), keeping the desired volumes.
  const Functional& constrain(SlidingVertices extra);
  // If cells are inverted at x, untangles them (docs/untangling.md) towards the current desired
  // volumes, telling `observer`; throws Error naming the cells that stay inverted.
  std::optional<UntanglingSummary> untangle(const QuasiNewtonOptions& method,
                                            const Observer& observer);
  // The free coordinates and the boundary's classification.
  ProblemSummary problem() const;
  // The solver options with what derives from the mesh.
  QuasiNewtonOptions method(const SolverOptions& solver) const;
  // Volume of each local cell at the mesh's coordinates (where a call starts).
  std::vector<double> cell_volumes() const;
  // Moves the mesh to x and returns its quality; throws Error if a cell is inverted (the
  // energy is infinite there, so the method cannot produce one: a promise kept for every
  // output).
  QualitySummary finish();

  Mesh& mesh;
  OwnedVec x;                // set by start()
  double mesh_volume = 0.0;  // of the mesh when the functional was built
  std::optional<EnergyOptions> energy;
  std::optional<BoundaryOptions> boundary_options;
  std::unique_ptr<Boundary> boundary;
  std::unique_ptr<Functional> functional;
  OwnedVec cell_size;  // local cell size per dof, for the practical criterion
  bool warm = false;   // an adapt() ran: the next one starts from its volumes
};

// The run's iterations, stop reason, energies, defects and times into `result`.
void copy_run(const QuasiNewtonResult& run, Result& result);

}  // namespace neomesh
