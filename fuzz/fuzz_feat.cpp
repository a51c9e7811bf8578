// libFuzzer harness: read_feat on arbitrary bytes (see README.md).
#include "formats/feat_reader.hpp"
#include "fuzz_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return neomesh::fuzz::read_input(data, size, ".xml",
                                   [](const auto& path) { neomesh::read_feat(path); });
}
