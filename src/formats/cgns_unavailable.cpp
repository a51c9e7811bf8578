// CGNS in a build without the CGNS library (cmake -DNEOMESH_CGNS=OFF; see
// CMakeLists.txt): .cgns files are refused in one line.
#include "core/error.hpp"
#include "formats/cgns_reader.hpp"
#include "formats/mesh_writers.hpp"

namespace neomesh {

InputMesh read_cgns(const std::filesystem::path& path) {
  fail("{}: this neomesh was built without CGNS (cmake -DNEOMESH_CGNS=ON)", path.string());
}

void write_cgns(const GatheredMesh&, const std::filesystem::path&, const std::string& target) {
  fail("{}: this neomesh was built without CGNS (cmake -DNEOMESH_CGNS=ON)", target);
}

}  // namespace neomesh
