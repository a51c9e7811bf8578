#include "app/run.hpp"

#include <cctype>
#include <csignal>
#include <string>
#include <vector>

#include <petscsys.h>

#include "app/subcommand.hpp"
#include "core/error.hpp"
#include "core/log.hpp"

namespace neomesh::app {

namespace {

// Options of the form `-name [value]` (one dash, then a letter, then more) belong to PETSc;
// a value is the next argument unless it starts with '-' and is not a number. Short neomesh
// options are a single letter (`-o`), so they never look like this.
bool is_petsc_option(const std::string& arg) {
  return arg.size() > 2 && arg[0] == '-' && arg[1] != '-' && std::isalpha(arg[1]) &&
         arg.find('=') == std::string::npos;
}
bool is_number(const std::string& s) {
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return !s.empty() && end == s.c_str() + s.size();
}

struct SplitArguments {
  std::vector<std::string> neomesh;  // argv[0] first
  std::vector<std::string> petsc;    // argv[0] first
};

SplitArguments split_arguments(int argc, char** argv) {
  SplitArguments out;
  out.neomesh.emplace_back(argv[0]);
  out.petsc.emplace_back(argv[0]);
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (is_petsc_option(arg)) {
      out.petsc.push_back(arg);
      if (i + 1 < argc && (argv[i + 1][0] != '-' || is_number(argv[i + 1])))
        out.petsc.emplace_back(argv[++i]);
    } else {
      out.neomesh.push_back(arg);
    }
  }
  return out;
}

// PETSc and MPI for the lifetime of one command; PETSc's own signal handler is replaced by
// the default so that Ctrl-C ends the run (temporary output files are then never renamed).
class PetscSession {
 public:
  explicit PetscSession(std::vector<std::string>& args) {
    for (auto& a : args) argv_.push_back(a.data());
    argv_.push_back(nullptr);
    int argc = static_cast<int>(args.size());
    char** argv = argv_.data();
    if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0)
      throw Error("could not initialize PETSc/MPI");
    PetscPopSignalHandler();
  }
  ~PetscSession() { PetscFinalize(); }

 private:
  std::vector<char*> argv_;
};

}  // namespace

int run(int argc, char** argv) {
  SplitArguments args = split_arguments(argc, argv);

  CLI::App cli{
      "neomesh moves the vertices of a 2D/3D mesh (triangles, quadrilaterals, tetrahedra, "
      "hexahedra) so that its cells become well shaped and correctly sized, minimizing a "
      "Neo-Hookean energy. Options with a single dash that neomesh does not know (e.g. "
      "-hess_ksp_monitor) are passed to PETSc; put them after neomesh's own options."};
  cli.set_version_flag("--version", std::string("neomesh ") + NEOMESH_VERSION);
  cli.require_subcommand(1);
  bool quiet = false, verbose = false;
  cli.add_flag("-q,--quiet", quiet, "print only the final summary and errors");
  cli.add_flag("-v,--verbose", verbose, "also print linear-solver details");
  cli.set_config("--config", "", "read options from a TOML/INI file (command line wins)");

  std::vector<Subcommand> commands = {add_generate(cli), add_quality(cli), add_convert(cli),
                                      add_smooth(cli),   add_render(cli),  add_adapt(cli)};
  for (auto& c : commands) c.cli->fallthrough();

  try {
    std::vector<std::string> reversed(args.neomesh.rbegin(), args.neomesh.rend() - 1);
    cli.parse(std::move(reversed));
  } catch (const CLI::CallForHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return cli.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "neomesh: error: %s (see neomesh --help)\n", e.what());
    return 2;
  }
  set_verbosity(quiet ? Verbosity::Quiet : verbose ? Verbosity::Verbose : Verbosity::Normal);

  try {
    PetscSession petsc(args.petsc);
    try {
      for (auto& c : commands)
        if (c.cli->parsed()) c.run();
    } catch (const std::exception& e) {
      // Printed by whichever rank found it (input errors are found collectively, so that
      // is usually rank 0 alone); other ranks may be blocked in a collective call, so a
      // parallel run ends the whole job.
      std::fprintf(stderr, "neomesh: error: %s\n", e.what());
      std::fflush(stderr);
      int size = 1;
      MPI_Comm_size(MPI_COMM_WORLD, &size);
      if (size > 1) MPI_Abort(MPI_COMM_WORLD, 1);
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "neomesh: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace neomesh::app
