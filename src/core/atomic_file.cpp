#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstring>

#include "core/error.hpp"

namespace neomesh {

namespace {

// The temporary files open right now, where a signal handler can reach them without
// allocating: a slot is Free, being Filled, or holds a path that is Ready to unlink.
enum SlotState : int { Free, Filling, Ready };
constexpr int kSlots = 16;
constexpr std::size_t kMaxPath = 4096;
std::array<std::atomic<int>, kSlots> slot_state{};
std::array<std::array<char, kMaxPath>, kSlots> slot_path{};

int register_temporary(const std::filesystem::path& path) {
  const std::string& text = path.native();
  if (text.size() >= kMaxPath) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = Free;
    if (slot_state[i].compare_exchange_strong(expected, Filling)) {
      std::memcpy(slot_path[i].data(), text.c_str(), text.size() + 1);
      slot_state[i].store(Ready);
      return i;
    }
  }
  return -1;  // more than kSlots files at once: not cleaned up on a signal
}

void unregister_temporary(int slot) {
  if (slot >= 0) slot_state[slot].store(Free);
}

// The targets committed so far ("a.msh, r.json"), for the interrupt message, and whether a
// commit is between its rename and its record in that list right now.
std::array<char, kMaxPath> committed_list{};
std::atomic<std::size_t> committed_length{0};
std::atomic<bool> committing{false};
std::atomic<bool> stopping{false};  // a signal handler is removing the temporary files

void record_committed(const std::string& target) {
  std::size_t length = committed_length.load();
  const std::string entry = length == 0 ? target : ", " + target;
  if (length + entry.size() + 1 > committed_list.size()) return;  // the start is enough
  std::memcpy(committed_list.data() + length, entry.c_str(), entry.size() + 1);
  committed_length.store(length + entry.size());
}

// SIGINT and SIGTERM held back on this thread while a commit renames and records its file:
// the handler then never runs between the two on this thread (and waits on another).
class SignalsHeld {
 public:
  SignalsHeld() {
    sigset_t held;
    sigemptyset(&held);
    sigaddset(&held, SIGINT);
    sigaddset(&held, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &held, &previous_);
    committing.store(true);
  }
  ~SignalsHeld() {
    committing.store(false);
    pthread_sigmask(SIG_SETMASK, &previous_, nullptr);
  }
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;

 private:
  sigset_t previous_;
};

std::filesystem::path directory_of(const std::filesystem::path& target) {
  return target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
}

std::filesystem::path temporary_for(const std::filesystem::path& target) {
  return directory_of(target) / fmt::format(".{}.tmp-{}", target.filename().string(), getpid());
}

void check_directory(const std::filesystem::path& target) {
  if (std::filesystem::is_directory(target))
    fail("cannot write {}: it is a directory", target.string());
  const auto dir = directory_of(target);
  if (!std::filesystem::is_directory(dir))
    fail("cannot write {}: directory {} does not exist", target.string(), dir.string());
}

}  // namespace

void check_writable(const std::filesystem::path& target) {
  check_directory(target);
  const auto probe = temporary_for(target);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0)
    fail("cannot write {}: directory {} is not writable", target.string(),
         directory_of(target).string());
  ::close(fd);
  ::unlink(probe.c_str());
}

void remove_temporary_files() noexcept {
  // A commit either saw `stopping` and renames nothing, or finishes before the files go.
  stopping.store(true);
  const timespec pause{0, 1000000};  // 1 ms
  while (committing.load()) nanosleep(&pause, nullptr);
  for (int i = 0; i < kSlots; ++i)
    if (slot_state[i].load() == Ready) ::unlink(slot_path[i].data());
}

const char* committed_targets() noexcept {
  return committed_list.data();
}

AtomicFile::AtomicFile(const std::filesystem::path& target, bool binary) : target_(target) {
  check_directory(target);
  temporary_ = temporary_for(target);
  slot_ = register_temporary(temporary_);
  stream_.open(temporary_, binary ? std::ios::out | std::ios::binary : std::ios::out);
  if (!stream_) {
    unregister_temporary(slot_);
    fail("cannot write {}: directory {} is not writable", target.string(),
         directory_of(target).string());
  }
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  stream_.close();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
  unregister_temporary(slot_);
}

void AtomicFile::commit() {
  stream_.flush();
  if (!stream_) fail("writing {} failed (disk full?)", target_.string());
  stream_.close();
  std::error_code error;
  {
    const SignalsHeld held;
    if (stopping.load()) fail("interrupted before {} was written", target_.string());
    std::filesystem::rename(temporary_, target_, error);
    if (!error) {
      record_committed(target_.string());
      committed_ = true;
      unregister_temporary(slot_);
    }
  }
  if (error) fail("cannot write {}: {}", target_.string(), error.message());
}

}  // namespace neomesh
