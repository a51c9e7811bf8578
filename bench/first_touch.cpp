// Cost of the first touch of fresh memory: the page faults and the zeroing behind them, with
// 4 KiB pages and with transparent huge pages (madvise, as neomesh's launcher asks glibc to),
// and what the same memory costs once faulted in. neomesh's large arrays (the matrices, the
// vectors) are touched first while they are set up, so this is a floor of every run's set-up
// (docs/benchmarks.md, "Huge pages").
//
//   first_touch [MiB=200] [pause seconds=5] [repeats=3]
//
// Before each allocation it sleeps `pause` seconds: a VM that reports free memory to its host
// (virtio-balloon free page reporting) has then handed the freed blocks back, as between two
// runs of neomesh; 0 measures back-to-back allocations.
#include <omp.h>
#include <sys/mman.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// Zeroes `bytes` of fresh memory with `threads` threads (64 KiB per piece); returns the time
// of that first touch and of a second pass over the same, faulted-in memory.
void touch(std::size_t bytes, bool huge, int threads, double& first, double& again) {
  char* p = static_cast<char*>(std::aligned_alloc(kHugePage, bytes));
  if (!p) std::abort();
  if (huge) madvise(p, bytes, MADV_HUGEPAGE);
  constexpr std::size_t kPiece = std::size_t{1} << 16;
  const long pieces = static_cast<long>(bytes / kPiece);
  for (int pass = 0; pass < 2; ++pass) {
    const auto start = std::chrono::steady_clock::now();
#pragma omp parallel for num_threads(threads) schedule(static)
    for (long k = 0; k < pieces; ++k) std::memset(p + k * kPiece, pass, kPiece);
    (pass == 0 ? first : again) = milliseconds_since(start);
  }
  std::free(p);
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t mib = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 200;
  const double pause = argc > 2 ? std::strtod(argv[2], nullptr) : 5.0;
  const int repeats = argc > 3 ? std::atoi(argv[3]) : 3;
  const std::size_t bytes = (mib << 20) / kHugePage * kHugePage;
  std::printf("| pages | threads | first touch of %zu MiB, ms | again, ms |\n|---|---:|---|---|\n",
              mib);
  for (int huge = 0; huge < 2; ++huge)
    for (int threads = 1; threads <= 2; ++threads) {
      std::printf("| %s | %d |", huge ? "huge (madvise)" : "4 KiB", threads);
      double again_min = 1e300;
      for (int r = 0; r < repeats; ++r) {
        usleep(static_cast<useconds_t>(pause * 1e6));
        double first = 0.0, again = 0.0;
        touch(bytes, huge, threads, first, again);
        std::printf(" %.0f", first);
        if (again < again_min) again_min = again;
      }
      std::printf(" | %.0f |\n", again_min);
    }
}
