#include "core/memory.hpp"

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string>

namespace neomesh {

namespace {

constexpr double kKiB = 1024.0, kMiB = 1024.0 * kKiB;

// One process, one run's memory: the peak it expects, and what it faulted in for it.
double expected_peak = 0.0;
double kept = 0.0;

// The first number in `path` (bytes), or +∞ if there is none ("max", no such file).
double number_in(const char* path) {
  std::ifstream in(path);
  double value = 0;
  return in >> value ? value : std::numeric_limits<double>::infinity();
}

double mem_available() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kib = 0;
  while (in >> key >> kib) {
    if (key == "MemAvailable:") return kib * kKiB;
    in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace

double available_bytes() {
  if (const char* given = std::getenv("NEOMESH_MEMORY_AVAILABLE_MIB"))
    return std::atof(given) * kMiB;
  const double limit = number_in("/sys/fs/cgroup/memory.max");  // +∞ for "max"
  const double used = number_in("/sys/fs/cgroup/memory.current");
  return std::min(mem_available(), std::isfinite(used) ? limit - used : limit);
}

double resident_bytes() {
  std::ifstream in("/proc/self/statm");  // sizes in pages: total, resident, ...
  double total = 0, resident = 0;
  if (!(in >> total >> resident)) return 0.0;
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

void expect_peak(double bytes) {
  expected_peak = bytes;
}

double spare_bytes() {
  return available_bytes() - std::max(0.0, expected_peak - resident_bytes());
}

void keep_freed_memory() {
  mallopt(M_MMAP_MAX, 0);         // large blocks from the heap too, not from mmap
  mallopt(M_TRIM_THRESHOLD, -1);  // and the heap never shrinks
  mallopt(M_ARENA_MAX, 1);        // one heap for every thread
}

void keep_and_fault_in(double bytes) {
  keep_freed_memory();
  if (!(bytes >= 1.0)) return;
  const auto size = static_cast<std::size_t>(bytes);
  char* block = static_cast<char*>(std::malloc(size));
  if (!block) return;
  const std::ptrdiff_t page = sysconf(_SC_PAGESIZE);
  const std::ptrdiff_t pages = static_cast<std::ptrdiff_t>(size) / page;
  volatile char* touch = block;  // stores into a block about to be freed are otherwise dropped
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < pages; ++i) touch[i * page] = 0;
  std::free(block);  // back to the top of the heap, faulted in
  kept += static_cast<double>(size);
}

double kept_bytes() {
  return kept;
}

}  // namespace neomesh
