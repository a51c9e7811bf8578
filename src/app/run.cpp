#include "app/run.hpp"

#include <cctype>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <petscsys.h>
#include <unistd.h>

#include "app/method_options.hpp"
#include "app/subcommand.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/memory.hpp"
#include "core/petsc.hpp"

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

void write_stderr(const char* text) noexcept {
  (void)!write(STDERR_FILENO, text, std::strlen(text));
}

// Ctrl-C (SIGINT) or a kill (SIGTERM, also what mpiexec forwards): remove the temporary
// file being written, if any, say which outputs were already renamed into place (all or
// nothing each: see core/atomic_file.hpp), and die of the signal. Async-signal-safe.
extern "C" void on_interrupt(int signal) {
  remove_temporary_files();
  if (report_interrupt) {
    const char* written = committed_targets();
    if (*written == '\0') {
      write_stderr(
          "\nneomesh: interrupted; no output file was written (existing files are "
          "untouched)\n");
    } else {
      write_stderr("\nneomesh: interrupted; written completely before the interrupt: ");
      write_stderr(written);
      write_stderr("; no other output file was written\n");
    }
  }
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
    configure_singleton_mpi();
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

// Text between `prefix` and `suffix` if `m` is exactly prefix + text + suffix (no std::regex:
// its recursion overflows the stack on a value of 30,000 characters).
std::optional<std::string> between(const std::string& m, std::string_view prefix,
                                   std::string_view suffix) {
  if (m.size() < prefix.size() + suffix.size() || !m.starts_with(prefix) || !m.ends_with(suffix))
    return std::nullopt;
  return m.substr(prefix.size(), m.size() - prefix.size() - suffix.size());
}

// "a: b" split at the first (or last) ": ".
std::optional<std::pair<std::string, std::string>> split_at(const std::string& m,
                                                            std::string_view separator,
                                                            bool last = false) {
  const auto at = last ? m.rfind(separator) : m.find(separator);
  if (at == std::string::npos) return std::nullopt;
  return std::pair{m.substr(0, at), m.substr(at + separator.size())};
}

std::string describe_parse_error(const CLI::ParseError& e, const std::vector<std::string>& args,
                                 const CLI::App* command) {
  std::string config_file;
  for (std::size_t i = 1; i < args.size(); ++i)
    if (args[i - 1] == "--config") config_file = shorten(args[i], 200);
  std::string m = e.what();
  if (auto rest = between(m, "Could not convert: ", ""))
    if (auto parts = split_at(*rest, " = "))
      return fmt::format("{}: '{}' is not {}", shorten(parts->first), shorten(parts->second),
                         expected_value(command, parts->first));
  // --circle 1,2 (CLI11 says "At least 3 required", or "At Most" for too many values)
  if (auto parts = split_at(m, ": At "))
    for (std::string_view how : {"least", "Most"})
      if (auto counts = between(parts->second, std::string(how) + " ", ""))
        if (auto numbers = split_at(*counts, " required but received "))
          return fmt::format("{} takes {} {} comma-separated values (got {})",
                             shorten(parts->first), how == "least" ? "at least" : "at most",
                             numbers->first, numbers->second);
  if (auto option = between(m, "", " is required");
      option && !option->empty() && std::islower(static_cast<unsigned char>(option->front())) &&
      option->find(' ') == std::string::npos)
    return fmt::format("missing the {} argument", shorten(*option));
  for (std::string_view prefix :
       {"The following argument was not expected: ", "The following arguments were not expected: "})
    if (auto extra = between(m, prefix, ""))
      return fmt::format("unknown option or extra argument: {}", shorten(*extra));
  if (auto choices = between(m, "", "}"))
    if (auto parts = split_at(*choices, " not in {", true))
      if (auto option_value = split_at(parts->first, ": ")) {
        std::string list = parts->second;
        for (auto at = list.find(','); at != std::string::npos; at = list.find(',', at + 2))
          list.replace(at, 1, ", ");
        return fmt::format("{}: unknown value '{}' (choose one of {})",
                           shorten(option_value->first), shorten(option_value->second), list);
      }
  if (auto item = between(m, "INI was not able to parse ", "")) {
    const auto dot = item->rfind('.');
    if (dot == std::string::npos)
      return fmt::format(
          "--config {}: unknown option '{}' (options of a subcommand go in its section, "
          "e.g. [smooth])",
          config_file, shorten(*item));
    return fmt::format("--config {}: unknown option '{}' in section [{}]", config_file,
                       shorten(item->substr(dot + 1)), shorten(item->substr(0, dot)));
  }
  if (auto file = between(m, "", " was not readable (missing?)"))
    return fmt::format("--config {}: cannot read the file (missing?)", shorten(*file, 200));
  if (m == "A subcommand is required")
    return "give a subcommand: generate, quality, convert, curve, smooth, render or adapt";
  if (!m.empty()) m[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(m[0])));
  return shorten(m, 300);
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

// Every failure, a command line that cannot be parsed included: scripts test for non-zero,
// and the message says what went wrong.
constexpr int kFailure = 1;

// Open MPI's MPI_Abort without the banner that MPI_Abort prints first ("MPI_ABORT was invoked
// on rank 0 ... NOTE: invoking MPI_ABORT causes Open MPI to kill all MPI processes"): it ends
// every rank and mpiexec exits with the given code. Weak: absent with other MPI libraries.
extern "C" int ompi_mpi_abort(MPI_Comm comm, int errcode) __attribute__((weak));

// Started by a launcher (mpiexec, srun), even with one process.
bool launched_by_mpi() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(variable)) return true;
  return false;
}

