// neomesh as a library, the way a simulation with a moving object uses it: the simulation owns
// a mesh of [-1,1]² (here: a jittered grid of quadrilaterals and triangles, given as arrays in
// its own vertex numbering), smooths it once, then at every time step moves the mesh so that
// small cells follow a bubble rising through the domain and a closed chain of edges lies on its
// surface. Each step starts warm from the one before. Runs serially or under mpiexec.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include <neomesh/neomesh.hpp>

namespace {

// A grid of n × n cells on [-1,1]², interior vertices moved by up to a quarter cell; the
// lower half quadrilaterals, the upper half split into two triangles each. Vertex j * (n + 1)
// + i is the one at column i, row j. Cells list their vertices counter-clockwise (Gmsh order).
struct Arrays {
  std::vector<double> coordinates;
  std::vector<std::int64_t> cells;
  std::vector<neomesh::CellType> types;
};

Arrays jittered_grid(int n) {
  Arrays a;
  const double h = 2.0 / n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool interior = i > 0 && i < n && j > 0 && j < n;
      // Deterministic "noise": the same mesh on every run.
      const double dx = interior ? 0.25 * h * std::sin(12.9898 * i + 78.233 * j) : 0.0;
      const double dy = interior ? 0.25 * h * std::cos(39.3468 * i + 11.135 * j) : 0.0;
      a.coordinates.push_back(-1.0 + i * h + dx);
      a.coordinates.push_back(-1.0 + j * h + dy);
    }
  const auto vertex = [n](int i, int j) { return std::int64_t{j} * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::int64_t v00 = vertex(i, j), v10 = vertex(i + 1, j), v11 = vertex(i + 1, j + 1),
                         v01 = vertex(i, j + 1);
      if (j < n / 2) {
        a.cells.insert(a.cells.end(), {v00, v10, v11, v01});
        a.types.push_back(neomesh::CellType::Quadrilateral);
      } else {
        a.cells.insert(a.cells.end(), {v00, v10, v11, v00, v11, v01});
        a.types.insert(a.types.end(), 2, neomesh::CellType::Triangle);
      }
    }
  return a;
}

void print_quality(int rank, const char* when, const neomesh::QualitySummary& q) {
  if (rank == 0)
    std::printf("%-28s min scaled Jacobian %.3f, mean inverse mean ratio %.4f, %lld inverted\n",
                when, q.scaled_jacobian.min, q.inverse_mean_ratio.mean,
                static_cast<long long>(q.inverted));
}

}  // namespace

int main(int argc, char** argv) {
  neomesh::Session session(&argc, &argv);  // MPI and PETSc, unless the program runs them
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  try {
    // The arrays are given on the first process; neomesh distributes the cells.
    const Arrays grid = rank == 0 ? jittered_grid(32) : Arrays{};
    neomesh::Mesh mesh = neomesh::Mesh::from_arrays(MPI_COMM_WORLD, 2, grid.coordinates, grid.cells,
                                                    grid.types, "jittered grid");
    print_quality(rank, "input:", mesh.quality());

    neomesh::Optimizer optimizer(mesh);
    neomesh::SmoothOptions smooth;
    smooth.sizes = neomesh::SizeMode::Uniform;
    const neomesh::Result smoothed = optimizer.smooth(smooth);
    if (rank == 0)
      std::printf("smoothed in %zu iterations (%s)\n", smoothed.history.size(),
                  neomesh::describe(smoothed.reason).c_str());
    print_quality(rank, "smoothed:", smoothed.quality_after);

    // A bubble of radius 0.2 rising from y = -0.5: small cells near its surface, and a closed
    // chain of edges on it.
    neomesh::LevelSet bubble = neomesh::LevelSet::expression("sqrt(x^2+(y+0.5-0.25*t)^2)-0.2");
    neomesh::AdaptOptions adapt;
    for (int step = 0; step <= 4; ++step) {
      bubble.set_time(step);
      const neomesh::Result r = optimizer.adapt(bubble, adapt);
      if (rank == 0)
        std::printf("step %d (bubble at y = %+.2f): %3zu iterations, %zu updates, %.2f s\n", step,
                    -0.5 + 0.25 * step, r.history.size(), r.update_iterations.size(), r.seconds);
      if (rank == 0 && r.fit)
        std::printf("  fitted: %lld edges on the bubble, every vertex within %.1e of it\n",
                    static_cast<long long>(r.fit->facets), r.fit->max_distance);
      print_quality(rank, "  adapted:", r.quality_after);
    }

    // The simulation reads the moved vertices back in its own numbering.
    const std::vector<std::int64_t> numbers = mesh.vertex_numbers();
    const std::vector<double> xy = mesh.coordinates();
    for (std::size_t k = 0; k < numbers.size(); ++k)
      if (numbers[k] == 33 * 16 + 16)  // the grid's centre vertex, on whichever process owns it
        std::printf("vertex %lld (the grid's centre) is now at (%.4f, %.4f)\n",
                    static_cast<long long>(numbers[k]), xy[2 * k], xy[2 * k + 1]);
    mesh.write("moving_bubble.vtu", optimizer.cell_fields(), optimizer.vertex_fields());
    // The fitted edges as the physical group "interface".
    mesh.write("moving_bubble.msh", {}, {}, optimizer.facet_groups());
    if (rank == 0) std::printf("wrote moving_bubble.vtu and moving_bubble.msh\n");
  } catch (const neomesh::Error& e) {
    if (rank == 0) std::fprintf(stderr, "moving_bubble: %s\n", e.what());
    return 1;
  }
  return 0;
}
