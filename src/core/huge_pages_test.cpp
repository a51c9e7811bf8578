#include "core/huge_pages.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace neomesh {
namespace {

// A /sys with the virtio devices given as (device id, feature string).
class FakeSys {
 public:
  FakeSys() {
    root_ = std::filesystem::temp_directory_path() /
            ("neomesh_sys_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
             "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(root_);
    std::filesystem::create_directories(root_ / "bus/virtio/devices");
  }
  ~FakeSys() { std::filesystem::remove_all(root_); }
  void add(const std::string& name, const std::string& id, const std::string& features) {
    const auto dir = root_ / "bus/virtio/devices" / name;
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "device") << id << "\n";
    std::ofstream(dir / "features") << features << "\n";
  }
  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path root_;
};

// The feature strings of this project's CI machine: a balloon with bits 1, 2 and 5
// (statistics, deflate on OOM, free page reporting), and a block device.
constexpr const char* kBalloonReporting = "0110010100000000000000000000000010000000";
constexpr const char* kBalloonWithout = "0110000100000000000000000000000010000000";
constexpr const char* kBlockDevice = "0010011001100100000000000000010010000000";

TEST(HugePages, AskedForUnlessTheBalloonReportsFreeMemory) {
  FakeSys sys;
  EXPECT_FALSE(reports_free_memory_to_host(sys.root()));  // no virtio device: bare metal
  // Bit 5 of a device that is not a balloon means something else.
  sys.add("virtio1", "0x0002", kBlockDevice);
  EXPECT_FALSE(reports_free_memory_to_host(sys.root()));
  sys.add("virtio0", "0x0005", kBalloonWithout);
  EXPECT_FALSE(reports_free_memory_to_host(sys.root()));
  sys.add("virtio0", "0x0005", kBalloonReporting);
  EXPECT_TRUE(reports_free_memory_to_host(sys.root()));
  EXPECT_FALSE(reports_free_memory_to_host(sys.root() / "missing"));
  EXPECT_STREQ(huge_pages_tunable(true), "glibc.malloc.hugetlb=0");
  EXPECT_STREQ(huge_pages_tunable(false), "glibc.malloc.hugetlb=1");
}

TEST(HugePages, AskedIsWhatGlibcWasToldToDo) {
  const char* saved = std::getenv("GLIBC_TUNABLES");
  const std::string before = saved ? saved : "";
  setenv("GLIBC_TUNABLES", "glibc.malloc.check=0:glibc.malloc.hugetlb=1", 1);
  EXPECT_TRUE(huge_pages_asked());
  setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=0", 1);
  EXPECT_FALSE(huge_pages_asked());
  unsetenv("GLIBC_TUNABLES");
  EXPECT_FALSE(huge_pages_asked());
  if (saved) setenv("GLIBC_TUNABLES", before.c_str(), 1);
}

}  // namespace
}  // namespace neomesh
