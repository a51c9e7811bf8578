#include "energy/problem.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "core/error.hpp"
#include "geometry/surface_frame.hpp"
#include "geometry/surface_orientation.hpp"

namespace neomesh {

namespace {

// Every coordinate of a fixed vertex is a fixed dof.
FixedDofs per_dof(const MeshView& view, const std::vector<std::uint8_t>& fixed_vertices) {
  if (static_cast<PetscInt>(fixed_vertices.size()) != view.num_vertices)
    fail("Functional: {} fixed flags for {} local vertices", fixed_vertices.size(),
         view.num_vertices);
  FixedDofs fixed;
  for (std::uint8_t f : fixed_vertices) fixed.flags.insert(fixed.flags.end(), view.dim, f);
  return fixed;
}

// S⁻ᵀ scaled to det 1 per cell (fixed-size: a mesh has up to millions of them); fails for a
// shape or weight that is not positive.
template <int Dim>
void invert_target_shapes(std::span<const double> shapes, const std::vector<double>& weights,
                          std::vector<double>& inverse_t) {
  using Matrix = Eigen::Matrix<double, Dim, Dim>;
  constexpr std::size_t n = Dim * Dim;
  const std::size_t cells = shapes.size() / n;
  std::size_t first_bad = cells;  // cell by cell on every thread; the first bad one is named
#pragma omp parallel for schedule(static) reduction(min : first_bad)
  for (std::size_t c = 0; c < cells; ++c) {
    const Eigen::Map<const Matrix> S(shapes.data() + c * n);
    const double det = S.determinant();
    if (!(det > 0.0) || !std::isfinite(det) || !(weights[c] > 0.0) || !std::isfinite(weights[c])) {
      first_bad = std::min(first_bad, c);
      continue;
    }
    Eigen::Map<Matrix>(inverse_t.data() + c * n) =
        std::pow(det, 1.0 / Dim) * S.inverse().transpose();
  }
  if (first_bad == cells) return;
  const double det = Eigen::Map<const Matrix>(shapes.data() + first_bad * n).determinant();
  if (!(det > 0.0) || !std::isfinite(det))
    fail("the target shape of local cell {} has determinant {} (must be positive)", first_bad, det);
  fail("the target weight of local cell {} is {} (must be positive)", first_bad,
       weights[first_bad]);
}

void set_volumes(const MeshView& view, std::span<const double> volumes, Targets& t) {
  if (static_cast<PetscInt>(volumes.size()) != view.num_cells)
    fail("Functional: {} desired volumes for {} cells", volumes.size(), view.num_cells);
  for (std::size_t c = 0; c < volumes.size(); ++c)
    if (!(volumes[c] > 0.0) || !std::isfinite(volumes[c]))
      fail("desired volume of local cell {} is {} (must be positive and finite)", c, volumes[c]);
  t.volumes.assign(volumes.begin(), volumes.end());
  t.inverse_edges.resize(volumes.size());
  const double power = -1.0 / view.cell_dim();
  for (std::size_t c = 0; c < volumes.size(); ++c) t.inverse_edges[c] = std::pow(volumes[c], power);
}

}  // namespace

std::vector<double> surface_frames(const MeshView& view, const DofMap& dofs,
                                   std::span<const double> coords) {
  if (!view.surface) return {};
  const std::vector<double> normals = surface_reference_normals(view, coords, &dofs);
  std::vector<double> frames(static_cast<std::size_t>(6 * view.num_cells));
  for (const CellBlock& block : view.blocks)
    for (PetscInt c = 0; c < block.size(); ++c) {
      const PetscInt cell = block.first_cell + c;
      const auto point = [&](int i) {
        return Eigen::Map<const Vector<3>>(coords.data() + 3 * block.cell(c)[i]);
      };
      const Vector<3> normal = Eigen::Map<const Vector<3>>(normals.data() + 3 * cell);
      // t1 along the first edge, as surface_cell_frame takes it.
      const std::optional<SurfaceFrame> frame =
          normal.isZero(0.0) ? std::nullopt : tangent_frame(normal, point(1) - point(0));
      if (!frame)
        fail("surface cell {} has no area: it has no tangent plane",
             view.global_cell.empty() ? cell : view.global_cell[cell]);
      Eigen::Map<SurfaceFrame>(frames.data() + 6 * cell) = *frame;
    }
  return frames;
}

Constraints::Constraints(const MeshView& v, const DofMap& d, const std::vector<std::uint8_t>& f)
    : Constraints(v, d, per_dof(v, f)) {}

Constraints::Constraints(const MeshView& v, const DofMap& d, FixedDofs f, SlidingVertices s)
    : view(v), dofs(d), fixed(std::move(f.flags)), sliding(std::move(s)) {
  if (dofs.dim() != view.dim)
    fail("Functional: the mesh is {}D but its DofMap has {} components", view.dim, dofs.dim());
  if (static_cast<PetscInt>(fixed.size()) != view.num_vertices * view.dim)
    fail("Functional: {} fixed flags for {} local dofs", fixed.size(),
         view.num_vertices * view.dim);
  if (dofs.num_local_dofs() != view.num_vertices * view.dim)
    fail("Functional: DofMap has {} local dofs, the mesh {} vertices of dimension {}",
         dofs.num_local_dofs(), view.num_vertices, view.dim);
  for (const CellBlock& block : view.blocks)
    if (dimension(block.type) != view.cell_dim())
      fail("Functional: {} cells in a {}D mesh", name(block.type), view.cell_dim());
  // A file's vertex that no cell uses (Gmsh writes the nodes of every curve of an extrusion with
  // rotation, not all of them the volume's) has no energy: free, its rows of the matrices would
  // be empty, and hypre's eigenvalue estimate loops forever on them. It stays.
  std::vector<std::uint8_t> used(view.num_vertices, 0);
  for (const CellBlock& block : view.blocks)
    for (PetscInt c = 0; c < block.size(); ++c)
      for (int i = 0; i < block.nodes(); ++i) used[block.cell(c)[i]] = 1;
  for (PetscInt u = 0; u < view.num_vertices; ++u)
    if (!used[u]) std::fill_n(fixed.begin() + u * view.dim, view.dim, 1);
  projector_of.assign(view.num_vertices, -1);
  for (std::size_t i = 0; i < sliding.vertices.size(); ++i)
    projector_of[sliding.vertices[i]] = static_cast<PetscInt>(i);
  int slides = !sliding.vertices.empty();
  MPI_Allreduce(MPI_IN_PLACE, &slides, 1, MPI_INT, MPI_MAX, dofs.comm());
  slides_anywhere = slides != 0;
  int alike = 1;  // every local vertex has all or none of its coordinates fixed
  for (PetscInt l = 0; l < dofs.num_local_dofs(); ++l)
    if (fixed[l] != fixed[l - l % view.dim]) alike = 0;
  MPI_Allreduce(MPI_IN_PLACE, &alike, 1, MPI_INT, MPI_MIN, dofs.comm());
  scalar_laplacian = !slides_anywhere && alike;

  for (PetscInt l = 0; l < dofs.num_local_dofs(); ++l)
    if (view.owned[l / view.dim] && !fixed[l]) ++free_dofs;
  MPI_Allreduce(MPI_IN_PLACE, &free_dofs, 1, MPI_INT64_T, MPI_SUM, dofs.comm());
}

MatrixAssembler& Constraints::assembler() const {
  if (!assembler_) assembler_.emplace(view, dofs, fixed);
  return *assembler_;
}

Targets::Targets(const MeshView& view, std::span<const double> volumes,
                 std::span<const double> shapes, std::span<const double> w) {
  set_volumes(view, volumes, *this);
  const int d = view.cell_dim();
  const std::size_t n = static_cast<std::size_t>(d * d);
  const std::size_t cells = static_cast<std::size_t>(view.num_cells);
  if (!shapes.empty() && shapes.size() != n * cells)
    fail("Functional: {} target shape entries for {} cells of dimension {}", shapes.size(), cells,
         d);
  if (!w.empty() && (shapes.empty() || w.size() != cells))
    fail("Functional: {} target weights for {} cells", w.size(), cells);
  weights.assign(w.begin(), w.end());
  if (weights.empty() && !shapes.empty()) weights.assign(cells, 1.0);
  shapes_inv_t.resize(shapes.size());
  if (d == 2)
    invert_target_shapes<2>(shapes, weights, shapes_inv_t);
  else
    invert_target_shapes<3>(shapes, weights, shapes_inv_t);
}

Targets::Targets(const MeshView& view, std::span<const double> volumes, const Targets& shaped)
    : shapes_inv_t(shaped.shapes_inv_t), weights(shaped.weights) {
  if (shaped.volumes.size() != volumes.size())
    fail("Functional: the targets of {} cells for {} cells", shaped.volumes.size(), volumes.size());
  set_volumes(view, volumes, *this);
}

Problem::Problem(const MeshView& view, const DofMap& dofs, const std::vector<std::uint8_t>& fixed)
    : constraints(std::make_shared<const Constraints>(view, dofs, fixed)) {}

Problem::Problem(const MeshView& view, const DofMap& dofs, FixedDofs fixed, SlidingVertices sliding)
    : constraints(
          std::make_shared<const Constraints>(view, dofs, std::move(fixed), std::move(sliding))) {}

Problem Problem::with_untangling(double epsilon) const {
  Problem p = *this;
  p.untangling_epsilon = epsilon;
  return p;
}

Problem Problem::with_corner_weight(double weight) const {
  Problem p = *this;
  p.corner_weight = weight;
  return p;
}

Problem Problem::with_targets(std::span<const double> volumes, std::span<const double> shapes,
                              std::span<const double> weights) const {
  if (!constraints) fail("internal error: targets for a problem without a mesh");
  Problem p = *this;
  p.targets = std::make_shared<const Targets>(constraints->view, volumes, shapes, weights);
  return p;
}

Problem Problem::with_desired_volumes(std::span<const double> volumes) const {
  if (!constraints) fail("internal error: targets for a problem without a mesh");
  Problem p = *this;
  p.targets = targets ? std::make_shared<const Targets>(constraints->view, volumes, *targets)
                      : std::make_shared<const Targets>(constraints->view, volumes);
  return p;
}

Problem Problem::with_constraints(std::shared_ptr<const Constraints> c) const {
  Problem p = *this;
  p.constraints = std::move(c);
  return p;
}

const std::vector<double>& Problem::desired_volumes() const {
  static const std::vector<double> none;
  return targets ? targets->volumes : none;
}

}  // namespace neomesh
