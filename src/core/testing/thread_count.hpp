// Runs a scope with a given number of OpenMP threads, and restores the number before it:
// for tests that compare results across thread counts.
#pragma once

#include <omp.h>

namespace neomesh::testing {

class ThreadCount {
 public:
  explicit ThreadCount(int n) : saved_(omp_get_max_threads()) { omp_set_num_threads(n); }
  ~ThreadCount() { omp_set_num_threads(saved_); }
  ThreadCount(const ThreadCount&) = delete;
  ThreadCount& operator=(const ThreadCount&) = delete;

 private:
  int saved_;
};

}  // namespace neomesh::testing
