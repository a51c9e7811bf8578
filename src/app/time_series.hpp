// Time steps of `adapt --time A:B:N` (a geometry that moves) and the files they write: one
// mesh per step (OUT-0000.vtu … beside OUT.pvd, ParaView's collection of them, or
// OUT-0000.msh …) and one picture per step from a printf-style pattern (frames/%04d.png).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace neomesh::app {

// "A:B:N": N ≥ 1 times from A to B, both included (N = 1: A alone). Throws Error naming
// --time for anything else.
std::vector<double> parse_time_steps(const std::string& spec);

// The mesh file of step `step` of a series written to `output`: OUT.pvd → OUT-0003.vtu;
// OUT.vtu, OUT.msh → OUT-0003.vtu, OUT-0003.msh.
std::filesystem::path series_member(const std::filesystem::path& output, int step);

// `pattern` with its one %d conversion (a width and zero flag allowed: %04d) replaced by
// `step`; throws Error naming `option` unless it has exactly one such conversion and no
// other '%'.
std::string numbered_path(const std::string& option, const std::string& pattern, int step);

// Writes ParaView's collection file: one DataSet per (time, member file, relative to the
// collection's directory). Rank 0 only; atomic.
void write_pvd(const std::filesystem::path& path, const std::vector<double>& times,
               const std::vector<std::filesystem::path>& members);

}  // namespace neomesh::app
