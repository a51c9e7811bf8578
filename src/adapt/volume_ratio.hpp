// How well an adapted mesh meets its desired volumes: the distribution of
// Q = actual volume / desired volume (thesis §6.2). Q = 1 is a perfect fit; the thesis'
// Figs. 6.4/6.8 show where it fails.
#pragma once

#include <cstdint>
#include <span>

#include <mpi.h>

namespace neomesh {

struct VolumeRatioStats {
  std::int64_t cells = 0;
  double within = 0.0;  // fraction of cells with Q in [1/2, 2]
  double min = 0.0, median = 0.0, max = 0.0;
};

// `q`: Q of this rank's cells. Collective.
VolumeRatioStats volume_ratio_stats(std::span<const double> q, MPI_Comm comm);

}  // namespace neomesh
