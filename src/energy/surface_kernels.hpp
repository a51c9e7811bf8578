// energy/surface_kernels.hpp — the energy of one surface cell and its derivatives
// (docs/method.md, "Surface cells"): a triangle or quadrilateral whose vertices are points in
// space (3 coordinates each) and slide on the input surface.
//
// The cell gets a tangent frame Q = [t1 t2] (3 × 2, orthonormal, t1 × t2 = n its reference
// unit normal), and its energy is the 2D energy (Neo-Hookean, or the untangling law) of its
// image in that frame:
//
//   G = Qᵀ X D_qᵀ,   E(X) = E₂(Qᵀ X),   ∂E/∂X = Q ∂E₂/∂Y,   ∂²E/∂X² = (I ⊗ Q) ∂²E₂/∂Y² (I ⊗ Qᵀ)
//
// with E₂ the 2D cell kernel (cell_kernels.hpp) of the same type, law and target (desired
// volume = desired area, shapes as in 2D) and Y = Qᵀ X the cell's 2D image. Every matrix the
// quasi-Newton method uses (B1 + α B2, μ times the target cell's Laplacian) is the 2D one with
// each 2 × 2 vertex block A lifted to Q A Qᵀ.
//
// Why Q is fixed during one solve (and refreshed between solves, as the desired volumes are):
// - with Q fixed, X ↦ Qᵀ X is linear, so the energy is the 2D law composed with a linear map:
//   its gradient and Hessian are the 2D ones pulled back exactly, H(α) keeps its split and its
//   positive definiteness for small α, and the solver and its convergence theory carry over.
//   A frame recomputed from X at every evaluation would add the frame's derivatives (a term
//   with the stress times ∂Q/∂X, indefinite) to every matrix.
// - the energy does not see the normal direction: a move along n leaves Qᵀ X, and so E,
//   unchanged. That direction is the one the sliding constraint removes (every vertex moves in
//   the tangent plane of the surface, energy/sliding_vertices.hpp), so nothing is lost.
// - the error is small: a cell tilted by θ against the plane of its frame is seen with its
//   lengths across the tilt axis shortened by cos θ = 1 − θ²/2 + …, so its energy differs from
//   that of the cell laid flat by O(θ²). A cell that turns as it slides over a curved surface
//   stays close to its frame within one solve, and the next solve takes a new frame.
#pragma once

#include "energy/cell_kernels.hpp"
#include "geometry/surface_frame.hpp"

namespace neomesh {

// The 2D cell kernel of `Law` (NeoHooke<2> or RegularizedNeoHooke<2>) on the image of a
// surface cell in its frame. Every function takes X (3 × vertices) and the cell's frame Q,
// fixed during a solve (see above), and returns what CellKernel returns for Y = Qᵀ X, lifted
// to 3 coordinates per vertex (dof = 3 · vertex + component).
template <CellType Type, typename Law>
class SurfaceCellKernel {
 public:
  static_assert(CellTraits<Type>::dim == 2, "a surface cell is a triangle or a quadrilateral");
  using Planar = CellKernel<Type, Law>;
  static constexpr CellType type = Type;
  static constexpr int dim = 3;
  static constexpr int vertices = Planar::vertices;
  static constexpr int dofs = dim * vertices;
  using Coordinates = Eigen::Matrix<double, dim, vertices>;  // X, one column per vertex
  using Gradient = Coordinates;                              // ∂(cell energy)/∂X
  using Block = Eigen::Matrix<double, dofs, dofs>;           // (dof, dof) in local order
  using Target = CellTarget<2>;  // desired area and shape, as for a 2D cell

  // As CellKernel's: `corner_weight` is the share of the corner samples.
  SurfaceCellKernel(const Law& law, int gauss_points, double corner_weight = 0.0)
      : planar_(law, gauss_points, corner_weight) {}

  // Y = Qᵀ X: the cell's image in its frame, the 2D cell the law sees.
  static typename Planar::Coordinates in_frame(const Coordinates& x, const SurfaceFrame& frame) {
    return frame.transpose() * x;
  }

