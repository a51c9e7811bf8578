// The distribution of Q = actual volume / desired volume over a distributed mesh
// (VolumeRatioStats, include/neomesh/quality.hpp); the thesis' Figs. 6.4/6.8 show where
// adaptation fails to meet it.
#pragma once

#include <span>

#include <mpi.h>

#include <neomesh/quality.hpp>

namespace neomesh {

// `q`: Q of this rank's cells. Collective.
VolumeRatioStats volume_ratio_stats(std::span<const double> q, MPI_Comm comm);

}  // namespace neomesh
