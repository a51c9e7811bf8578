// Whether neomesh's large arrays should ask for transparent huge pages. On most machines they
// should: the first touch of fresh memory costs a page fault and the zeroing of each page, and
// a 2 MiB page is faulted and zeroed in one go (200 MiB: 20 ms against 110 ms with 4 KiB
// pages, bench/first_touch). But a virtual machine whose balloon device reports free memory to
// its host (virtio-balloon free page reporting) hands every free 2 MiB block back to the host,
// so that a huge page is then new host memory, faulted in again at the host: 450-500 ms for
// the same 200 MiB, while 4 KiB pages mostly come from smaller free blocks it keeps
// (docs/benchmarks.md, "Huge pages"). Header-only: the launcher (src/launcher.cpp) has no
// dependencies.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace neomesh {

// True if a virtio balloon device (device id 0x0005) under `sys` (/sys) offers free page
// reporting (feature bit 5, VIRTIO_BALLOON_F_REPORTING, in the driver's feature string).
inline bool reports_free_memory_to_host(const std::filesystem::path& sys = "/sys") {
  constexpr std::size_t kReportingBit = 5;
  std::error_code ec;
  std::filesystem::directory_iterator devices(sys / "bus/virtio/devices", ec);
  if (ec) return false;
  for (const auto& device : devices) {
    std::string id, features;
    std::ifstream(device.path() / "device") >> id;
    std::ifstream(device.path() / "features") >> features;
    if (id == "0x0005" && features.size() > kReportingBit && features[kReportingBit] == '1')
      return true;
  }
  return false;
}

// The GLIBC_TUNABLES setting the launcher adds when the user's environment names none.
inline const char* huge_pages_tunable(bool reports_free_memory) {
  return reports_free_memory ? "glibc.malloc.hugetlb=0" : "glibc.malloc.hugetlb=1";
}

// Whether this process was started asking glibc for huge pages (by the launcher or the user):
// the arrays neomesh allocates itself follow the same choice.
inline bool huge_pages_asked() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  return tunables && std::string(tunables).find("glibc.malloc.hugetlb=1") != std::string::npos;
}

}  // namespace neomesh
