#include "adapt/volume_ratio.hpp"

#include <algorithm>
#include <vector>

namespace neomesh {

VolumeRatioStats volume_ratio_stats(std::span<const double> q, MPI_Comm comm) {
  // Every rank gathers all values: the median needs them, and one double per cell is small
  // next to the mesh itself.
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const int local = static_cast<int>(q.size());
  std::vector<int> counts(ranks), offsets(ranks, 0);
  MPI_Allgather(&local, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 1; r < ranks; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<double> all(offsets.back() + counts.back());
  MPI_Allgatherv(q.data(), local, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE,
                 comm);

  VolumeRatioStats s;
  s.cells = static_cast<std::int64_t>(all.size());
  if (all.empty()) return s;
  std::sort(all.begin(), all.end());
  s.min = all.front();
  s.max = all.back();
  const std::size_t n = all.size();
  s.median = n % 2 ? all[n / 2] : 0.5 * (all[n / 2 - 1] + all[n / 2]);
  s.within = static_cast<double>(std::count_if(all.begin(), all.end(),
                                               [](double x) { return x >= 0.5 && x <= 2.0; })) /
             static_cast<double>(n);
  return s;
}

}  // namespace neomesh
