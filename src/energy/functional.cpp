#include "energy/functional.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <type_traits>

#include "core/collective_error.hpp"
#include "energy/cell_kernels.hpp"
#include "energy/curved_kernels.hpp"
#include "energy/matrix_assembler.hpp"
#include "energy/surface_kernels.hpp"

namespace neomesh {

namespace {

// The coordinates of cell c of `block` from the local coordinate array, as kernel K takes them
// (K::dim per vertex).
template <typename K>
typename K::Coordinates cell_coordinates(const CellBlock& block, PetscInt c,
                                         const double* local_x) {
  constexpr int dim = K::dim;
  typename K::Coordinates x;
  const PetscInt* vertex = block.cell(c);
  for (int i = 0; i < K::vertices; ++i)
    x.col(i) = Eigen::Map<const Vector<dim>>(local_x + dim * vertex[i]);
  return x;
}

// The corners of cell c of `block` as the straight kernel of its type takes them: a curved
// cell's corners in canonical order (curved_cell.hpp: linear_corners).
template <typename Cells>
typename Cells::StraightCoordinates corner_coordinates(const CellBlock& block, PetscInt c,
                                                       const double* local_x) {
  const auto x = cell_coordinates<typename Cells::Energy>(block, c, local_x);
  if constexpr (Cells::curved) {
    typename Cells::StraightCoordinates corners;
    const auto order = linear_corners<Cells::curved_type>();
    for (std::size_t i = 0; i < order.size(); ++i) corners.col(i) = x.col(order[i]);
    return corners;
  } else {
    return x;
  }
}

// The target of a surface cell: its 2D target and its frame Q (surface_frames).
struct FramedTarget {
  CellTarget<2> target;
  const double* frame;  // 3 × 2, column-major

  SurfaceFrame q() const { return Eigen::Map<const SurfaceFrame>(frame); }
};

// A surface kernel (surface_kernels.hpp) called as a cell kernel is, its frame in the target:
// the loops over cells below serve volume and surface cells alike.
template <typename Surface>
class FramedKernel {
 public:
  static constexpr int dim = Surface::dim;
  static constexpr int vertices = Surface::vertices;
  using Coordinates = typename Surface::Coordinates;
  using Gradient = typename Surface::Gradient;
  using Block = typename Surface::Block;

  explicit FramedKernel(Surface kernel) : k_(std::move(kernel)) {}

  double energy(const Coordinates& x, const FramedTarget& t) const {
    return k_.energy(x, t.q(), t.target);
  }
  double energy_and_gradient(const Coordinates& x, const FramedTarget& t, Gradient& g) const {
    return k_.energy_and_gradient(x, t.q(), t.target, g);
  }
  bool hessian(const Coordinates& x, const FramedTarget& t, double alpha,
               Eigen::Ref<Block> block) const {
    return k_.hessian(x, t.q(), t.target, alpha, block);
  }
  void optimal_laplacian(const FramedTarget& t, Eigen::Ref<Block> block) const {
    k_.optimal_laplacian(t.q(), t.target, block);
  }
  bool current_laplacian(const Coordinates& x, const FramedTarget& t,
                         Eigen::Ref<Block> block) const {
    return k_.current_laplacian(x, t.q(), t.target, block);
  }
  CellMeasure measure(const Coordinates& x, const FramedTarget& t) const {
    return k_.measure(x, t.q(), t.target);
  }
  std::pair<double, CellMeasure> energy_and_measure(const Coordinates& x,
                                                    const FramedTarget& t) const {
    return k_.energy_and_measure(x, t.q(), t.target);
  }

