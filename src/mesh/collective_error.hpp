// Errors found by some ranks of a collective operation (reading on rank 0, writing on rank
// 0, validating local cells) must end the operation on every rank, or the others would
// wait forever in the next collective call.
#pragma once

#include <string>

#include <mpi.h>

namespace neomesh {

// Collective: if any rank passes a non-empty `local_error`, every rank throws Error with the
// message of the lowest such rank.
void throw_if_any(MPI_Comm comm, const std::string& local_error);

// Collective: runs `action` on rank 0 only; an Error (or other exception) it throws is
// rethrown as Error on every rank.
template <typename Action>
void on_root(MPI_Comm comm, Action&& action) {
  std::string error;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0) {
    try {
      action();
    } catch (const std::exception& e) {
      error = e.what();
      if (error.empty()) error = "unknown error";
    }
  }
  throw_if_any(comm, error);
}

}  // namespace neomesh
