// Reading a whole input file into memory, for the readers. Only regular files: a FIFO with no
// writer would block forever and /dev/zero would never end, so both are refused before they
// are opened.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace neomesh {

// Throws Error "<file>: is not a regular file" (FIFO, device, socket, directory), "... no such
// file" or "... cannot be read".
void check_regular_file(const std::filesystem::path& path);

// Memory for large buffers in transparent huge pages where the system allows it (Linux with
// transparent_hugepage "madvise"): filling 87 MB of fresh 4 KiB pages cost more page faults
// than the parsing of a 1M-cell mesh. Small buffers come from malloc.
void* allocate_large(std::size_t bytes);
void free_large(void* p) noexcept;

template <typename T>
struct LargeBufferAllocator {
  using value_type = T;
  LargeBufferAllocator() = default;
  template <typename U>
  LargeBufferAllocator(const LargeBufferAllocator<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocate_large(n * sizeof(T))); }
  void deallocate(T* p, std::size_t) noexcept { free_large(p); }
  template <typename U>
  bool operator==(const LargeBufferAllocator<U>&) const {
    return true;
  }
};

using InputText = std::basic_string<char, std::char_traits<char>, LargeBufferAllocator<char>>;

// A piece of an input file for a message, on one line: its first `max` characters (then
// "..."), each that is not printable as '?'.
std::string shown_text(std::string_view text, std::size_t max);

// The file's bytes, after check_regular_file.
InputText read_input_file(const std::filesystem::path& path);

}  // namespace neomesh
