// libFuzzer harness: read_vtu on arbitrary bytes (see README.md).
#include "formats/vtu_reader.hpp"
#include "fuzz_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return neomesh::fuzz::read_input(data, size, ".vtu",
                                   [](const auto& path) { neomesh::read_vtu(path); });
}
