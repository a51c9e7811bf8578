// Cost of the energy per cell type: F, F and its gradient, the assembly of H(α) (cell blocks
// added into the matrix values) and the one-time setup of the H and L matrices, on perturbed
// boxes of about 2.5·10⁵ (2D) or 10⁵ (3D) cells; and the assembly of H(α) and L and the
// setup on the boxes of the whole-program runs (300² quadrilaterals, 40³ cubes of tetrahedra,
// 30³ hexahedra).
// Every problem uses the energy `neomesh smooth` runs (SmoothOptions' λ, μ and 2 Gauss points
// per direction). The counter `s_per_Mcell` is the time of one evaluation scaled to a million
// cells.
//
//   OMP_NUM_THREADS=1 ./energy_bench     (serial; the default uses every core)
#include <benchmark/benchmark.h>
#include <petscsys.h>

#include <map>
#include <memory>
#include <random>

#include "energy/functional.hpp"
#include "generate/generate.hpp"
#include "generate/serial_view.hpp"

namespace neomesh {
namespace {

const EnergyOptions kSmoothEnergy = SmoothOptions{}.energy;

// Cells per direction giving about 2.5·10⁵ (2D) or 10⁵ (3D) cells: 2 n² = 250 632 triangles,
// n² = 250 000 quadrilaterals, 6 n³ = 105 456 tetrahedra, n³ = 97 336 hexahedra,
// 2 n³ = 93 312 wedges and 6 n³ = 93 750 pyramids.
int cells_per_direction(CellType type) {
  constexpr int kCells[kNumCellTypes] = {354, 500, 26, 46, 36, 25};
  return kCells[static_cast<int>(type)];
}

// A box whose interior vertices are moved by up to 20% of the cell size (pyramids: 8%), equal
// desired volumes, boundary fixed; built once per cell type and kept for all benchmarks.
struct BenchMesh {
  MeshData data;
  MeshView view;
  DofMap dofs;
  OwnedVec x;
  Functional functional;
  OwnedMat matrix;

  BenchMesh(CellType type, int n)
      : data(perturbed_box(type, n)),
        view(serial_view(data)),
        dofs(DofMap::serial(data.dim, static_cast<PetscInt>(data.num_vertices()))),
        x(dofs.create_global_vector()),
        functional(equal_volumes(view, dofs, x)) {
    matrix = functional.create_matrix(HessianUse::Products);
  }

  // Copies the mesh's coordinates into x; the functional of equal desired volumes.
  static Functional equal_volumes(const MeshView& view, const DofMap& dofs, Vec x) {
    {
      VecWriteView out(x);
      std::copy(view.coords.begin(), view.coords.end(), out.data());
    }
    const double volume = mesh_volume(view, dofs, x) / view.num_cells;
    return Functional(kSmoothEnergy,
                      Problem(view, dofs, view.on_boundary)
                          .with_desired_volumes(std::vector<double>(view.num_cells, volume)));
  }

