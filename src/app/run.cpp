#include "app/run.hpp"

#include <cctype>
#include <csignal>
#include <cstring>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <petscsys.h>
#include <unistd.h>

#include "app/subcommand.hpp"
#include "core/atomic_file.hpp"
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

// Set once MPI is up; the signal handler may not call MPI.
volatile std::sig_atomic_t report_interrupt = 1;

// Ctrl-C (SIGINT) or a kill (SIGTERM, also what mpiexec forwards): remove the temporary
// file being written, if any, and die of the signal. Output files only appear by a rename
// at the very end, so nothing partial is left behind.
extern "C" void on_interrupt(int signal) {
  remove_temporary_files();
  const char message[] = "\nneomesh: interrupted; no output file was written\n";
  if (report_interrupt) (void)!write(STDERR_FILENO, message, sizeof message - 1);
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

// Options that PETSc itself reads only in PetscFinalize: never reported as unused.
bool read_at_finalize(const char* name) {
  for (const char* prefix : {"log", "options_", "malloc", "memory_view", "objects_dump"})
    if (std::strncmp(name, prefix, std::strlen(prefix)) == 0) return true;
  return false;
}

// PETSc and MPI for the lifetime of one command. PETSc's own signal handler is replaced by
// on_interrupt, and its error handler by one that returns the error without printing
// PETSc's multi-line banner (check_petsc turns it into one Error line).
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
    report_interrupt = is_root_rank();
    std::signal(SIGINT, on_interrupt);
    std::signal(SIGTERM, on_interrupt);
    PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  }
  ~PetscSession() { PetscFinalize(); }

  // A misspelled PETSc option (-hess_ksp_monitr) would otherwise be ignored in silence.
  static void warn_unused_options() {
    PetscInt count = 0;
    char** names = nullptr;
    char** values = nullptr;
    if (PetscOptionsLeftGet(nullptr, &count, &names, &values) != 0) return;
    for (PetscInt i = 0; i < count; ++i)
      if (is_root_rank() && !read_at_finalize(names[i]))
        std::fprintf(stderr,
                     "neomesh: warning: PETSc option -%s was not used (misspelled, or not "
                     "for this subcommand?)\n",
                     names[i]);
    PetscOptionsLeftRestore(nullptr, &count, &names, &values);
  }

 private:
  std::vector<char*> argv_;
};

// "--lambda: 'abc' is not a number (see neomesh smooth --help)": CLI11's messages made
// lower-case, specific and pointing to the help of the subcommand being parsed.
// "a number" / "a whole number": what an option's value must look like, from CLI11's type.
std::string expected_value(const CLI::App* command, const std::string& option) {
  const CLI::Option* o = command ? command->get_option_no_throw(option) : nullptr;
  const std::string type = o ? o->get_type_name() : "";
  if (type.find("UINT") != std::string::npos) return "a whole number >= 0";
  if (type.find("INT") != std::string::npos) return "a whole number";
  if (type.find("FLOAT") != std::string::npos) return "a number";
  return "a valid value";
}

std::string describe_parse_error(const CLI::ParseError& e, const std::vector<std::string>& args,
                                 const CLI::App* command) {
  std::string config_file;
  for (std::size_t i = 1; i < args.size(); ++i)
    if (args[i - 1] == "--config") config_file = args[i];
  std::string m = e.what();
  std::smatch match;
  if (std::regex_match(m, match, std::regex("Could not convert: (\\S+) = (.*)")))
    return fmt::format("{}: '{}' is not {}", match[1].str(), match[2].str(),
                       expected_value(command, match[1].str()));
  // --circle 1,2 (CLI11 says "At least 3 required", or "At Most" for too many values)
  if (std::regex_match(m, match,
                       std::regex("(\\S+): At (least|Most) (\\d+) required but received (\\d+)")))
    return fmt::format("{} takes {} {} comma-separated values (got {})", match[1].str(),
                       match[2].str() == "least" ? "at least" : "at most", match[3].str(),
                       match[4].str());
  if (std::regex_match(m, match, std::regex("([a-z]\\S*) is required")))
    return fmt::format("missing the {} argument", match[1].str());
  if (std::regex_match(m, match,
                       std::regex("The following arguments? (was|were) not expected: (.*)")))
    return fmt::format("unknown option or extra argument: {}", match[2].str());
  if (std::regex_match(m, match, std::regex("(.*): (.*) not in \\{(.*)\\}"))) {
    std::string choices = std::regex_replace(match[3].str(), std::regex(","), ", ");
    return fmt::format("{}: unknown value '{}' (choose one of {})", match[1].str(), match[2].str(),
                       choices);
  }
  if (std::regex_match(m, match, std::regex("INI was not able to parse (.*)"))) {
    std::string item = match[1].str();
    const auto dot = item.rfind('.');
    if (dot == std::string::npos)
      return fmt::format(
          "--config {}: unknown option '{}' (options of a subcommand go in its section, "
          "e.g. [smooth])",
          config_file, item);
    return fmt::format("--config {}: unknown option '{}' in section [{}]", config_file,
                       item.substr(dot + 1), item.substr(0, dot));
  }
  if (std::regex_match(m, match, std::regex("(.*) was not readable \\(missing\\?\\)")))
    return fmt::format("--config {}: cannot read the file (missing?)", match[1].str());
  if (m == "A subcommand is required")
    return "give a subcommand: generate, quality, convert, smooth, render or adapt";
  if (!m.empty()) m[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(m[0])));
  return m;
}

