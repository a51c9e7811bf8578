// The library call that the Python package's overhead is measured against
// (bench/python_overhead.py): Optimizer::smooth on a mesh read from a file, timed alone, best
// of N runs, each on a freshly read mesh, with the command line's thread count.
//   smooth_call MESH [RUNS]  ->  prints "seconds <best> iterations <n>"
// With WARM steps, each run then calls smooth() WARM times more on the same Optimizer, each
// after moving 1 % of the vertices (every 100th by number) by a tenth of the mean cell size in
// a direction of a fixed pseudo-random sequence: what a simulation that moves a few vertices
// between calls pays per call.
//   smooth_call MESH RUNS WARM  ->  also "warm <k> seconds <best> iterations <n>" per step
// Under callgrind, --dump-before/--dump-after=neomesh::Optimizer::smooth* give each call's
// instructions as a part of its own.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <neomesh/neomesh.hpp>

#include "api/thread_count.hpp"

namespace {

// Moves every 100th vertex by a tenth of the mean cell size (from the bounding box), the
// directions drawn from `rng`.
void move_one_percent(neomesh::Mesh& mesh, std::mt19937& rng) {
  std::vector<double> x = mesh.coordinates();
  const int d = mesh.coordinate_dim();
  double box = 1.0;
  for (int a = 0; a < d; ++a) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t i = a; i < x.size(); i += d) lo = std::min(lo, x[i]), hi = std::max(hi, x[i]);
    box *= hi - lo;
  }
  const double h = std::pow(box / static_cast<double>(mesh.num_cells()), 1.0 / d);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t v = 0; v < x.size() / d; v += 100)
    for (int a = 0; a < d; ++a) x[d * v + a] += 0.1 * h * u(rng);
  mesh.set_coordinates(x);
}

}  // namespace

int main(int argc, char** argv) {
  neomesh::Session session(&argc, &argv);
  if (argc < 2) {
    std::fprintf(stderr, "usage: smooth_call MESH [RUNS [WARM]]\n");
    return 2;
  }
  const int runs = argc > 2 ? std::stoi(argv[2]) : 5;
  const int warm = argc > 3 ? std::stoi(argv[3]) : 0;
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> best_warm(warm, std::numeric_limits<double>::infinity());
  std::vector<int> iterations(warm, 0);
  int cold_iterations = 0;
  for (int run = 0; run < runs; ++run) {
    neomesh::Mesh mesh = neomesh::Mesh::read(argv[1]);
    if (const int t = neomesh::run_thread_count(mesh); t > 0) omp_set_num_threads(t);
    neomesh::Optimizer optimizer(mesh);
    const double start = MPI_Wtime();
    cold_iterations = static_cast<int>(optimizer.smooth().history.size());
    best = std::min(best, MPI_Wtime() - start);
    std::mt19937 rng(1);  // the same moves in every run
    for (int k = 0; k < warm; ++k) {
      move_one_percent(mesh, rng);
      const double at = MPI_Wtime();
      iterations[k] = static_cast<int>(optimizer.smooth().history.size());
      best_warm[k] = std::min(best_warm[k], MPI_Wtime() - at);
    }
  }
  std::printf("seconds %.6f iterations %d\n", best, cold_iterations);
  for (int k = 0; k < warm; ++k)
    std::printf("warm %d seconds %.6f iterations %d\n", k + 1, best_warm[k], iterations[k]);
  return 0;
}