 private:
  Surface k_;
};

template <CellType Type>
using FramedNeoHooke = FramedKernel<NeoHookeSurfaceKernel<Type>>;
template <CellType Type>
using FramedUntangling = FramedKernel<UntanglingSurfaceKernel<Type>>;

// The kernels of the cells of `Type`: in space, framed (surface cells), or as they are.
template <CellType Type, bool Framed>
using EnergyKernel = std::conditional_t<Framed, FramedNeoHooke<Type>, NeoHookeKernel<Type>>;
template <CellType Type, bool Framed>
using UntanglingEnergyKernel =
    std::conditional_t<Framed, FramedUntangling<Type>, UntanglingKernel<Type>>;

using SurfaceKernels =
    std::tuple<FramedNeoHooke<CellType::Triangle>, FramedNeoHooke<CellType::Quadrilateral>,
               FramedUntangling<CellType::Triangle>, FramedUntangling<CellType::Quadrilateral>>;

SurfaceKernels make_surface_kernels(const EnergyOptions& options, double corner_weight,
                                    double epsilon) {
  const NeoHooke<2> law{options.lambda, options.mu, options.effective_kappa()};
  const RegularizedNeoHooke<2> untangling{options.lambda, options.mu, epsilon};
  const int n = options.gauss_points;
  return SurfaceKernels{
      FramedNeoHooke<CellType::Triangle>(NeoHookeSurfaceKernel<CellType::Triangle>(law, n)),
      FramedNeoHooke<CellType::Quadrilateral>(
          NeoHookeSurfaceKernel<CellType::Quadrilateral>(law, n, corner_weight)),
      FramedUntangling<CellType::Triangle>(
          make_untangling_surface_kernel<CellType::Triangle>(untangling, n)),
      FramedUntangling<CellType::Quadrilateral>(
          make_untangling_surface_kernel<CellType::Quadrilateral>(untangling, n))};
}

// What the loops over cells need to know of a block's cells: the kernels of both laws, the
// dimension of their targets, and whether they are framed (surface cells) or curved.
template <CellType Type, bool Framed>
struct StraightCells {
  using Energy = EnergyKernel<Type, Framed>;
  using Untangling = UntanglingEnergyKernel<Type, Framed>;
  static constexpr CellType type = Type;
  static constexpr bool framed = Framed;
  static constexpr bool curved = false;
  static constexpr int target_dim = CellTraits<Type>::dim;
  using StraightCoordinates = typename Energy::Coordinates;
};
template <CurvedType Type>
struct CurvedCells {
  using Energy = CurvedNeoHookeKernel<Type>;
  using Untangling = CurvedUntanglingKernel<Type>;
  static constexpr CellType type = CurvedTraits<Type>::linear;
  static constexpr CurvedType curved_type = Type;
  static constexpr bool framed = false;
  static constexpr bool curved = true;
  static constexpr int target_dim = CurvedTraits<Type>::dim;
  using StraightCoordinates = typename NeoHookeKernel<CurvedTraits<Type>::linear>::Coordinates;
};

// Calls f.template operator()<Cells>() for the cells of `block`: StraightCells, framed for the
// triangles and quadrilaterals of a surface mesh, or CurvedCells for second-order cells.
template <typename F>
void visit_cells(const MeshView& view, const CellBlock& block, F&& f) {
  if (block.curved) {
    visit_curved_type(*block.curved, [&]<CurvedType Type>(CurvedTag<Type>) {
      f.template operator()<CurvedCells<Type>>();
    });
    return;
  }
  visit_cell_type(block.type, [&]<CellType Type>(CellTag<Type>) {
    if constexpr (CellTraits<Type>::dim == 2) {
      if (view.surface) {
        f.template operator()<StraightCells<Type, true>>();
        return;
      }
    }
    f.template operator()<StraightCells<Type, false>>();
  });
}

using Kernels =
    std::tuple<NeoHookeKernel<CellType::Triangle>, NeoHookeKernel<CellType::Quadrilateral>,
               NeoHookeKernel<CellType::Tetrahedron>, NeoHookeKernel<CellType::Hexahedron>,
               NeoHookeKernel<CellType::Wedge>, NeoHookeKernel<CellType::Pyramid>>;

using UntanglingKernels =
    std::tuple<UntanglingKernel<CellType::Triangle>, UntanglingKernel<CellType::Quadrilateral>,
               UntanglingKernel<CellType::Tetrahedron>, UntanglingKernel<CellType::Hexahedron>,
               UntanglingKernel<CellType::Wedge>, UntanglingKernel<CellType::Pyramid>>;

UntanglingKernels make_untangling_kernels(const EnergyOptions& options, double epsilon) {
  const RegularizedNeoHooke<2> law2{options.lambda, options.mu, epsilon};
  const RegularizedNeoHooke<3> law3{options.lambda, options.mu, epsilon};
  const int n = options.gauss_points;
  return UntanglingKernels{make_untangling_kernel<CellType::Triangle>(law2, n),
                           make_untangling_kernel<CellType::Quadrilateral>(law2, n),
                           make_untangling_kernel<CellType::Tetrahedron>(law3, n),
                           make_untangling_kernel<CellType::Hexahedron>(law3, n),
                           make_untangling_kernel<CellType::Wedge>(law3, n),
                           make_untangling_kernel<CellType::Pyramid>(law3, n)};
}

Kernels make_kernels(const EnergyOptions& options, double corner_weight = 0.0) {
  const double kappa = options.effective_kappa();
  const NeoHooke<2> law2{options.lambda, options.mu, kappa};
  const NeoHooke<3> law3{options.lambda, options.mu, kappa};
  const int n = options.gauss_points;
  const double w = corner_weight;
  return Kernels{NeoHookeKernel<CellType::Triangle>(law2, n),
                 NeoHookeKernel<CellType::Quadrilateral>(law2, n, w),
                 NeoHookeKernel<CellType::Tetrahedron>(law3, n),
                 NeoHookeKernel<CellType::Hexahedron>(law3, n, w),
                 NeoHookeKernel<CellType::Wedge>(law3, n, w),
                 NeoHookeKernel<CellType::Pyramid>(law3, n, w)};
}

// The curved cells' kernels of both laws (curved_kernels.hpp: their own Gauss rule, with the
// corner samples of `corner_weight`, and the untangling law's at half the weight each).
using CurvedKernels = std::tuple<
    CurvedNeoHookeKernel<CurvedType::Triangle6>, CurvedNeoHookeKernel<CurvedType::Quadrilateral8>,
    CurvedNeoHookeKernel<CurvedType::Quadrilateral9>,
    CurvedNeoHookeKernel<CurvedType::Tetrahedron10>, CurvedNeoHookeKernel<CurvedType::Hexahedron20>,
    CurvedNeoHookeKernel<CurvedType::Hexahedron27>, CurvedNeoHookeKernel<CurvedType::Wedge15>,
    CurvedNeoHookeKernel<CurvedType::Wedge18>, CurvedUntanglingKernel<CurvedType::Triangle6>,
    CurvedUntanglingKernel<CurvedType::Quadrilateral8>,
    CurvedUntanglingKernel<CurvedType::Quadrilateral9>,
    CurvedUntanglingKernel<CurvedType::Tetrahedron10>,
    CurvedUntanglingKernel<CurvedType::Hexahedron20>,
    CurvedUntanglingKernel<CurvedType::Hexahedron27>, CurvedUntanglingKernel<CurvedType::Wedge15>,
    CurvedUntanglingKernel<CurvedType::Wedge18>>;

template <CurvedType Type>
CurvedNeoHookeKernel<Type> curved_kernel(const EnergyOptions& options, double corner_weight) {
  constexpr int d = CurvedTraits<Type>::dim;
  return CurvedNeoHookeKernel<Type>(
      NeoHooke<d>{options.lambda, options.mu, options.effective_kappa()}, kCurvedGaussPoints,
      corner_weight);
}
template <CurvedType Type>
CurvedUntanglingKernel<Type> curved_untangling_kernel(const EnergyOptions& options,
                                                      double epsilon) {
  constexpr int d = CurvedTraits<Type>::dim;
  return make_curved_untangling_kernel<Type>(
      RegularizedNeoHooke<d>{options.lambda, options.mu, epsilon});
}

CurvedKernels make_curved_kernels(const EnergyOptions& o, double corner_weight, double epsilon) {
  using enum CurvedType;
  const double w = corner_weight;
  return CurvedKernels{curved_kernel<Triangle6>(o, w),
                       curved_kernel<Quadrilateral8>(o, w),
                       curved_kernel<Quadrilateral9>(o, w),
                       curved_kernel<Tetrahedron10>(o, w),
                       curved_kernel<Hexahedron20>(o, w),
                       curved_kernel<Hexahedron27>(o, w),
                       curved_kernel<Wedge15>(o, w),
                       curved_kernel<Wedge18>(o, w),
                       curved_untangling_kernel<Triangle6>(o, epsilon),
                       curved_untangling_kernel<Quadrilateral8>(o, epsilon),
                       curved_untangling_kernel<Quadrilateral9>(o, epsilon),
                       curved_untangling_kernel<Tetrahedron10>(o, epsilon),
                       curved_untangling_kernel<Hexahedron20>(o, epsilon),
                       curved_untangling_kernel<Hexahedron27>(o, epsilon),
                       curved_untangling_kernel<Wedge15>(o, epsilon),
                       curved_untangling_kernel<Wedge18>(o, epsilon)};
}

// True if some block of `view` holds second-order cells.
bool has_curved_cells(const MeshView& view) {
  return std::any_of(view.blocks.begin(), view.blocks.end(),
                     [](const CellBlock& b) { return b.curved.has_value(); });
}

double sum_over_ranks(double local, MPI_Comm comm) {
  double global = 0.0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, comm);
  return global;
}

}  // namespace

