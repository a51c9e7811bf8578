#include "energy/functional.hpp"

#include <omp.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <tuple>
#include <type_traits>

#include "energy/assembly_pattern.hpp"
#include "energy/cell_kernels.hpp"

namespace neomesh {

namespace {

// Calls body(CellTag<type>{}) with the cell type as a compile-time constant: the dispatch
// happens once per block, the loop over the block's cells is compiled per type.
template <typename Body>
void dispatch(CellType type, Body&& body) {
  switch (type) {
    case CellType::Triangle:
      return body(CellTag<CellType::Triangle>{});
    case CellType::Quadrilateral:
      return body(CellTag<CellType::Quadrilateral>{});
    case CellType::Tetrahedron:
      return body(CellTag<CellType::Tetrahedron>{});
    case CellType::Hexahedron:
      return body(CellTag<CellType::Hexahedron>{});
  }
}

// The coordinates of cell c of `block` from the local coordinate array.
template <CellType Type>
typename CellKernel<Type>::Coordinates cell_coordinates(const CellBlock& block, PetscInt c,
                                                        const double* local_x) {
  constexpr int dim = CellKernel<Type>::dim;
  typename CellKernel<Type>::Coordinates x;
  const PetscInt* vertex = block.cell(c);
  for (int i = 0; i < CellKernel<Type>::vertices; ++i)
    x.col(i) = Eigen::Map<const Vector<dim>>(local_x + dim * vertex[i]);
  return x;
}

using Kernels = std::tuple<CellKernel<CellType::Triangle>, CellKernel<CellType::Quadrilateral>,
                           CellKernel<CellType::Tetrahedron>, CellKernel<CellType::Hexahedron>>;

Kernels make_kernels(const EnergyOptions& options) {
  const double kappa = options.kappa < 0.0 ? options.lambda : options.kappa;
  const NeoHooke<2> law2{options.lambda, options.mu, kappa};
  const NeoHooke<3> law3{options.lambda, options.mu, kappa};
  const int n = options.gauss_points;
  return Kernels{
      CellKernel<CellType::Triangle>(law2, n), CellKernel<CellType::Quadrilateral>(law2, n),
      CellKernel<CellType::Tetrahedron>(law3, n), CellKernel<CellType::Hexahedron>(law3, n)};
}

double sum_over_ranks(double local, MPI_Comm comm) {
  double global = 0.0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, comm);
  return global;
}

}  // namespace

struct Functional::Impl {
  const MeshView& view;
  const DofMap& dofs;
  Kernels kernels;
  std::vector<std::uint8_t> fixed;  // per local dof
  std::vector<double> volumes;      // desired volume per local cell
  OwnedVec free_mask;

  // The COO layout of H(α) and L: per block, its cells' (dofs × dofs) blocks, column-major,
  // one after the other from coo_offset[block]; then a 1 on the diagonal of each owned fixed dof.
  std::vector<std::size_t> coo_offset;
  std::size_t num_cell_entries = 0;
  std::vector<PetscInt> owned_fixed_dofs;

  // On one rank: the AIJ pattern, built by the first create_*matrix and shared by every matrix
  // of its kind (MatDuplicate with MAT_SHARE_NONZERO_PATTERN), and assembly straight into its
  // values. Laplacian matrices leave out the couplings between components (all zero).
  mutable std::optional<AssemblyPattern> pattern;
  mutable bool pattern_built = false;
  mutable OwnedMat pattern_matrix[2];  // [coupled]

  // Work arrays reused between calls.
  mutable std::vector<double> local_x;
  mutable std::vector<double> thread_gradients;  // one local gradient per OpenMP thread
  mutable std::vector<double> local_gradient;
  mutable std::vector<PetscScalar> coo_values;

  Impl(const MeshView& v, const DofMap& d, const EnergyOptions& o, std::vector<std::uint8_t> f)
      : view(v), dofs(d), kernels(make_kernels(o)), fixed(std::move(f)) {}

