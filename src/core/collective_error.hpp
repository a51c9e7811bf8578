// Errors found by some ranks of a collective operation (reading on rank 0, writing on rank
// 0, validating local cells) must end the operation on every rank, or the others would
// wait forever in the next collective call. Every rank then throws the same
// CollectiveError, which the command line reports once (rank 0) and ends the run in order.
#pragma once

#include <string>

#include <mpi.h>

#include "core/error.hpp"

namespace neomesh {

// Collective: if any rank passes a non-empty `local_error`, every rank throws CollectiveError
// with the message of the lowest such rank.
void throw_if_any(MPI_Comm comm, const std::string& local_error);

// Collective: runs `action` on every rank; if it throws on any rank (Error, std::bad_alloc,
// ...), every rank throws CollectiveError with the message of the lowest such rank
// (user_message). `action` must not call collective operations that could leave a rank
// waiting: it is for local work such as checks and file access.
template <typename Action>
void collectively(MPI_Comm comm, Action&& action) {
  std::string error;
  try {
    action();
  } catch (const std::exception& e) {
    error = user_message(e);
  }
  throw_if_any(comm, error);
}

// Collective: runs `action` on rank 0 only; an Error (or other exception) it throws is
// rethrown as CollectiveError on every rank.
template <typename Action>
void on_root(MPI_Comm comm, Action&& action) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  collectively(comm, [&] {
    if (rank == 0) action();
  });
}

}  // namespace neomesh
