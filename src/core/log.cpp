#include "core/log.hpp"

#include <mpi.h>

namespace neomesh {

namespace {
Verbosity current = Verbosity::Normal;
}

void set_verbosity(Verbosity v) {
  current = v;
}
Verbosity verbosity() {
  return current;
}

bool is_root_rank() {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) return true;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank == 0;
}

}  // namespace neomesh
