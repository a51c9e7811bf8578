// The `neomesh` command: starts the command line proper (neomesh-main, beside it in a build
// tree, in libexec/neomesh once installed) with glibc's transparent huge pages for large
// allocations. Its matrices' arrays are tens to hundreds of MB, first touched page by page;
// with 4 KiB pages the page faults cost 15-25% of a run (docs/benchmarks.md, "Huge pages").
// Not on a virtual machine that reports free memory to its host: there a huge page costs more
// than the 4 KiB pages it replaces (core/huge_pages.hpp), and the tunable is set to 0. glibc
// reads it only when a process starts, hence this separate, dependency-free program:
// re-executing neomesh-main itself would load its libraries twice (80 ms). A GLIBC_TUNABLES that
// already names glibc.malloc.hugetlb is left as it is.
//
// It also sets OMP_WAIT_POLICY=PASSIVE unless the user set a policy: OpenMP threads (neomesh's,
// hypre's, OpenBLAS's) that wait by spinning make a run 5-30x slower when another process holds
// a core (a shared workstation, a cluster node with other jobs), while sleeping costs a quiet
// machine nothing measurable (docs/benchmarks.md, "Threads and a shared machine"). libgomp
// reads the variable when it is loaded, so it has to be set before neomesh-main starts.
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/huge_pages.hpp"

int main(int, char** argv) {
  constexpr const char* kTunable = "glibc.malloc.hugetlb";
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string before = tunables ? tunables : "";
  if (before.find(kTunable) == std::string::npos)
    setenv("GLIBC_TUNABLES",
           ((before.empty() ? "" : before + ":") +
            neomesh::huge_pages_tunable(neomesh::reports_free_memory_to_host()))
               .c_str(),
           1);

  setenv("OMP_WAIT_POLICY", "PASSIVE", /*overwrite=*/0);

  std::string self(4096, '\0');
  const ssize_t length = readlink("/proc/self/exe", self.data(), self.size());
  if (length <= 0) {
    std::fprintf(stderr, "neomesh: error: cannot find its own path: %s\n", std::strerror(errno));
    return 1;
  }
  self.resize(static_cast<std::size_t>(length));
  const std::string dir = self.substr(0, self.rfind('/'));
  std::string tried;
  for (const std::string& program :
       {dir + "/neomesh-main", dir + "/../libexec/neomesh/neomesh-main"}) {
    execv(program.c_str(), argv);  // returns only on failure
    tried += (tried.empty() ? "" : ", ") + program + " (" + std::strerror(errno) + ")";
  }
  std::fprintf(stderr, "neomesh: error: cannot start the command line: %s\n", tried.c_str());
  return 1;
}