struct Functional::Impl {
  const Problem problem;
  const Constraints& constraints;
  const MeshView& view;
  const DofMap& dofs;
  EnergyOptions options;
  Kernels kernels;
  // With problem.untangling_epsilon > 0, value, gradient and H(α) are those of the untangling
  // energy; its kernels also find inverted cells (their sample points are where det G must be
  // > 0), at any ε.
  UntanglingKernels untangling_kernels;
  SurfaceKernels surface_kernels;  // both laws, in the frames of a surface mesh's cells
  std::optional<CurvedKernels> curved_kernels;  // both laws, for a view with curved cells
  bool untangling = false;
  const std::vector<std::uint8_t>& fixed;  // per local dof
  const SlidingVertices& sliding;
  const std::vector<PetscInt>& projector_of;  // per local vertex: index in sliding, or -1
  const Targets* targets = nullptr;           // null until the problem has targets
  // A surface mesh's cell frames at the view's coordinates (where a call starts), or as
  // refresh_frames last took them.
  mutable std::vector<double> frames;

  // Work arrays reused between calls.
  mutable std::vector<double> local_x;
  mutable std::vector<double> thread_gradients;  // a local gradient per OpenMP thread after 0
  mutable std::vector<double> local_gradient;    // on several processes
  mutable std::vector<double> tangent_spaces;    // per sliding.vertices entry, at local_x
  mutable std::vector<double> bending_force;     // per sliding.vertices entry: g · w (owned)

