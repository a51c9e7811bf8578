// Console output of a run: what the user sees, by verbosity level. Rank 0 prints; the
// other ranks stay silent so that `mpiexec -n P` output reads like a serial run.
#pragma once

#include <cstdio>
#include <utility>

#include <fmt/format.h>

namespace neomesh {

enum class Verbosity { Quiet, Normal, Verbose };

void set_verbosity(Verbosity v);
Verbosity verbosity();
bool is_root_rank();

// Normal output (tables, summaries, progress), shown unless --quiet.
template <typename... Args>
void say(fmt::format_string<Args...> format, Args&&... args) {
  if (verbosity() != Verbosity::Quiet && is_root_rank())
    fmt::print(stdout, format, std::forward<Args>(args)...), std::fflush(stdout);
}

// Solver details, shown with --verbose.
template <typename... Args>
void detail(fmt::format_string<Args...> format, Args&&... args) {
  if (verbosity() == Verbosity::Verbose && is_root_rank())
    fmt::print(stdout, format, std::forward<Args>(args)...), std::fflush(stdout);
}

// Final results, shown even with --quiet.
template <typename... Args>
void always(fmt::format_string<Args...> format, Args&&... args) {
  if (is_root_rank()) fmt::print(stdout, format, std::forward<Args>(args)...), std::fflush(stdout);
}

}  // namespace neomesh