// The main help lists each subcommand with the first sentence of its description; the
// whole description is in `neomesh SUBCOMMAND --help`.
class Formatter : public CLI::Formatter {
 public:
  std::string make_subcommand(const CLI::App* sub) const override {
    std::string text = sub->get_description();
    text = text.substr(0, std::min({text.find(". "), text.find(".\n"), text.find(": ")}));
    if (!text.empty() && text.back() != '.') text += '.';
    std::stringstream out;
    CLI::detail::format_help(out, sub->get_name(), text, column_width_);
    return out.str();
  }
};

constexpr const char* kFooter = R"(Examples:
  neomesh generate square-midpoint --level 4 -o square.msh
  neomesh smooth square.msh -o smoothed.vtu --plot-history history.png   (.vtu: ParaView)
  neomesh smooth square.msh -o smoothed.msh && neomesh render smoothed.msh -o smoothed.png
  neomesh smooth in.msh -o out.msh --config run.toml --lambda 2

PETSc options: single-dash options that neomesh does not know go to PETSc, which runs
the linear solves. The quasi-Newton system has the prefix -hess_, the Riesz solve -riesz_:
  neomesh smooth in.msh -o out.msh -hess_ksp_monitor        (residuals of every CG solve)
  neomesh smooth in.msh -o out.msh -riesz_pc_type gamg      (PETSc's AMG instead of hypre)
An option that nothing used is reported as a warning at the end.

Config file (--config FILE, TOML or INI): the same options, long names without dashes,
a subcommand's options in its section; values given on the command line win:
  [smooth]
  lambda = 2
  linear-solver = "jacobi"

Parallel: mpiexec -n 4 neomesh smooth in.msh -o out.msh
Each subcommand has its own --help. User guide: docs/user-guide.md)";

}  // namespace

int run(int argc, char** argv) {
  SplitArguments args = split_arguments(argc, argv);

  CLI::App cli{
      "neomesh moves the vertices of a 2D/3D mesh (triangles, quadrilaterals, tetrahedra,\n"
      "hexahedra) so that its cells become well shaped and correctly sized, minimizing a\n"
      "Neo-Hookean energy; the connectivity never changes.",
      "neomesh"};
  cli.footer(kFooter);
  cli.formatter(std::make_shared<Formatter>());
  cli.set_version_flag("--version", std::string("neomesh ") + NEOMESH_VERSION,
                       "print the version and exit");
  cli.set_help_flag("-h,--help", "print this help and exit");
  cli.require_subcommand(1);
  // Inherited by the subcommands: a misspelled key in a config file is an error.
  cli.allow_config_extras(CLI::config_extras_mode::error);
  bool quiet = false, verbose = false;
  cli.add_flag("-q,--quiet", quiet, "print only the final summary and errors");
  cli.add_flag("-v,--verbose", verbose,
               "also print solver details: linear solver types, Krylov iterations per solve");
  cli.set_config("--config", "", "read options from a TOML/INI file (command line wins)")
      ->type_name("FILE");

  std::vector<Subcommand> commands = {add_generate(cli), add_quality(cli), add_convert(cli),
                                      add_smooth(cli),   add_render(cli),  add_adapt(cli)};
  for (auto& c : commands) {
    c.cli->fallthrough();
    c.cli->set_help_flag("-h,--help", "print this help and exit");
  }

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
    const CLI::App* command = nullptr;
    for (auto& c : commands)
      if (c.cli->parsed()) command = c.cli;
    const std::string help =
        command ? "neomesh " + command->get_name() + " --help" : "neomesh --help";
    std::fprintf(stderr, "neomesh: error: %s (see %s)\n",
                 describe_parse_error(e, args.neomesh, command).c_str(), help.c_str());
    return 2;
  }
  set_verbosity(quiet ? Verbosity::Quiet : verbose ? Verbosity::Verbose : Verbosity::Normal);

  try {
    PetscSession petsc(args.petsc);
    try {
      for (auto& c : commands)
        if (c.cli->parsed()) c.run();
      PetscSession::warn_unused_options();
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
