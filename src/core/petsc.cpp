#include "core/petsc.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

namespace neomesh {

void check_petsc(PetscErrorCode code, const char* call, const char* file, int line) {
  if (code == 0) return;
  const char* text = nullptr;
  char* specific = nullptr;
  PetscErrorMessage(code, &text, &specific);
  // PETSc's specific message first ("Unable to find requested KSP type foo"): it is the
  // one a user can act on; the call and place are for bug reports.
  const std::string where =
      fmt::format("{} at {}:{}", call, std::filesystem::path(file).filename().string(), line);
  if (specific && *specific)
    throw Error(fmt::format("PETSc: {} ({}; in {})", specific, text ? text : "", where));
  throw Error(
      fmt::format("PETSc error {}: {} (in {})", static_cast<int>(code), text ? text : "", where));
}

VecReadView::VecReadView(Vec v) : vec_(v) {
  NM_PETSC(VecGetLocalSize(v, &size_));
  NM_PETSC(VecGetArrayRead(v, &data_));
}
VecReadView::~VecReadView() {
  VecRestoreArrayRead(vec_, &data_);
}

VecWriteView::VecWriteView(Vec v) : vec_(v) {
  NM_PETSC(VecGetLocalSize(v, &size_));
  NM_PETSC(VecGetArray(v, &data_));
}
VecWriteView::~VecWriteView() {
  VecRestoreArray(vec_, &data_);
}

int mpi_rank(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}
int mpi_size(MPI_Comm comm) {
  int s = 1;
  MPI_Comm_size(comm, &s);
  return s;
}

Mat maij_scalar(Mat m) {
  PetscBool maij = PETSC_FALSE;
  NM_PETSC(PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(m), &maij, MATSEQMAIJ,
                                     MATMPIMAIJ, ""));
  if (!maij) return nullptr;
  Mat scalar = nullptr;
  NM_PETSC(MatMAIJGetAIJ(m, &scalar));
  return scalar;
}

// A run not started by mpiexec initializes Open MPI as a singleton, which by default starts a
// daemon and probes the UCX network transports: most of the wall time of a small run
// (docs/benchmarks.md, "Start-up"). One process needs neither, so unless the user set them,
// a singleton skips the daemon and uses the plain point-to-point layer. Nor does it need the
// I/O devices that hwloc's topology probe lists for Open MPI (network cards' locality): reading
// every PCI device's configuration space was 7 of MPI_Init's 18 ms here. Under mpiexec nothing
// changes.
//
// Nor does one process need most of the components Open MPI opens at MPI_Init (~50 shared
// objects: network and shared-memory transports, tuned collectives, the daemon's state
// machines), each dlopen'ed and its symbols resolved: the loopback transport, the collectives
// for one process (self, basic, and libnbc for PETSc's non-blocking ones) and the application's
// state machine do, 15 of 260 M instructions of `neomesh --version` fewer
// (docs/benchmarks.md, "Start-up").
//
// Isolated singletons all put their session directory at jf.0 under the same top directory,
// and one that ends removes it while another starts in it ("A call to mkdir was unable to
// create the desired directory ... orte_session_dir failed": 2 of 316 tests under ctest -j2
// next to other test runs). So each singleton gets a top directory of its own,
// neomesh-mpi-<pid>-XXXXXX, removed at exit; a run killed by a signal cannot remove its own,
// so every singleton also removes those of processes that no longer exist.
namespace {

void remove_stale_session_directories(const std::filesystem::path& tmp) {
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(tmp, error)) {
    const std::string name = entry.path().filename().string();
    constexpr std::string_view prefix = "neomesh-mpi-";
    if (!name.starts_with(prefix)) continue;
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    if (pid > 0 && kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
      std::filesystem::remove_all(entry.path(), error);
  }
}

}  // namespace

void configure_singleton_mpi() {
  for (const char* launched : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(launched)) return;
  setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
  setenv("OMPI_MCA_pml", "ob1", 0);
  setenv("OMPI_MCA_btl", "self", 0);
  setenv("OMPI_MCA_coll", "self,basic,libnbc", 0);
  setenv("OMPI_MCA_state", "app", 0);
  setenv("OMPI_MCA_errmgr", "default_app", 0);
  setenv("OMPI_MCA_schizo", "orte", 0);
  setenv("OMPI_MCA_reachable", "weighted", 0);
  setenv("OMPI_MCA_shmem", "mmap", 0);
  setenv("HWLOC_COMPONENTS", "-pci,-linuxio", 0);
  if (std::getenv("OMPI_MCA_orte_tmpdir_base")) return;
  static std::string session_base;
  const char* tmp = std::getenv("TMPDIR");
  const std::string tmp_dir = tmp && *tmp ? tmp : "/tmp";
  remove_stale_session_directories(tmp_dir);
  std::string pattern = tmp_dir + "/neomesh-mpi-" + std::to_string(getpid()) + "-XXXXXX";
  if (!mkdtemp(pattern.data())) return;  // Open MPI's default then
  session_base = pattern;
  setenv("OMPI_MCA_orte_tmpdir_base", session_base.c_str(), 1);
  std::atexit([] {
    std::error_code ignored;
    std::filesystem::remove_all(session_base, ignored);
  });
}

OwnedVec copy_of(Vec v) {
  OwnedVec copy;
  NM_PETSC(VecDuplicate(v, copy.out()));
  NM_PETSC(VecCopy(v, copy));
  return copy;
}

}  // namespace neomesh
