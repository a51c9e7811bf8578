#include "app/checks.hpp"

#include <neomesh/mesh.hpp>
#include "core/atomic_file.hpp"

#include "report/canvas.hpp"

namespace neomesh::app {

std::string input_mesh_help(const char* what) {
  return fmt::format("{} ({}; a FEAT3 mesh may come with the files of its charts, in any order)",
                     what, kMeshInputs);
}

void check_input_mesh(const std::string& path) {
  check_readable_format(path);
}

void check_input_mesh(const std::vector<std::string>& paths) {
  for (const std::string& path : paths) check_input_mesh(path);
}

std::vector<std::filesystem::path> input_paths(const std::vector<std::string>& paths) {
  return {paths.begin(), paths.end()};
}

std::string input_label(const std::vector<std::string>& paths) {
  std::string label;
  for (const std::string& path : paths) label += (label.empty() ? "" : " + ") + path;
  return label;
}

void check_finite(const char* option, std::span<const double> values) {
  for (double v : values)
    if (!std::isfinite(v)) fail("{}: every value must be a finite number (got {})", option, v);
}

void check_output_file(const char* option, const std::string& path, OutputKind kind) {
  if (path.empty()) fail("{}: the output path is empty", option);
  try {
    switch (kind) {
      case OutputKind::Mesh:
        check_writable_format(path);
        break;
      case OutputKind::Picture:
        picture_format(path);
        break;
      case OutputKind::Json:
        break;
    }
    check_writable(path);
  } catch (const Error& e) {
    fail("{}: {}", option, e.what());  // which option, when a run writes several files
  }
}

const CLI::Validator kOutputPath(
    [](const std::string& path) { return path.empty() ? "the output path is empty" : ""; }, "PATH");

}  // namespace neomesh::app
