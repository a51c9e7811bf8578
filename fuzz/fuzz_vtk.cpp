// libFuzzer harness: read_vtk on arbitrary bytes (see README.md).
#include "formats/vtk_reader.hpp"
#include "fuzz_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return neomesh::fuzz::read_input(data, size, ".vtk",
                                   [](const auto& path) { neomesh::read_vtk(path); });
}