  template <CellType Type>
  const CellKernel<Type>& kernel() const {
    return std::get<CellKernel<Type>>(kernels);
  }

  bool is_fixed_dof(PetscInt local_dof) const { return fixed[local_dof] != 0; }

  void require_volumes() const {
    if (static_cast<PetscInt>(volumes.size()) != view.num_cells)
      fail("Functional: desired volumes are not set ({} given for {} cells)", volumes.size(),
           view.num_cells);
  }

  void load_coordinates(Vec x) const {
    require_volumes();
    dofs.global_to_local(x, local_x);
  }

  double local_energy() const;
  double local_energy_and_gradient(std::vector<double>& gradient) const;
  std::vector<PetscInt> coo_indices(bool rows, bool coupled) const;
  OwnedMat create_matrix(bool coupled) const;
  // Fills coo_values with cell blocks computed by fill(kernel, x, volume, block) -> bool;
  // fails naming the first cell for which fill returned false.
  template <typename Fill>
  void fill_coo_values(Fill&& fill, const char* what) const;
  // Assembles the cell blocks computed by fill into M (values only), through the pattern
  // when there is one, else through COO.
  template <typename Fill>
  void assemble(Fill&& fill, const char* what, Mat M) const;
  [[noreturn]] void fail_inverted(const char* what, PetscInt cell) const {
    fail("{}: local cell {} (input cell {}) is inverted or degenerate (det G <= 0)", what, cell,
         view.global_cell.empty() ? cell : view.global_cell[cell]);
  }
};

double Functional::Impl::local_energy() const {
  double sum = 0.0;
  for (const CellBlock& block : view.blocks) {
    dispatch(block.type, [&]<CellType Type>(CellTag<Type>) {
      const CellKernel<Type>& k = kernel<Type>();
      const double* desired = volumes.data() + block.first_cell;
      double block_sum = 0.0;
#pragma omp parallel for reduction(+ : block_sum) schedule(static)
      for (PetscInt c = 0; c < block.size(); ++c)
        block_sum += k.energy(cell_coordinates<Type>(block, c, local_x.data()), desired[c]);
      sum += block_sum;
    });
  }
  return sum;
}

// Each thread adds its cells' gradients into its own local array; the arrays are summed
// in thread order afterwards (deterministic for a fixed number of threads).
double Functional::Impl::local_energy_and_gradient(std::vector<double>& gradient) const {
  const std::size_t n = local_x.size();
  const int threads = omp_get_max_threads();
  thread_gradients.assign(n * threads, 0.0);
  double sum = 0.0;
  for (const CellBlock& block : view.blocks) {
    dispatch(block.type, [&]<CellType Type>(CellTag<Type>) {
      constexpr int dim = CellKernel<Type>::dim;
      const CellKernel<Type>& k = kernel<Type>();
      const double* desired = volumes.data() + block.first_cell;
      double block_sum = 0.0;
#pragma omp parallel reduction(+ : block_sum)
      {
        double* mine = thread_gradients.data() + n * omp_get_thread_num();
        typename CellKernel<Type>::Gradient g;
#pragma omp for schedule(static)
        for (PetscInt c = 0; c < block.size(); ++c) {
          block_sum += k.energy_and_gradient(cell_coordinates<Type>(block, c, local_x.data()),
                                             desired[c], g);
          const PetscInt* vertex = block.cell(c);
          for (int i = 0; i < CellKernel<Type>::vertices; ++i)
            Eigen::Map<Vector<dim>>(mine + dim * vertex[i]) += g.col(i);
        }
      }
      sum += block_sum;
    });
  }
  gradient.assign(n, 0.0);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (is_fixed_dof(static_cast<PetscInt>(i))) continue;  // gradient is zero at fixed dofs
    double s = 0.0;
    for (int t = 0; t < threads; ++t) s += thread_gradients[n * t + i];
    gradient[i] = s;
  }
  return sum;
}

