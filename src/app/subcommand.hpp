// What every subcommand provides: it adds its options to the CLI and returns the action
// to run once the command line was parsed and PETSc is up.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace neomesh::app {

struct Subcommand {
  CLI::App* cli = nullptr;
  std::function<void()> run;
};

Subcommand add_generate(CLI::App& app);
Subcommand add_quality(CLI::App& app);
Subcommand add_convert(CLI::App& app);
Subcommand add_curve(CLI::App& app);
Subcommand add_smooth(CLI::App& app);
Subcommand add_render(CLI::App& app);
Subcommand add_adapt(CLI::App& app);

}  // namespace neomesh::app
