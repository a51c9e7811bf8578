// libFuzzer harness: read_gmsh on arbitrary bytes (see README.md).
#include "formats/gmsh_reader.hpp"
#include "fuzz_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return neomesh::fuzz::read_input(data, size, ".msh",
                                   [](const auto& path) { neomesh::read_gmsh(path); });
}