// Global row (rows = true) or column indices of the COO entries; −1 (ignored by PETSc)
// where the row or column is a fixed dof, or, unless `coupled`, they are different components.
std::vector<PetscInt> Functional::Impl::coo_indices(bool rows, bool coupled) const {
  const std::vector<PetscInt>& global = dofs.global_dof();
  std::vector<PetscInt> index(num_cell_entries + owned_fixed_dofs.size());
  for (std::size_t b = 0; b < view.blocks.size(); ++b) {
    const CellBlock& block = view.blocks[b];
    const int nv = num_vertices(block.type);
    const int n = dofs.dim() * nv;
    PetscInt* out = index.data() + coo_offset[b];
    for (PetscInt c = 0; c < block.size(); ++c) {
      const PetscInt* vertex = block.cell(c);
      for (int col = 0; col < n; ++col) {
        for (int row = 0; row < n; ++row) {
          const int mine = rows ? row : col;
          const int other = rows ? col : row;
          const PetscInt dof = dofs.dim() * vertex[mine / dofs.dim()] + mine % dofs.dim();
          const PetscInt other_dof = dofs.dim() * vertex[other / dofs.dim()] + other % dofs.dim();
          const bool dropped = is_fixed_dof(dof) || is_fixed_dof(other_dof) ||
                               (!coupled && row % dofs.dim() != col % dofs.dim());
          *out++ = dropped ? -1 : global[dof];
        }
      }
    }
  }
  std::copy(owned_fixed_dofs.begin(), owned_fixed_dofs.end(),
            index.begin() + static_cast<std::ptrdiff_t>(num_cell_entries));
  return index;
}

template <typename Fill>
void Functional::Impl::fill_coo_values(Fill&& fill, const char* what) const {
  coo_values.resize(num_cell_entries + owned_fixed_dofs.size());
  std::fill(coo_values.begin() + static_cast<std::ptrdiff_t>(num_cell_entries), coo_values.end(),
            1.0);
  PetscInt first_bad = std::numeric_limits<PetscInt>::max();
  for (std::size_t b = 0; b < view.blocks.size(); ++b) {
    const CellBlock& block = view.blocks[b];
    dispatch(block.type, [&]<CellType Type>(CellTag<Type>) {
      using Block = typename CellKernel<Type>::Block;
      const CellKernel<Type>& k = kernel<Type>();
      const double* desired = volumes.data() + block.first_cell;
      PetscScalar* values = coo_values.data() + coo_offset[b];
#pragma omp parallel for schedule(static) reduction(min : first_bad)
      for (PetscInt c = 0; c < block.size(); ++c) {
        Eigen::Map<Block> cell_block(values + c * Block::SizeAtCompileTime);
        if (!fill(k, cell_coordinates<Type>(block, c, local_x.data()), desired[c], cell_block))
          first_bad = std::min(first_bad, block.first_cell + c);
      }
    });
  }
  if (first_bad != std::numeric_limits<PetscInt>::max()) fail_inverted(what, first_bad);
}