  Impl(const EnergyOptions& o, Problem p, const Constraints& c)
      : problem(std::move(p)),
        constraints(c),
        view(c.view),
        dofs(c.dofs),
        options(o),
        kernels(make_kernels(o, problem.corner_weight)),
        untangling_kernels(make_untangling_kernels(
            o, problem.untangling_epsilon > 0.0 ? problem.untangling_epsilon : 1.0)),
        surface_kernels(make_surface_kernels(
            o, problem.corner_weight,
            problem.untangling_epsilon > 0.0 ? problem.untangling_epsilon : 1.0)),
        curved_kernels(
            has_curved_cells(view)
                ? std::optional(make_curved_kernels(
                      o, problem.corner_weight,
                      problem.untangling_epsilon > 0.0 ? problem.untangling_epsilon : 1.0))
                : std::nullopt),
        untangling(problem.untangling_epsilon > 0.0),
        fixed(c.fixed),
        sliding(c.sliding),
        projector_of(c.projector_of),
        targets(problem.targets.get()),
        frames(targets ? surface_frames(view, dofs, view.coords) : std::vector<double>{}) {}

  template <typename Cells>
  const typename Cells::Energy& kernel() const {
    if constexpr (Cells::framed)
      return std::get<typename Cells::Energy>(surface_kernels);
    else if constexpr (Cells::curved)
      return std::get<typename Cells::Energy>(*curved_kernels);
    else
      return std::get<typename Cells::Energy>(kernels);
  }
  template <typename Cells>
  const typename Cells::Untangling& untangling_kernel() const {
    if constexpr (Cells::framed)
      return std::get<typename Cells::Untangling>(surface_kernels);
    else if constexpr (Cells::curved)
      return std::get<typename Cells::Untangling>(*curved_kernels);
    else
      return std::get<typename Cells::Untangling>(untangling_kernels);
  }
  // Calls f with the kernel of the energy being minimized: Neo-Hookean, or untangling.
  template <typename Cells, typename F>
  decltype(auto) with_energy_kernel(F&& f) const {
    if (untangling) return f(untangling_kernel<Cells>());
    return f(kernel<Cells>());
  }

  // The target of local cell `cell` (cell_kernels.hpp).
  template <int Dim>
  CellTarget<Dim> target(PetscInt cell) const {
    const Targets& t = *targets;
    if (t.shapes_inv_t.empty()) return {t.volumes[cell], t.inverse_edges[cell], nullptr, 1.0};
    return {t.volumes[cell], t.inverse_edges[cell], t.shapes_inv_t.data() + Dim * Dim * cell,
            t.weights[cell]};
  }
  // The same as the kernel of cells of `Type` takes it: with its frame for a surface cell.
  template <typename Cells>
  auto target_of(PetscInt cell) const {
    if constexpr (Cells::framed)
      return FramedTarget{target<2>(cell), frames.data() + 6 * cell};
    else
      return target<Cells::target_dim>(cell);
  }

  bool is_fixed_dof(PetscInt local_dof) const { return fixed[local_dof] != 0; }

  void require_volumes() const {
    if (!targets) fail("Functional: desired volumes are not set ({} cells)", view.num_cells);
  }

  void load_coordinates(Vec x) const {
    require_volumes();
    dofs.global_to_local(x, local_x);
  }
  // The same, and the tangent spaces of sliding vertices at x, for derivatives (the energy
  // alone, evaluated at every line-search trial point, does not need them).
  void load_coordinates_and_tangents(Vec x) const {
    load_coordinates(x);
    if (!sliding.vertices.empty()) sliding.tangent_spaces(local_x, tangent_spaces);
  }

  // The projector of local vertex v (sliding_vertices.hpp), or null if v does not slide.
  const double* projector(PetscInt v) const {
    const PetscInt i = projector_of[v];
    return i < 0 ? nullptr : tangent_spaces.data() + i * tangent_space_size(view.dim);
  }
  // g_v ← P_v g_v for every owned sliding vertex of the global gradient; keeps g_v · w_v
  // (the force that bends along the boundary) for the curvature term of H(α).
  void project_gradient(Vec gradient) const;
  // B ← P B P over a cell's (dim · vertices)² block, P = diag(P_v) (identity for vertices that
  // do not slide).
  template <int D, int N, typename Block>
  void project_block(const PetscInt* vertex, Block& block) const;

  double local_energy() const;
  double local_energy_and_gradient(std::span<double> gradient) const;
  OwnedMat create_matrix(MatrixLayout layout) const;
  // Assembles the cell blocks computed by fill(CellTag<type>, x, target, block) -> bool into M
  // (values only); fails on every rank, naming the first cell for which fill returned false.
  // With sliding vertices, `curvature` times their curvature term is added (α for H(α)).
  template <typename Fill>
  void assemble(Fill&& fill, const char* what, Mat M, double curvature = 0.0) const;
  // Adds the blocks of the cells of block b; returns the first cell for which fill returned
  // false (or the largest PetscInt).
  template <typename Cells, typename Fill>
  PetscInt add_cell_blocks(Fill& fill, std::size_t b, MatrixAssembler::Values& values) const;
};

