// The optimization problem as a value: the law, what each cell should become (its target) and
// which vertices may move (the constraints). A Functional is built from one and never changes
// it; a phase (an untangling round, the corner lift, a retry with the boundary pinned, a fit's
// interface) derives a new Problem from the current one and builds its own Functional.
// Copies are cheap: targets and constraints are immutable and shared.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "energy/matrix_assembler.hpp"
#include "energy/sliding_vertices.hpp"
#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

// Per local dof (dim * vertex + component, MeshView order): 1 if that coordinate does not
// move. Lets a boundary vertex slide within a plane x_j = const (boundary/boundary.hpp).
struct FixedDofs {
  std::vector<std::uint8_t> flags;
};

// Which vertices move, and how, on one mesh, with what derives from that alone: the free dofs
// and the matrices' pattern. Built once per mesh and constraints and shared by every
// Functional of them, so that a new law or new targets cost no new pattern, and matrices made
// by one of these Functionals can be assembled by another.
class Constraints {
 public:
  // `fixed` marks local vertices whose coordinates do not move (MeshView order). `view` and
  // `dofs` are kept by reference and must outlive the Constraints. Collective.
  Constraints(const MeshView& view, const DofMap& dofs, const std::vector<std::uint8_t>& fixed);
  // The same with single coordinates fixed, and vertices restricted to tangent spaces.
  Constraints(const MeshView& view, const DofMap& dofs, FixedDofs fixed,
              SlidingVertices sliding = {});
  Constraints(const Constraints&) = delete;
  Constraints& operator=(const Constraints&) = delete;

  const MeshView& view;
  const DofMap& dofs;
  // Per local dof; vertices of no cell are fixed too (they have no energy).
  std::vector<std::uint8_t> fixed;
  SlidingVertices sliding;
  std::vector<PetscInt> projector_of;  // per local vertex: its index in sliding.vertices, or -1
  bool slides_anywhere = false;        // sliding.vertices is not empty on some rank
  bool scalar_laplacian = false;       // see Functional::laplacian_is_scalar
  std::int64_t free_dofs = 0;          // over all ranks

  // The pattern, built by the first matrix asked for (not every use needs one). Collective.
  MatrixAssembler& assembler() const;

 private:
  mutable std::optional<MatrixAssembler> assembler_;
};

// What each local cell should become (docs/method.md, "Target cells"), in the form the kernels
// use (cell_kernels.hpp: CellTarget).
struct Targets {
  // Desired (absolute) volumes per local cell, MeshView order (a surface cell's: its area); and
  // the shape S of each cell's target (d² numbers per cell, d = view.cell_dim(), column-major,
  // scaled here to det S = 1) with the weight of its energy (empty: 1). Empty shapes: the thesis'
  // ideal cells. Throws Error for a volume or det S ≤ 0, a weight ≤ 0 or a wrong length.
  Targets(const MeshView& view, std::span<const double> volumes,
          std::span<const double> shapes = {}, std::span<const double> weights = {});
  // New volumes, the shapes and weights of `shaped`.
  Targets(const MeshView& view, std::span<const double> volumes, const Targets& shaped);

  std::vector<double> volumes;        // desired volume per local cell
  std::vector<double> inverse_edges;  // per local cell v^(−1/d)
  std::vector<double> shapes_inv_t;   // per local cell S⁻ᵀ with det S = 1; empty: ideal
  std::vector<double> weights;        // per local cell with shapes: its energy's weight
};

// Per local cell of a surface mesh its tangent frame Q at `coords` (view.coords' layout;
// surface_frame.hpp): 6 numbers, column-major, about the cell's reference normal
// (surface_orientation.hpp, summed over the ranks of `dofs`), so that a folded cell sees its
// mirror image; empty for other meshes. Throws Error for a cell without area. The Functional takes
// them where a call starts and again where each step starts (docs/method.md, "Surface cells").
std::vector<double> surface_frames(const MeshView& view, const DofMap& dofs,
                                   std::span<const double> coords);

struct Problem {
  // Untangling (docs/untangling.md): with ε > 0 the functional's value, gradient and H(α) are
  // those of the untangling energy (regularized_neo_hooke.hpp), finite on inverted cells; 0 is
  // the Neo-Hookean energy. The Riesz Laplacian and cell fields are the Neo-Hookean ones.
  double untangling_epsilon = 0.0;
  // The share of the corner samples in the Neo-Hookean energy of cells other than simplices
  // (OptimalCellQuadrature): 0, the thesis' Gauss rule, lets a corner of a Q1 cell, wedge or
  // pyramid flatten while its Gauss points stay well; > 0 puts the law's barrier there too
  // (the worst-cell phase of smoothing, docs/method.md).
  double corner_weight = 0.0;
  // Null until set: a Functional without them fails on evaluation.
  std::shared_ptr<const Targets> targets;
  std::shared_ptr<const Constraints> constraints;

  Problem() = default;
  explicit Problem(std::shared_ptr<const Constraints> c) : constraints(std::move(c)) {}
  // Problem(make_shared<Constraints>(view, dofs, fixed...)), the common case.
  Problem(const MeshView& view, const DofMap& dofs, const std::vector<std::uint8_t>& fixed);
  Problem(const MeshView& view, const DofMap& dofs, FixedDofs fixed, SlidingVertices sliding = {});

  Problem with_untangling(double epsilon) const;
  Problem with_corner_weight(double weight) const;
  // Targets(view, volumes, shapes, weights) of the constraints' mesh.
  Problem with_targets(std::span<const double> volumes, std::span<const double> shapes = {},
                       std::span<const double> weights = {}) const;
  // New desired volumes; the target shapes and weights stay.
  Problem with_desired_volumes(std::span<const double> volumes) const;
  Problem with_constraints(std::shared_ptr<const Constraints> c) const;

  // The targets' volumes (empty while no targets are set).
  const std::vector<double>& desired_volumes() const;
};

}  // namespace neomesh