template <typename Fill>
void Functional::Impl::assemble(Fill&& fill, const char* what, Mat M) const {
  if (!pattern) {
    fill_coo_values(fill, what);
    NM_PETSC(MatSetValuesCOO(M, coo_values.data(), INSERT_VALUES));
    return;
  }
  // The pattern of M: all couplings (create_matrix) or only within components (Laplacian,
  // 1/d of the entries, at entry / d of the coupled ones).
  const int d = dofs.dim();
  MatInfo info;
  NM_PETSC(MatGetInfo(M, MAT_LOCAL, &info));
  const bool coupled = static_cast<std::size_t>(info.nz_allocated) == pattern->num_entries();
  const int shrink = coupled ? 1 : d;
  PetscScalar* values = nullptr;
  NM_PETSC(MatSeqAIJGetArrayWrite(M, &values));
  const std::size_t entries = pattern->num_entries() / shrink;
#pragma omp parallel for schedule(static)
  for (std::size_t e = 0; e < entries; ++e) values[e] = 0.0;
  PetscInt first_bad = std::numeric_limits<PetscInt>::max();
  for (std::size_t b = 0; b < view.blocks.size(); ++b) {
    const CellBlock& block = view.blocks[b];
    dispatch(block.type, [&]<CellType Type>(CellTag<Type>) {
      using Block = typename CellKernel<Type>::Block;
      constexpr int n = CellKernel<Type>::vertices;
      const CellKernel<Type>& k = kernel<Type>();
      const double* desired = volumes.data() + block.first_cell;
      const std::vector<PetscInt>& order = pattern->colour_order[b];
      const std::vector<PetscInt>& start = pattern->colour_start[b];
      for (std::size_t colour = 0; colour + 1 < start.size(); ++colour) {
        // Cells of one colour share no vertex: their blocks go to disjoint entries.
#pragma omp parallel for schedule(static) reduction(min : first_bad)
        for (PetscInt i = start[colour]; i < start[colour + 1]; ++i) {
          const PetscInt c = order[i];
          Block cell_block;
          if (!fill(k, cell_coordinates<Type>(block, c, local_x.data()), desired[c],
                    Eigen::Map<Block>(cell_block.data()))) {
            first_bad = std::min(first_bad, block.first_cell + c);
            continue;
          }
          const PetscInt* vertex = block.cell(c);
          const PetscInt* entry = pattern->block_entry[b].data() + c * n * n;
          for (int vi = 0; vi < n; ++vi) {
            const PetscInt stride = pattern->row_stride[vertex[vi]] / shrink;
            for (int vj = 0; vj < n; ++vj) {
              PetscScalar* out = values + entry[vi * n + vj] / shrink;
              for (int a = 0; a < d; ++a) {
                if (is_fixed_dof(d * vertex[vi] + a)) continue;
                if (!coupled) {
                  if (!is_fixed_dof(d * vertex[vj] + a))
                    out[a * stride] += cell_block(d * vi + a, d * vj + a);
                  continue;
                }
                for (int bb = 0; bb < d; ++bb)
                  if (!is_fixed_dof(d * vertex[vj] + bb))
                    out[a * stride + bb] += cell_block(d * vi + a, d * vj + bb);
              }
            }
          }
        }
      }
    });
  }
  for (PetscInt l = 0; l < dofs.num_local_dofs(); ++l)
    if (is_fixed_dof(l))
      values[coupled ? pattern->diagonal[l] : (pattern->diagonal[l] - l % d) / d] = 1.0;
  NM_PETSC(MatSeqAIJRestoreArrayWrite(M, &values));
  if (first_bad != std::numeric_limits<PetscInt>::max()) fail_inverted(what, first_bad);
}

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

}  // namespace

Functional::Functional(const MeshView& view, const DofMap& dofs, const EnergyOptions& options,
                       const std::vector<std::uint8_t>& fixed)
    : Functional(view, dofs, options, per_dof(view, fixed)) {}