// Once one cell's energy is not finite, neither is the sum, and the other cells are skipped:
// most of the line search's rejected trials invert a cell (the first steps along −s try
// lengths of up to 64 cells), and each cost a whole evaluation. A finite sum visits every cell.
double Functional::Impl::local_energy() const {
  double sum = 0.0;
  std::atomic<bool> not_finite{false};
  for (const CellBlock& block : view.blocks) {
    if (not_finite.load(std::memory_order_relaxed)) break;
    visit_cells(view, block, [&]<typename Cells>() {
      with_energy_kernel<Cells>([&]<typename K>(const K& k) {
        double block_sum = 0.0;
#pragma omp parallel for reduction(+ : block_sum) schedule(static)
        for (PetscInt c = 0; c < block.size(); ++c) {
          if (not_finite.load(std::memory_order_relaxed)) continue;
          const double e = k.energy(cell_coordinates<K>(block, c, local_x.data()),
                                    target_of<Cells>(block.first_cell + c));
          if (!std::isfinite(e)) not_finite.store(true, std::memory_order_relaxed);
          block_sum += e;
        }
        sum += block_sum;
      });
    });
  }
  return sum;
}

// Each thread adds its cells' gradients into its own local array (thread 0 into `gradient`
// itself); the arrays are summed in thread order afterwards (deterministic for a fixed number
// of threads).
double Functional::Impl::local_energy_and_gradient(std::span<double> gradient) const {
  const std::size_t n = local_x.size();
  const int threads = omp_get_max_threads();
  std::fill(gradient.begin(), gradient.end(), 0.0);
  thread_gradients.assign(n * (threads - 1), 0.0);
  double sum = 0.0;
  for (const CellBlock& block : view.blocks) {
    visit_cells(view, block, [&]<typename Cells>() {
      with_energy_kernel<Cells>([&]<typename K>(const K& k) {
        constexpr int dim = K::dim;
        double block_sum = 0.0;
#pragma omp parallel reduction(+ : block_sum)
        {
          const int t = omp_get_thread_num();
          double* mine = t == 0 ? gradient.data() : thread_gradients.data() + n * (t - 1);
          typename K::Gradient g;
#pragma omp for schedule(static)
          for (PetscInt c = 0; c < block.size(); ++c) {
            block_sum += k.energy_and_gradient(cell_coordinates<K>(block, c, local_x.data()),
                                               target_of<Cells>(block.first_cell + c), g);
            const PetscInt* vertex = block.cell(c);
            for (int i = 0; i < K::vertices; ++i)
              Eigen::Map<Vector<dim>>(mine + dim * vertex[i]) += g.col(i);
          }
        }
        sum += block_sum;
      });
    });
  }
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (is_fixed_dof(static_cast<PetscInt>(i))) {
      gradient[i] = 0.0;  // the gradient is zero at fixed dofs
      continue;
    }
    for (int t = 1; t < threads; ++t) gradient[i] += thread_gradients[n * (t - 1) + i];
  }
  return sum;
}

void Functional::Impl::project_gradient(Vec gradient) const {
  if (sliding.vertices.empty()) return;
  const int d = view.dim;
  PetscInt first = 0;
  NM_PETSC(VecGetOwnershipRange(gradient, &first, nullptr));
  VecWriteView g(gradient);
  for (std::size_t i = 0; i < sliding.vertices.size(); ++i) {
    const PetscInt v = sliding.vertices[i];
    if (!view.owned[v]) continue;
    const double* space = projector(v);
    Eigen::Map<const Eigen::MatrixXd> p(space, d, d);
    Eigen::Map<const Eigen::VectorXd> w(space + d * d, d);
    Eigen::Map<Eigen::VectorXd> at(g.data() + dofs.global_dof()[d * v] - first, d);
    bending_force[i] = w.dot(at);
    at = p * Eigen::VectorXd(at);
  }
}

template <int D, int N, typename Block>
void Functional::Impl::project_block(const PetscInt* vertex, Block& block) const {
  for (int i = 0; i < N; ++i) {
    const double* p = projector(vertex[i]);
    if (!p) continue;
    // P is symmetric, so its row-major array is also its column-major one.
    const Eigen::Map<const Eigen::Matrix<double, D, D>> P(p);
    block.template middleRows<D>(D * i) = P * block.template middleRows<D>(D * i);
    block.template middleCols<D>(D * i) = block.template middleCols<D>(D * i) * P;
  }
}

