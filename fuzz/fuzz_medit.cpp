// libFuzzer harness: read_medit on arbitrary bytes (see README.md).
#include "formats/medit_reader.hpp"
#include "fuzz_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return neomesh::fuzz::read_input(data, size, ".mesh",
                                   [](const auto& path) { neomesh::read_medit(path); });
}