Functional::Functional(const MeshView& view, const DofMap& dofs, const EnergyOptions& options,
                       FixedDofs fixed)
    : impl_(std::make_unique<Impl>(view, dofs, options, std::move(fixed.flags))) {
  if (dofs.dim() != view.dim)
    fail("Functional: the mesh is {}D but its DofMap has {} components", view.dim, dofs.dim());
  if (static_cast<PetscInt>(impl_->fixed.size()) != view.num_vertices * view.dim)
    fail("Functional: {} fixed flags for {} local dofs", impl_->fixed.size(),
         view.num_vertices * view.dim);
  if (dofs.num_local_dofs() != view.num_vertices * view.dim)
    fail("Functional: DofMap has {} local dofs, the mesh {} vertices of dimension {}",
         dofs.num_local_dofs(), view.num_vertices, view.dim);
  if (!(options.lambda > 0.0 && options.mu > 0.0))
    fail("energy parameters must be positive (lambda = {}, mu = {})", options.lambda, options.mu);

  std::size_t offset = 0;
  for (const CellBlock& block : view.blocks) {
    if (dimension(block.type) != view.dim)
      fail("Functional: {} cells in a {}D mesh", name(block.type), view.dim);
    impl_->coo_offset.push_back(offset);
    const std::size_t n = static_cast<std::size_t>(view.dim * num_vertices(block.type));
    offset += n * n * static_cast<std::size_t>(block.size());
  }
  impl_->num_cell_entries = offset;
  impl_->local_x.resize(static_cast<std::size_t>(dofs.num_local_dofs()));

  // free_mask and the owned fixed dofs: every local dof of an owned vertex is owned.
  impl_->free_mask = dofs.create_global_vector();
  PetscInt first = 0;
  NM_PETSC(VecGetOwnershipRange(impl_->free_mask, &first, nullptr));
  VecWriteView mask(impl_->free_mask);
  for (PetscInt l = 0; l < dofs.num_local_dofs(); ++l) {
    if (!view.owned[l / view.dim]) continue;
    const PetscInt g = dofs.global_dof()[l];
    const bool is_fixed = impl_->is_fixed_dof(l);
    mask[g - first] = is_fixed ? 0.0 : 1.0;
    if (is_fixed) impl_->owned_fixed_dofs.push_back(g);
  }
}

Functional::~Functional() = default;

void Functional::set_desired_volumes(std::span<const double> volumes) {
  if (static_cast<PetscInt>(volumes.size()) != impl_->view.num_cells)
    fail("Functional: {} desired volumes for {} cells", volumes.size(), impl_->view.num_cells);
  for (std::size_t c = 0; c < volumes.size(); ++c)
    if (!(volumes[c] > 0.0) || !std::isfinite(volumes[c]))
      fail("desired volume of local cell {} is {} (must be positive and finite)", c, volumes[c]);
  impl_->volumes.assign(volumes.begin(), volumes.end());
}

const std::vector<double>& Functional::desired_volumes() const {
  return impl_->volumes;
}

double Functional::value(Vec x) const {
  impl_->load_coordinates(x);
  return sum_over_ranks(impl_->local_energy(), impl_->dofs.comm());
}

double Functional::value_and_gradient(Vec x, Vec gradient) const {
  impl_->load_coordinates(x);
  const double local = impl_->local_energy_and_gradient(impl_->local_gradient);
  NM_PETSC(VecZeroEntries(gradient));
  impl_->dofs.add_local_to_global(impl_->local_gradient, gradient);
  return sum_over_ranks(local, impl_->dofs.comm());
}