template <typename Cells, typename Fill>
PetscInt Functional::Impl::add_cell_blocks(Fill& fill, std::size_t b,
                                           MatrixAssembler::Values& values) const {
  using K = typename Cells::Energy;
  using Block = typename K::Block;
  constexpr int n = K::vertices;
  constexpr int d = K::dim;
  const CellBlock& block = view.blocks[b];
  const MatrixAssembler& assembler = constraints.assembler();
  const std::vector<PetscInt>& chunks = assembler.colour_chunks(b);
  const std::vector<PetscInt>& start = assembler.colour_start(b);
  PetscInt first_bad = std::numeric_limits<PetscInt>::max();
  for (std::size_t colour = 0; colour + 1 < start.size(); ++colour) {
    // Chunks of one colour share no vertex: their blocks go to disjoint entries.
#pragma omp parallel for schedule(static) reduction(min : first_bad)
    for (PetscInt k = start[colour]; k < start[colour + 1]; ++k) {
      const PetscInt end = std::min(block.size(), (chunks[k] + 1) * MatrixAssembler::kChunk);
      for (PetscInt c = chunks[k] * MatrixAssembler::kChunk; c < end; ++c) {
        Block cell_block;
        if (!fill.template operator()<Cells>(cell_coordinates<K>(block, c, local_x.data()),
                                             target_of<Cells>(block.first_cell + c),
                                             Eigen::Map<Block>(cell_block.data()))) {
          first_bad = std::min(first_bad, block.first_cell + c);
          continue;
        }
        if (!sliding.vertices.empty()) project_block<d, n>(block.cell(c), cell_block);
        values.add_cell<d, n>(b, c, cell_block.data());
      }
    }
  }
  return first_bad;
}

template <typename Fill>
void Functional::Impl::assemble(Fill&& fill, const char* what, Mat M, double curvature) const {
  const int d = dofs.dim();
  PetscInt first_bad = std::numeric_limits<PetscInt>::max();
  MatrixAssembler::Values values(constraints.assembler(), M);
  for (std::size_t b = 0; b < view.blocks.size(); ++b) {
    visit_cells(view, view.blocks[b], [&]<typename Cells>() {
      first_bad = std::min(first_bad, add_cell_blocks<Cells>(fill, b, values));
    });
  }
  values.gather();
  // The normal part of a sliding vertex's rows: + (I − P_v) on its diagonal block; and the
  // curvature term (g_v · w_v) M_v of the last gradient (sliding_vertices.hpp).
  for (std::size_t i = 0; i < sliding.vertices.size(); ++i) {
    const PetscInt v = sliding.vertices[i];
    if (!view.owned[v]) continue;
    const double* proj = projector(v);
    const double* bend = proj + d * d + d;
    const double force = curvature * bending_force[i];
    double diagonal_block[9];
    for (int a = 0; a < d; ++a)
      for (int bb = 0; bb < d; ++bb)
        diagonal_block[a * d + bb] =
            (a == bb ? 1.0 : 0.0) - proj[a * d + bb] + force * bend[a * d + bb];
    values.add_to_diagonal_block(v, diagonal_block);
  }
  values.finish();
  std::string error;
  if (first_bad != std::numeric_limits<PetscInt>::max())
    error = fmt::format("{}: input cell {} is inverted or degenerate (det G <= 0)", what,
                        view.global_cell.empty() ? first_bad : view.global_cell[first_bad]);
  throw_if_any(dofs.comm(), error);
}

namespace {

const Constraints& constraints_of(const Problem& problem) {
  if (!problem.constraints) fail("internal error: a Functional of a problem without constraints");
  return *problem.constraints;
}

}  // namespace

Functional::Functional(const EnergyOptions& options, Problem problem) {
  if (!(options.lambda > 0.0 && options.mu > 0.0))
    fail("energy parameters must be positive (lambda = {}, mu = {})", options.lambda, options.mu);
  const Constraints& constraints = constraints_of(problem);
  if (problem.targets &&
      static_cast<PetscInt>(problem.targets->volumes.size()) != constraints.view.num_cells)
    fail("Functional: the targets of {} cells for {} cells", problem.targets->volumes.size(),
         constraints.view.num_cells);
  impl_ = std::make_unique<Impl>(options, std::move(problem), constraints);
  impl_->local_x.resize(static_cast<std::size_t>(impl_->dofs.num_local_dofs()));
  impl_->tangent_spaces.resize(impl_->sliding.vertices.size() *
                               tangent_space_size(impl_->view.dim));
  impl_->bending_force.assign(impl_->sliding.vertices.size(), 0.0);
}

Functional::~Functional() = default;
Functional::Functional(Functional&&) noexcept = default;
Functional& Functional::operator=(Functional&&) noexcept = default;

const EnergyOptions& Functional::options() const {
  return impl_->options;
}

const Problem& Functional::problem() const {
  return impl_->problem;
}