// Ends every process of the job with exit code `code` and no further output.
[[noreturn]] void end_job(int code) {
  std::fflush(stdout);
  std::fflush(stderr);
  if (ompi_mpi_abort) ompi_mpi_abort(MPI_COMM_WORLD, code);
  MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);
}

enum class Agreed {
  AllRanks,      // every rank has the same error (CollectiveError, the command line)
  ThisRankOnly,  // the others may be waiting in a collective call for this one
};

// How a failed command ends: one line `neomesh: error: <message>` on stderr, exit code `code`.
// A serial run returns the code (PETSc finalizes as usual). Under mpiexec a process that
// exits with a non-zero code makes Open MPI print a banner of its own, and so does
// MPI_Abort, so the job is ended by end_job(): when every rank has the error, rank 0 prints
// it once every rank has unwound its stack (no temporary file left) and ends the job; an
// error of this rank only is printed by rank 0 at once, by another rank after a grace
// period (in which a rank 0 that failed the same way ends the job first, so the line is
// printed once).
int end_failed_command(const std::string& message, int code, Agreed agreed) {
  const std::string line = fmt::format("neomesh: error: {}\n", message);
  int size = 1, rank = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (size == 1 && !launched_by_mpi()) {
    std::fputs(line.c_str(), stderr);
    return code;
  }
  if (agreed == Agreed::AllRanks) {
    if (rank == 0) std::fputs(line.c_str(), stderr);
    std::fflush(stderr);
    // Every rank is here: wait for all (at most a few seconds, in case one is not).
    MPI_Request request;
    MPI_Ibarrier(MPI_COMM_WORLD, &request);
    int done = 0;
    for (int waited_ms = 0; !done && waited_ms < 10000; ++waited_ms) {
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
      if (!done) usleep(1000);
    }
    if (rank != 0) sleep(10);  // rank 0 ends the job meanwhile
    end_job(code);
  }
  if (rank != 0) sleep(3);
  std::fputs(line.c_str(), stderr);
  end_job(code);
}

}  // namespace

int run(int argc, char** argv) {
  keep_freed_memory();  // the whole program: before any thread allocates
  SplitArguments args = split_arguments(argc, argv);

  CLI::App cli{
      "neomesh moves the vertices of a 2D/3D mesh (triangles, quadrilaterals, tetrahedra,\n"
      "hexahedra, wedges, pyramids) so that its cells become well shaped and correctly sized,\n"
      "minimizing a Neo-Hookean energy; the connectivity never changes.",
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
                                      add_curve(cli),    add_smooth(cli),  add_render(cli),
                                      add_adapt(cli)};
  for (auto& c : commands) {
    c.cli->fallthrough();
    c.cli->set_help_flag("-h,--help", "print this help and exit");
  }

  // MPI first: under mpiexec every rank parses the same command line, and rank 0 alone
  // prints help, errors and results.
  std::optional<PetscSession> petsc;
  try {
    petsc.emplace(args.petsc);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "neomesh: error: %s\n", user_message(e).c_str());
    return 1;
  }

  try {
    std::vector<std::string> reversed(args.neomesh.rbegin(), args.neomesh.rend() - 1);
    cli.parse(std::move(reversed));
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {  // --help, --version
      std::ostringstream ignored;
      const bool root = is_root_rank();
      return cli.exit(e, root ? std::cout : ignored, root ? std::cerr : ignored);
    }
    const CLI::App* command = nullptr;
    for (auto& c : commands)
      if (c.cli->parsed()) command = c.cli;
    const std::string help =
        command ? "neomesh " + command->get_name() + " --help" : "neomesh --help";
    // The same command line on every rank: every rank found the same error.
    return end_failed_command(
        fmt::format("{} (see {})", describe_parse_error(e, args.neomesh, command), help), kFailure,
        Agreed::AllRanks);
  }
  set_verbosity(quiet ? Verbosity::Quiet : verbose ? Verbosity::Verbose : Verbosity::Normal);

  try {
    for (auto& c : commands)
      if (c.cli->parsed()) c.run();
    PetscSession::warn_unused_options();
  } catch (const CollectiveError& e) {
    return end_failed_command(cli_message(e.what()), kFailure, Agreed::AllRanks);
  } catch (const std::exception& e) {
    return end_failed_command(cli_message(user_message(e)), kFailure, Agreed::ThisRankOnly);
  }
  return 0;
}

}  // namespace neomesh::app