OwnedMat Functional::Impl::create_matrix(bool coupled) const {
  if (!pattern_built) {
    pattern = make_assembly_pattern(view, dofs);
    pattern_built = true;
  }
  OwnedMat m;
  if (pattern_matrix[coupled]) {
    NM_PETSC(MatDuplicate(pattern_matrix[coupled], MAT_SHARE_NONZERO_PATTERN, m.out()));
  } else {
    NM_PETSC(MatCreate(dofs.comm(), m.out()));
    NM_PETSC(MatSetSizes(m, dofs.num_owned_dofs(), dofs.num_owned_dofs(), dofs.num_global_dofs(),
                         dofs.num_global_dofs()));
    NM_PETSC(MatSetType(m, MATAIJ));
    NM_PETSC(MatSetBlockSize(m, dofs.dim()));
    if (pattern) {
      if (coupled) {
        NM_PETSC(MatSeqAIJSetPreallocationCSR(m, pattern->row_start.data(), pattern->column.data(),
                                              nullptr));
      } else {
        const auto [row_start, column] = uncoupled_csr(*pattern, dofs.dim());
        NM_PETSC(MatSeqAIJSetPreallocationCSR(m, row_start.data(), column.data(), nullptr));
      }
      NM_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(m.get())));
      pattern_matrix[coupled] = OwnedMat(m.get());
      // Every later matrix is a duplicate: the matrices hold the columns from now on.
      if (pattern_matrix[0] && pattern_matrix[1]) std::vector<PetscInt>().swap(pattern->column);
    } else {
      std::vector<PetscInt> rows = coo_indices(true, coupled);
      std::vector<PetscInt> cols = coo_indices(false, coupled);
      NM_PETSC(MatSetPreallocationCOO(m, static_cast<PetscCount>(rows.size()), rows.data(),
                                      cols.data()));
    }
  }
  // H(α) and L are symmetric by construction (cell_kernels.hpp), exactly in floating point.
  NM_PETSC(MatSetOption(m, MAT_SYMMETRIC, PETSC_TRUE));
  NM_PETSC(MatSetOption(m, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  return m;
}

OwnedMat Functional::create_matrix() const {
  return impl_->create_matrix(true);
}

OwnedMat Functional::create_laplacian_matrix() const {
  return impl_->create_matrix(false);
}

void Functional::assemble_hessian(Vec x, double alpha, Mat H) const {
  impl_->load_coordinates(x);
  impl_->assemble([alpha](const auto& kernel, const auto& coordinates, double volume,
                          auto block) { return kernel.hessian(coordinates, volume, alpha, block); },
                  "H(alpha)", H);
}

void Functional::assemble_laplacian(RieszLaplacian kind, Vec x, Mat L) const {
  if (kind == RieszLaplacian::CurrentMesh) {
    impl_->load_coordinates(x);
    impl_->assemble([](const auto& kernel, const auto& coordinates, double volume,
                       auto block) { return kernel.current_laplacian(coordinates, volume, block); },
                    "current-mesh Laplacian", L);
  } else {
    impl_->require_volumes();
    impl_->assemble(
        [](const auto& kernel, const auto&, double volume, auto block) {
          kernel.optimal_laplacian(volume, block);
          return true;
        },
        "optimal-cell Laplacian", L);
  }
}

CellFields Functional::cell_fields(Vec x) const {
  impl_->load_coordinates(x);
  const MeshView& view = impl_->view;
  CellFields fields;
  fields.energy.resize(view.num_cells);
  fields.min_det.resize(view.num_cells);
  fields.volume_ratio.resize(view.num_cells);
  for (const CellBlock& block : view.blocks) {
    dispatch(block.type, [&]<CellType Type>(CellTag<Type>) {
      const CellKernel<Type>& k = impl_->kernel<Type>();
#pragma omp parallel for schedule(static)
      for (PetscInt c = 0; c < block.size(); ++c) {
        const PetscInt cell = block.first_cell + c;
        const double desired = impl_->volumes[cell];
        const auto x = cell_coordinates<Type>(block, c, impl_->local_x.data());
        const CellMeasure measure = k.measure(x, desired);
        fields.energy[cell] = k.energy(x, desired);
        fields.min_det[cell] = measure.min_det;
        fields.volume_ratio[cell] = measure.volume / desired;  // Q (thesis §6.2)
      }
    });
  }
  return fields;
}

const DofMap& Functional::dofs() const {
  return impl_->dofs;
}

Vec Functional::free_mask() const {
  return impl_->free_mask;
}

double mesh_volume(const MeshView& view, const DofMap& dofs, Vec x) {
  // Two Gauss points per direction integrate det ∇τ of Q1 cells exactly; the law is unused.
  const Kernels kernels = make_kernels(EnergyOptions{.gauss_points = 2});
  std::vector<double> local_x(static_cast<std::size_t>(dofs.num_local_dofs()));
  dofs.global_to_local(x, local_x);
  double sum = 0.0;
  for (const CellBlock& block : view.blocks) {
    dispatch(block.type, [&]<CellType Type>(CellTag<Type>) {
      const CellKernel<Type>& k = std::get<CellKernel<Type>>(kernels);
      for (PetscInt c = 0; c < block.size(); ++c)
        sum += k.measure(cell_coordinates<Type>(block, c, local_x.data()), 1.0).volume;
    });
  }
  return sum_over_ranks(sum, dofs.comm());
}

}  // namespace neomesh
