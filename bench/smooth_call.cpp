// The library call that the Python package's overhead is measured against
// (bench/python_overhead.py): Optimizer::smooth on a mesh read from a file, timed alone, best
// of N runs, each on a freshly read mesh, with the command line's thread count.
//   smooth_call MESH [RUNS]  ->  prints "seconds <best>"
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>

#include <neomesh/neomesh.hpp>

#include "api/thread_count.hpp"

int main(int argc, char** argv) {
  neomesh::Session session(&argc, &argv);
  if (argc < 2) {
    std::fprintf(stderr, "usage: smooth_call MESH [RUNS]\n");
    return 2;
  }
  const int runs = argc > 2 ? std::stoi(argv[2]) : 5;
  double best = std::numeric_limits<double>::infinity();
  for (int run = 0; run < runs; ++run) {
    neomesh::Mesh mesh = neomesh::Mesh::read(argv[1]);
    if (const int t = neomesh::run_thread_count(mesh); t > 0) omp_set_num_threads(t);
    neomesh::Optimizer optimizer(mesh);
    const double start = MPI_Wtime();
    optimizer.smooth();
    best = std::min(best, MPI_Wtime() - start);
  }
  std::printf("seconds %.6f\n", best);
  return 0;
}
