// The global mesh functional F(x) = Σ_K ∫_{optimal cell of K} W(∇γ_K) (docs/method.md §2) over
// this rank's cells, with its gradient and the quasi-Newton matrix H(α) = B1 + α B2 + B3
// (§3), plus the Riesz Laplacian L (§4). All vectors are global PETSc Vecs laid out by a
// DofMap; every method is collective.
//
// Fixed dofs (all coordinates of boundary vertices by default, or single coordinates) are
// eliminated: the gradient is zero there, and the rows and columns of H(α) and L are those
// of the identity, so that the Newton defect is the free-dof norm of the gradient and every
// linear solve leaves fixed dofs unchanged. Vertices that slide on a curved boundary are
// restricted to their tangent spaces the same way (sliding_vertices.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <neomesh/options.hpp>

#include "core/petsc.hpp"
#include "energy/neo_hooke.hpp"
#include "energy/problem.hpp"
#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

struct CellFields {
  std::vector<double> energy;        // ∫ W over the cell's optimal cell
  std::vector<double> min_det;       // min over quadrature points of det G (+∞ never: see below)
  std::vector<double> volume_ratio;  // Q = actual volume / desired volume
};

// Cells inverted at some x: det G ≤ 0 at a sample point of the untangling energy
// (cell_kernels.hpp: the corners of Q1 cells, and the Gauss points of hexahedra).
struct Inversion {
  PetscInt count = 0;           // over all ranks
  double min_det = 0.0;         // the smallest det G at a sample point, over all ranks
  std::vector<PetscInt> cells;  // the first few inverted cells, global (input) numbers
};

// What a matrix of H(α) is for: its entries (a preconditioner built from them, or a direct
// solver), or only products with it (a solve that L preconditions).
enum class HessianUse { Entries, Products };

class Functional {
 public:
  // The functional of `problem` on its constraints' mesh; throws Error without constraints.
  // Their view and DofMap must outlive the Functional; only their connectivity and layout are
  // used (coordinates always come from the Vec x of each call).
  Functional(const EnergyOptions& options, Problem problem);
  ~Functional();
  // Movable, so that its holder can take the Functional of another problem instead.
  Functional(Functional&&) noexcept;
  Functional& operator=(Functional&&) noexcept;

  // What it was built from: a phase derives its own problem from this one.
  const EnergyOptions& options() const;
  const Problem& problem() const;

  // Each local cell's Jacobian at x, at its centre, relative to its unit ideal cell (dim² per
  // cell, column-major, MeshView order): the shape an `input` target takes.
  std::vector<double> cell_jacobians(Vec x) const;

  // F(x); +∞ when any cell has det G ≤ 0 at a quadrature point (never NaN).
  double value(Vec x) const;
  // F(x) and its gradient (zero at fixed dofs). Returns +∞ (gradient unspecified) if inverted.
  double value_and_gradient(Vec x, Vec gradient) const;

  // A matrix with the sparsity of H(α) and L (the pattern of the problem's Constraints: any
  // Functional of the same Constraints assembles into it), not yet assembled. For
  // HessianUse::Products, on one rank, it stores each coupling once (the blocks on and above
  // the diagonal, about half the memory) and only multiplies.
  OwnedMat create_matrix(HessianUse use = HessianUse::Entries) const;
  // H(α) at x into a matrix made by create_matrix (values only). With vertices sliding on a
  // curved boundary its curvature term uses the forces of the last value_and_gradient, which
  // must have been at the same x.
  void assemble_hessian(Vec x, double alpha, Mat H) const;
  // A matrix with the sparsity of L only: the vector Laplacian couples no two components, so
  // it has 1/dim of the entries of create_matrix (cheaper AMG setup and V-cycles). With
  // vertices in tangent spaces (on any rank) it is create_matrix's: their projectors couple
  // the components.
  OwnedMat create_laplacian_matrix() const;
  // True if L is dim copies of one scalar n × n Laplacian L₁, one per component (interlaced):
  // no vertex slides and every vertex has all or none of its coordinates fixed, on every rank.
  bool laplacian_is_scalar() const;
  // With laplacian_is_scalar(): L as MatCreateMAIJ(L₁, dim), laid out like the other
  // matrices; only L₁ is stored (1/dim of create_laplacian_matrix's entries). Throws Error
  // otherwise.
  OwnedMat create_scalar_laplacian_matrix() const;
  // The Riesz Laplacian into a matrix made by create_laplacian_matrix, create_matrix or
  // create_scalar_laplacian_matrix (into its L₁). `x` is used for RieszLaplacian::CurrentMesh
  // and for the tangent spaces of sliding vertices.
  void assemble_laplacian(RieszLaplacian kind, Vec x, Mat L) const;

  // The inverted cells at x, listing at most `listed` of them. Collective. With `below` > 0,
  // the cells whose det G is at most that at a sample point (nearly flat ones too).
  Inversion inversion(Vec x, int listed = 10, double below = 0.0) const;

  // A surface mesh's cell frames taken again at x (docs/method.md, "Surface cells"): from now on
  // the energy, its derivatives and the matrices are those of the cells' frames at x, until the
  // next call (the quasi-Newton method calls it where each step starts). Before the first,
  // the frames are those at the view's coordinates, where the call started. False (nothing done)
  // for other meshes. Not collective.
  bool refresh_frames(Vec x) const;

  // Moves the sliding vertices of x back onto the boundary after a step (no-op if none
  // slide). Not collective.
  void project_onto_boundary(Vec x) const;
  // True if vertices slide on a curved or oblique boundary on some rank.
  bool slides() const;

  // Per-cell energy, min det G and volume ratio Q at x (MeshView order).
  CellFields cell_fields(Vec x) const;

  const DofMap& dofs() const;
  // The number of free dofs, over all ranks.
  std::int64_t free_dofs() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Total volume of the mesh at x (sum over all ranks).
double mesh_volume(const MeshView& view, const DofMap& dofs, Vec x);

}  // namespace neomesh
