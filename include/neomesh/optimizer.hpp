// neomesh::Optimizer: moves the vertices of a Mesh to minimize the Neo-Hookean energy
// (docs/method.md), either towards ideal cells of given sizes (smooth) or so that cells follow
// a size field (adapt). It owns what the optimization needs besides the mesh: the functional,
// the desired volumes and what derives from them, kept from one call to the next — so that a
// simulation whose geometry moves calls adapt() once per time step and each step starts warm
// from the one before.
#pragma once

#include <memory>

#include <neomesh/level_set.hpp>
#include <neomesh/mesh.hpp>
#include <neomesh/options.hpp>
#include <neomesh/result.hpp>
#include <neomesh/size_field.hpp>

namespace neomesh {

class Optimizer {
 public:
  // `mesh` must outlive the Optimizer; its coordinates are where every call starts, and every
  // call leaves the optimized coordinates in it. Collective over the mesh's communicator.
  explicit Optimizer(Mesh& mesh);
  ~Optimizer();
  Optimizer(Optimizer&&) noexcept;
  Optimizer& operator=(Optimizer&&) noexcept;

  // Every cell towards an ideal cell of its desired volume (thesis chapter 5); inverted cells
  // are untangled first unless options.untangle is false. Throws Error if the options are out
  // of range, if cells stay inverted, or if the boundary cannot be classified. Collective.
  // Called again with the same energy, boundary and targets options (the mesh moved a little
  // between calls), it starts warm: the targets are the mesh's as it finds them, as in any
  // call, but the quasi-Newton method starts in the Newton regime, with the α the last call
  // ended with and no antigradient steps (solver.advanced.alpha0, if set, still wins).
  Result smooth(const SmoothOptions& options = {}, const Observer& observer = {});

  // Cells crowd where `field` is small (thesis chapter 6): the desired volumes are recomputed
  // from the moving mesh in Picard iterations. The first call starts cold; a later call (the
  // field moved, e.g. set_time) starts warm from the mesh the last one left, where the field's
  // desired volumes are nearly met, and may stop after options.warm_updates updates. Inverted
  // cells are untangled first unless options.untangle is false. Collective.
  Result adapt(const SizeField& field, const AdaptOptions& options = {},
               const Observer& observer = {});
  // The same, then the mesh fitted to the zero set of `fit_to` at its time (docs/adaptivity.md):
  // a chain of edges (2D) or surface of faces (3D) — Mesh::interface() — is pulled onto it in
  // stages while the whole mesh is optimized, no cell inverted. A warm start adapts briefly
  // before (the fit goes on optimizing). The fit holds until the next smooth() or adapt().
  // Throws Error ("fit: ...") if there is no interface inside the mesh, it touches the
  // boundary, or no stage can be taken without inverting a cell. Collective; the interface may
  // cross processes.
  Result adapt(const SizeField& field, const LevelSet& fit_to, const AdaptOptions& options = {},
               const Observer& observer = {});
  // The same with φ itself as the size field (d = |φ|, SizeField::level_set of its expression)
  // at its time: one object to move (set_time) for a geometry that is both adapted to and fitted.
  Result adapt(const LevelSet& phi, const AdaptOptions& options = {},
               const Observer& observer = {});
  // The next smooth() or adapt() starts cold (the mesh was changed in another way, say).
  void forget_warm_start();

  // Per local cell at the mesh's coordinates: "energy", "det_G_min", "Q" (actual over desired
  // volume) and "desired_volume", for Mesh::write; after a fit also "inside" (1 where φ < 0).
  // Empty before the first call.
  std::vector<Field> cell_fields() const;
  // After a fit, per vertex of Mesh::vertex_numbers(): "interface" (1 on the fitted vertices)
  // and "phi" (φ there); empty otherwise.
  std::vector<Field> vertex_fields() const;
  // After a fit, the fitted facets as the group "interface"; empty otherwise.
  std::vector<FacetGroup> facet_groups() const;

  // Where smooth(options) would start, without moving a vertex: sets up the functional and the
  // desired volumes (options.sizes) at the mesh's coordinates and returns the energy F there
  // (+∞ if a cell is inverted: nothing is refused or untangled). cell_fields() then gives
  // every cell's energy and Q, e.g. for a picture of a mesh before it is smoothed. Throws
  // OptionError if the options are out of range. Collective.
  double evaluate(const SmoothOptions& options = {});

 private:
  struct Impl;  // src/api/optimizer_impl.hpp
  std::unique_ptr<Impl> impl_;
};

}  // namespace neomesh