std::vector<double> Functional::cell_jacobians(Vec x) const {
  const MeshView& view = impl_->view;
  const int d = view.cell_dim();
  impl_->dofs.global_to_local(x, impl_->local_x);
  std::vector<double> jacobians(static_cast<std::size_t>(d * d * view.num_cells));
  for (const CellBlock& block : view.blocks) {
    visit_cells(view, block, [&]<typename Cells>() {
      constexpr CellType Type = Cells::type;
      constexpr int dim = CellTraits<Type>::dim;
      // One Gauss point: the centre (for a pyramid the centre of its base).
      const OptimalCellQuadrature<Type> centre(1);
      for (PetscInt c = 0; c < block.size(); ++c) {
        const auto xc = corner_coordinates<Cells>(block, c, impl_->local_x.data());
        Eigen::Map<Matrix<dim>> jacobian(jacobians.data() + dim * dim * (block.first_cell + c));
        if constexpr (Cells::framed)  // of the cell's image in its frame at x
          jacobian = surface_cell_frame<Type>(xc).value_or(SurfaceFrame::Zero()).transpose() * xc *
                     centre.unit_gradients[0].transpose();
        else
          jacobian = xc * centre.unit_gradients[0].transpose();
      }
    });
  }
  return jacobians;
}

double Functional::value(Vec x) const {
  impl_->load_coordinates(x);
  return sum_over_ranks(impl_->local_energy(), impl_->dofs.comm());
}

double Functional::value_and_gradient(Vec x, Vec gradient) const {
  impl_->load_coordinates_and_tangents(x);
  double local = 0.0;
  if (impl_->dofs.local_is_global()) {  // one process: the local gradient is the global one
    VecWriteView g(gradient);
    local = impl_->local_energy_and_gradient({g.data(), static_cast<std::size_t>(g.size())});
  } else {
    impl_->local_gradient.resize(impl_->local_x.size());
    local = impl_->local_energy_and_gradient(impl_->local_gradient);
    NM_PETSC(VecZeroEntries(gradient));
    impl_->dofs.add_local_to_global(impl_->local_gradient, gradient);
  }
  impl_->project_gradient(gradient);  // once whole: the force on the boundary is kept
  return sum_over_ranks(local, impl_->dofs.comm());
}

OwnedMat Functional::Impl::create_matrix(MatrixLayout layout) const {
  return constraints.assembler().create(layout);
}

OwnedMat Functional::create_matrix(HessianUse use) const {
  return impl_->create_matrix(use == HessianUse::Products && mpi_size(impl_->dofs.comm()) == 1
                                  ? MatrixLayout::Symmetric
                                  : MatrixLayout::Coupled);
}

OwnedMat Functional::create_laplacian_matrix() const {
  // The projectors of sliding vertices couple the components.
  return impl_->create_matrix(impl_->constraints.slides_anywhere ? MatrixLayout::Coupled
                                                                 : MatrixLayout::Uncoupled);
}

bool Functional::laplacian_is_scalar() const {
  return impl_->constraints.scalar_laplacian;
}

OwnedMat Functional::create_scalar_laplacian_matrix() const {
  if (!impl_->constraints.scalar_laplacian)
    fail(
        "internal error: a scalar Riesz Laplacian where vertices slide or have only some "
        "coordinates fixed");
  const OwnedMat scalar = impl_->create_matrix(MatrixLayout::Scalar);
  OwnedMat L;
  NM_PETSC(MatCreateMAIJ(scalar, impl_->dofs.dim(), L.out()));  // takes a reference
  return L;
}

void Functional::assemble_hessian(Vec x, double alpha, Mat H) const {
  impl_->load_coordinates_and_tangents(x);
  const Impl& impl = *impl_;
  impl.assemble(
      [&impl, alpha]<typename Cells>(const auto& coordinates, const auto& target, auto block) {
        return impl.with_energy_kernel<Cells>(
            [&](const auto& k) { return k.hessian(coordinates, target, alpha, block); });
      },
      "H(alpha)", H, alpha);
}

