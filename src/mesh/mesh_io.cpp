#include "mesh/mesh_io.hpp"

#include "core/atomic_file.hpp"
#include "core/collective_error.hpp"
#include "mesh/gather.hpp"
#include "mesh/mesh_writers.hpp"

namespace neomesh {

bool is_exodus(const std::filesystem::path& path) {
  const auto ext = path.extension();
  return ext == ".exo" || ext == ".e" || ext == ".ex2";
}

void require_readable_format(const std::filesystem::path& path) {
  const auto ext = path.extension();
  if (ext != ".msh" && ext != ".xml" && ext != ".vtk" && ext != ".vtu" && ext != ".pvtu" &&
      ext != ".mesh" && ext != ".cgns" && !is_exodus(path))
    fail(
        "{}: unknown mesh format '{}' (neomesh reads Gmsh .msh, FEAT3 .xml, VTK legacy .vtk, "
        "VTK XML .vtu/.pvtu, Medit .mesh, Exodus II .exo/.e/.ex2 and CGNS .cgns)",
        path.string(), ext.string());
}

void require_writable_format(const std::filesystem::path& path) {
  const auto ext = path.extension();
  if (ext != ".msh" && ext != ".vtu" && ext != ".vtk" && ext != ".mesh" && ext != ".cgns" &&
      !is_exodus(path))
    fail(
        "{}: unknown output format '{}' (neomesh writes VTK .vtu and .vtk, Gmsh .msh, Medit "
        ".mesh, Exodus II .exo/.e/.ex2 and CGNS .cgns)",
        path.string(), ext.string());
}

void write_mesh(const PlexMesh& mesh, const std::filesystem::path& path, const MeshFields& fields) {
  require_writable_format(path);
  GatheredMesh gathered = gather_mesh(mesh, fields);
  make_room_for_data(gathered);
  on_root(mesh.comm(), [&] {
    const auto ext = path.extension();
    AtomicFile file(path, ext == ".vtu" || ext == ".cgns" || is_exodus(path));
    if (is_exodus(path))
      write_exodus(gathered, file.temporary_path(), path.string());
    else if (ext == ".cgns")
      write_cgns(gathered, file.temporary_path(), path.string());
    else if (ext == ".vtu")
      write_vtu(gathered, file.stream());
    else if (ext == ".vtk")
      write_vtk(gathered, file.stream());
    else if (ext == ".mesh")
      write_medit(gathered, file.stream());
    else
      write_msh(gathered, file.stream());
    file.commit();
  });
}

}  // namespace neomesh