  static MeshData perturbed_box(CellType type, int n) {
    MeshData mesh = box(type, n);
    std::mt19937 rng(1);
    // The pyramids of a split cube are half a cube high: moved by 20% of the cube some invert.
    const double amplitude = (type == CellType::Pyramid ? 0.08 : 0.2) * 2.0 / n;
    std::uniform_real_distribution<double> u(-amplitude, amplitude);
    const std::vector<std::uint8_t> boundary = boundary_vertices(mesh);
    for (std::int64_t v = 0; v < mesh.num_vertices(); ++v)
      if (!boundary[v])
        for (int d = 0; d < mesh.dim; ++d) mesh.coords[v * mesh.dim + d] += u(rng);
    return mesh;
  }
};

// Destroyed by main before PetscFinalize.
std::map<std::pair<CellType, int>, std::unique_ptr<BenchMesh>> problems;

BenchMesh& problem(CellType type, int n) {
  auto& p = problems[{type, n}];
  if (!p) p = std::make_unique<BenchMesh>(type, n);
  return *p;
}

BenchMesh& problem(CellType type) {
  return problem(type, cells_per_direction(type));
}

void report_per_cell(benchmark::State& state, const BenchMesh& p) {
  state.counters["cells"] = static_cast<double>(p.view.num_cells);
  state.counters["s_per_Mcell"] = benchmark::Counter(
      static_cast<double>(p.view.num_cells) / 1e6,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <CellType Type>
void Value(benchmark::State& state) {
  BenchMesh& p = problem(Type);
  for (auto _ : state) benchmark::DoNotOptimize(p.functional.value(p.x));
  report_per_cell(state, p);
}

template <CellType Type>
void ValueAndGradient(benchmark::State& state) {
  BenchMesh& p = problem(Type);
  OwnedVec gradient = p.dofs.create_global_vector();
  for (auto _ : state) benchmark::DoNotOptimize(p.functional.value_and_gradient(p.x, gradient));
  report_per_cell(state, p);
}

template <CellType Type>
void AssembleHessian(benchmark::State& state) {
  BenchMesh& p = problem(Type);
  for (auto _ : state) p.functional.assemble_hessian(p.x, 0.5, p.matrix);
  report_per_cell(state, p);
}

// The matrices a serial `smooth` with a fixed boundary makes: H(α) for products only (the
// Riesz solve's hierarchy preconditions the δ̃ solve) and the scalar Laplacian.
void create_run_matrices(const Functional& f) {
  const OwnedMat hessian = f.create_matrix(HessianUse::Products);
  const OwnedMat laplacian = f.create_scalar_laplacian_matrix();
}

// The one-time setup of a run: the patterns of H(α) and L on a fresh Functional.
template <CellType Type>
void CreateMatrices(benchmark::State& state) {
  BenchMesh& p = problem(Type);
  for (auto _ : state)
    create_run_matrices(Functional(kSmoothEnergy, Problem(p.view, p.dofs, p.view.on_boundary)));
  report_per_cell(state, p);
}

// A phase's Functional (an untangling round's) from the problem of another: the pattern is
// shared, so this is what a new ε or new desired volumes cost.
template <CellType Type>
void DerivedFunctional(benchmark::State& state) {
  BenchMesh& p = problem(Type);
  for (auto _ : state) {
    const Functional f(kSmoothEnergy, p.functional.problem().with_untangling(0.1));
    benchmark::DoNotOptimize(&f);
  }
  report_per_cell(state, p);
}

// Whole assemblies on the boxes of the whole-program runs: H(α), the optimal-cell Laplacian
// into its own (uncoupled) matrix, and the one-time setup of the run's matrices.
template <CellType Type, int N>
void WholeHessian(benchmark::State& state) {
  BenchMesh& p = problem(Type, N);
  for (auto _ : state) p.functional.assemble_hessian(p.x, 0.5, p.matrix);
  report_per_cell(state, p);
}

template <CellType Type, int N>
void WholeLaplacian(benchmark::State& state) {
  BenchMesh& p = problem(Type, N);
  const OwnedMat laplacian = p.functional.create_laplacian_matrix();
  for (auto _ : state)
    p.functional.assemble_laplacian(RieszLaplacian::OptimalCells, p.x, laplacian);
  report_per_cell(state, p);
}

template <CellType Type, int N>
void WholeSetup(benchmark::State& state) {
  BenchMesh& p = problem(Type, N);
  for (auto _ : state)
    create_run_matrices(Functional(kSmoothEnergy, Problem(p.view, p.dofs, p.view.on_boundary)));
  report_per_cell(state, p);
}

#define NEOMESH_WHOLE_BENCH(type, n)                                                \
  BENCHMARK(WholeHessian<type, n>)->Unit(benchmark::kMillisecond)->UseRealTime();   \
  BENCHMARK(WholeLaplacian<type, n>)->Unit(benchmark::kMillisecond)->UseRealTime(); \
  BENCHMARK(WholeSetup<type, n>)->Unit(benchmark::kMillisecond)->UseRealTime()

NEOMESH_WHOLE_BENCH(CellType::Quadrilateral, 300);
NEOMESH_WHOLE_BENCH(CellType::Tetrahedron, 40);
NEOMESH_WHOLE_BENCH(CellType::Hexahedron, 30);

#define NEOMESH_ENERGY_BENCH(type)                                                 \
  BENCHMARK(Value<type>)->Unit(benchmark::kMillisecond)->UseRealTime();            \
  BENCHMARK(ValueAndGradient<type>)->Unit(benchmark::kMillisecond)->UseRealTime(); \
  BENCHMARK(AssembleHessian<type>)->Unit(benchmark::kMillisecond)->UseRealTime();  \
  BENCHMARK(CreateMatrices<type>)->Unit(benchmark::kMillisecond)->UseRealTime();   \
  BENCHMARK(DerivedFunctional<type>)->Unit(benchmark::kMillisecond)->UseRealTime()

NEOMESH_ENERGY_BENCH(CellType::Triangle);
NEOMESH_ENERGY_BENCH(CellType::Quadrilateral);
NEOMESH_ENERGY_BENCH(CellType::Tetrahedron);
NEOMESH_ENERGY_BENCH(CellType::Hexahedron);
NEOMESH_ENERGY_BENCH(CellType::Wedge);
NEOMESH_ENERGY_BENCH(CellType::Pyramid);

}  // namespace
}  // namespace neomesh

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  neomesh::problems.clear();
  return PetscFinalize() != 0;
}