void Functional::assemble_laplacian(RieszLaplacian kind, Vec x, Mat matrix) const {
  const Mat scalar = maij_scalar(matrix);  // a scalar Laplacian's L₁
  const Mat L = scalar ? scalar : matrix;
  if (kind == RieszLaplacian::CurrentMesh) {
    impl_->load_coordinates_and_tangents(x);
    const Impl& impl = *impl_;
    impl.assemble(
        [&impl]<typename Cells>(const auto& coordinates, const auto& target, auto block) {
          return impl.kernel<Cells>().current_laplacian(coordinates, target, block);
        },
        "current-mesh Laplacian", L);
  } else {
    if (impl_->constraints.slides_anywhere)
      impl_->load_coordinates_and_tangents(x);
    else
      impl_->require_volumes();
    const Impl& impl = *impl_;
    impl.assemble(
        [&impl]<typename Cells>(const auto&, const auto& target, auto block) {
          impl.kernel<Cells>().optimal_laplacian(target, block);
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
    visit_cells(view, block, [&]<typename Cells>() {
      const auto& k = impl_->kernel<Cells>();
      using K = typename Cells::Energy;
#pragma omp parallel for schedule(static)
      for (PetscInt c = 0; c < block.size(); ++c) {
        const PetscInt cell = block.first_cell + c;
        const auto target = impl_->target_of<Cells>(cell);
        const auto x = cell_coordinates<K>(block, c, impl_->local_x.data());
        const auto [energy, measure] = k.energy_and_measure(x, target);
        fields.energy[cell] = energy;
        fields.min_det[cell] = measure.min_det;
        fields.volume_ratio[cell] = measure.volume / impl_->targets->volumes[cell];  // Q (§6.2)
      }
    });
  }
  return fields;
}

Inversion Functional::inversion(Vec x, int listed, double below) const {
  impl_->load_coordinates(x);
  const MeshView& view = impl_->view;
  Inversion local{0, std::numeric_limits<double>::infinity(), {}};
  for (const CellBlock& block : view.blocks) {
    visit_cells(view, block, [&]<typename Cells>() {
      const auto& k = impl_->untangling_kernel<Cells>();
      using K = typename Cells::Untangling;
      // The cells on every thread (a whole pass over the mesh before every smoothing), then
      // counted and listed in order.
      std::vector<double> dets(static_cast<std::size_t>(block.size()));
#pragma omp parallel for schedule(static)
      for (PetscInt c = 0; c < block.size(); ++c)
        dets[c] = k.measure(cell_coordinates<K>(block, c, impl_->local_x.data()),
                            impl_->target_of<Cells>(block.first_cell + c))
                      .min_det;
      for (PetscInt c = 0; c < block.size(); ++c) {
        const PetscInt cell = block.first_cell + c;
        const double det = dets[c];
        local.min_det = std::min(local.min_det, det);
        if (det > below) continue;
        ++local.count;
        if (static_cast<int>(local.cells.size()) < listed)
          local.cells.push_back(view.global_cell.empty() ? cell : view.global_cell[cell]);
      }
    });
  }
  const MPI_Comm comm = impl_->dofs.comm();
  Inversion global;
  MPI_Allreduce(&local.count, &global.count, 1, MPIU_INT, MPI_SUM, comm);
  MPI_Allreduce(&local.min_det, &global.min_det, 1, MPI_DOUBLE, MPI_MIN, comm);
  // The first `listed` cells by global number: every rank's first `listed`, padded with -1.
  local.cells.resize(listed, -1);
  global.cells.resize(static_cast<std::size_t>(listed) * mpi_size(comm));
  MPI_Allgather(local.cells.data(), listed, MPIU_INT, global.cells.data(), listed, MPIU_INT, comm);
  std::erase(global.cells, -1);
  std::sort(global.cells.begin(), global.cells.end());
  if (static_cast<int>(global.cells.size()) > listed) global.cells.resize(listed);
  return global;
}

bool Functional::refresh_frames(Vec x) const {
  if (!impl_->view.surface) return false;
  impl_->load_coordinates(x);
  impl_->frames = surface_frames(impl_->view, impl_->dofs, impl_->local_x);
  return true;
}

void Functional::project_onto_boundary(Vec x) const {
  if (impl_->sliding.project) impl_->sliding.project(x);
}

bool Functional::slides() const {
  return impl_->constraints.slides_anywhere;
}

const DofMap& Functional::dofs() const {
  return impl_->dofs;
}

std::int64_t Functional::free_dofs() const {
  return impl_->constraints.free_dofs;
}

double mesh_volume(const MeshView& view, const DofMap& dofs, Vec x) {
  // Two Gauss points per direction integrate det ∇τ of Q1 cells exactly; the law is unused.
  // The curved cells' rule integrates their det J exactly too (curved_kernels.hpp).
  const EnergyOptions options{.gauss_points = 2};
  const Kernels kernels = make_kernels(options);
  const std::optional<CurvedKernels> curved_kernels =
      has_curved_cells(view) ? std::optional(make_curved_kernels(options, 0.0, 1.0)) : std::nullopt;
  std::vector<double> local_x(static_cast<std::size_t>(dofs.num_local_dofs()));
  dofs.global_to_local(x, local_x);
  double sum = 0.0;
  for (const CellBlock& block : view.blocks) {
    visit_cells(view, block, [&]<typename Cells>() {
      constexpr CellType Type = Cells::type;
      using K = typename Cells::Energy;
      const auto& k = [&]() -> const auto& {
        if constexpr (Cells::curved)
          return std::get<K>(*curved_kernels);
        else
          return std::get<NeoHookeKernel<Type>>(kernels);
      }
      ();
      for (PetscInt c = 0; c < block.size(); ++c) {
        const auto x = cell_coordinates<K>(block, c, local_x.data());
        if constexpr (Cells::framed) {  // the area of its image in its own frame
          if (const auto frame = surface_cell_frame<Type>(x))
            sum += k.measure(frame->transpose() * x, 1.0).volume;
        } else {
          sum += k.measure(x, 1.0).volume;
        }
      }
    });
  }
  return sum_over_ranks(sum, dofs.comm());
}

}  // namespace neomesh
