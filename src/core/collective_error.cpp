#include "core/collective_error.hpp"

#include <climits>

#include "core/error.hpp"

namespace neomesh {

void throw_if_any(MPI_Comm comm, const std::string& local_error) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  int mine = local_error.empty() ? INT_MAX : rank;
  int first = INT_MAX;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == INT_MAX) return;
  std::string message = local_error;
  int size = static_cast<int>(message.size());
  MPI_Bcast(&size, 1, MPI_INT, first, comm);
  message.resize(size);
  MPI_Bcast(message.data(), size, MPI_CHAR, first, comm);
  throw CollectiveError(message);
}

}  // namespace neomesh