  // Whether the image is orientation-preserving at every corner (CellKernel's), i.e. whether
  // no corner is folded against the frame's normal.
  static bool corners_admissible(const Coordinates& x, const SurfaceFrame& frame) {
    return Planar::corners_admissible(in_frame(x, frame));
  }

  // E₂(Qᵀ X); +∞ for a barrier law where the image is inadmissible.
  double energy(const Coordinates& x, const SurfaceFrame& frame, const Target& target) const {
    return planar_.energy(in_frame(x, frame), target);
  }

  // The energy and its gradient Q ∂E₂/∂Y (tangent to the frame: no normal component).
  double energy_and_gradient(const Coordinates& x, const SurfaceFrame& frame, const Target& target,
                             Gradient& gradient) const {
    typename Planar::Gradient planar;
    const double energy = planar_.energy_and_gradient(in_frame(x, frame), target, planar);
    gradient.noalias() = frame * planar;
    return energy;
  }

  // H(α) = B1 + α B2 + B3 of the image, each vertex block lifted to Q A Qᵀ; exactly symmetric.
  // False (block unspecified) if the law is infinite at some point.
  bool hessian(const Coordinates& x, const SurfaceFrame& frame, const Target& target, double alpha,
               Eigen::Ref<Block> block) const {
    typename Planar::Block planar;
    if (!planar_.hessian(in_frame(x, frame), target, alpha, planar)) return false;
    lift(planar, frame, block);
    return true;
  }

  // The target cell's vector Laplacian (B3/μ) lifted: ∫ ∇φ̂_i·∇φ̂_j Q Qᵀ, the projector onto
  // the frame's plane per vertex pair.
  void optimal_laplacian(const SurfaceFrame& frame, const Target& target,
                         Eigen::Ref<Block> block) const {
    typename Planar::Block planar;
    planar_.optimal_laplacian(target, planar);
    lift(planar, frame, block);
  }

  // The image's Laplacian (CellKernel::current_laplacian) lifted; false if det G ≤ 0 somewhere.
  bool current_laplacian(const Coordinates& x, const SurfaceFrame& frame, const Target& target,
                         Eigen::Ref<Block> block) const {
    typename Planar::Block planar;
    if (!planar_.current_laplacian(in_frame(x, frame), target, planar)) return false;
    lift(planar, frame, block);
    return true;
  }

  // The image's area and smallest det G (CellKernel::measure).
  CellMeasure measure(const Coordinates& x, const SurfaceFrame& frame, const Target& target) const {
    return planar_.measure(in_frame(x, frame), target);
  }
  // energy() and measure() at once (CellKernel::energy_and_measure).
  std::pair<double, CellMeasure> energy_and_measure(const Coordinates& x, const SurfaceFrame& frame,
                                                    const Target& target) const {
    return planar_.energy_and_measure(in_frame(x, frame), target);
  }

 private:
  // Block (i, j) = Q A_ij Qᵀ for the 2D block A_ij; the lower blocks computed, the upper ones
  // mirrored, so the result is as exactly symmetric as the 2D one.
  static void lift(const typename Planar::Block& planar, const SurfaceFrame& frame,
                   Eigen::Ref<Block> block) {
    for (int j = 0; j < vertices; ++j)
      for (int i = j; i < vertices; ++i)
        block.template block<dim, dim>(dim * i, dim * j).noalias() =
            frame * planar.template block<2, 2>(2 * i, 2 * j) * frame.transpose();
    block.template triangularView<Eigen::StrictlyUpper>() = block.transpose().eval();
  }

  Planar planar_;
};

// The thesis' energy of a surface cell.
template <CellType Type>
using NeoHookeSurfaceKernel = SurfaceCellKernel<Type, NeoHooke<2>>;

// The untangling energy of a surface cell: the regularized law at the samples of the 2D
// untangling kernel (cell_kernels.hpp).
template <CellType Type>
using UntanglingSurfaceKernel = SurfaceCellKernel<Type, RegularizedNeoHooke<2>>;

template <CellType Type>
UntanglingSurfaceKernel<Type> make_untangling_surface_kernel(const RegularizedNeoHooke<2>& law,
                                                             int gauss_points) {
  return UntanglingSurfaceKernel<Type>(law, gauss_points, untangling_corner_weight<Type>());
}

}  // namespace neomesh
