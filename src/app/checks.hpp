// Checks every command runs before it costs any time: numeric options finite and in range,
// every output file writable in a known format. Each failure is one Error naming the option.
#pragma once

#include <cmath>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/error.hpp"

namespace neomesh::app {

// Throws Error "<option> must be <range> (got <value>)" unless `value` is finite and
// `in_range` (the caller's test, e.g. value > 0). inf and nan are refused here so that they
// never reach the method (an infinite λ would make every cell look inverted).
template <typename T>
void check_option(const char* option, T value, bool in_range, const char* range) {
  if (!std::isfinite(static_cast<double>(value)))
    fail("{} must be a finite number, {} (got {})", option, range, value);
  if (!in_range) fail("{} must be {} (got {})", option, range, value);
}

// Every value of a list option (--circle 0.5,0.5,0.2) is finite.
void check_finite(const char* option, std::span<const double> values);

// The mesh formats as --help names them, one list for every subcommand.
inline constexpr const char* kMeshInputs =
    ".msh Gmsh 2.2/4.1, .xml FEAT3, .vtk VTK legacy, .vtu/.pvtu VTK XML, .mesh Medit, "
    ".exo/.e/.ex2 Exodus II, .cgns CGNS";
inline constexpr const char* kMeshOutputs =
    ".vtu with per-cell fields, .vtk, .msh, .mesh, .exo or .cgns";
// "<what> (<kMeshInputs>; a FEAT3 mesh may come with the files of its charts, in any order)"
std::string input_mesh_help(const char* what);

// Not collective: throws Error unless `path` has the extension of a mesh format neomesh reads,
// before the (possibly long) read.
void check_input_mesh(const std::string& path);
void check_input_mesh(const std::vector<std::string>& paths);

// A command's input files — a mesh, and for a FEAT3 mesh the files with its charts, in any
// order — as Mesh::read takes them, and as messages name them ("charts.xml + mesh.xml").
std::vector<std::filesystem::path> input_paths(const std::vector<std::string>& paths);
std::string input_label(const std::vector<std::string>& paths);

enum class OutputKind { Mesh, Picture, Json };

// Not collective: throws Error unless `path`, the value of `option`, can be written: not
// empty, an extension neomesh writes for `kind`, an existing writable directory.
void check_output_file(const char* option, const std::string& path, OutputKind kind);

// For CLI11 options naming an optional output (--report, --picture): an empty value is an
// error at parsing ("--report: the output path is empty"), not "no report".
extern const CLI::Validator kOutputPath;

}  // namespace neomesh::app
