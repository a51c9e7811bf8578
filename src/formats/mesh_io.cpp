#include "formats/mesh_io.hpp"

#include <fstream>

#include "core/atomic_file.hpp"
#include "core/collective_error.hpp"
#include "formats/cgns_reader.hpp"
#include "formats/exodus_reader.hpp"
#include "formats/feat_reader.hpp"
#include "formats/gmsh_reader.hpp"
#include "formats/input_file.hpp"
#include "formats/medit_reader.hpp"
#include "formats/mesh_writers.hpp"
#include "formats/vtk_reader.hpp"
#include "formats/vtu_reader.hpp"
#include "mesh/gather.hpp"
#include "mesh/input_mesh.hpp"

namespace neomesh {

namespace {

void check_input_file(const std::filesystem::path& path) {
  check_regular_file(path);  // before opening it: a FIFO with no writer would block forever
  std::error_code ec;
  if (!std::ifstream(path)) fail("{}: cannot be opened for reading", path.string());
  if (std::filesystem::file_size(path, ec) == 0) fail("{}: the file is empty", path.string());
}

}  // namespace

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

namespace {

InputMesh read_input(const std::filesystem::path& path) {
  check_input_file(path);
  require_readable_format(path);
  const auto ext = path.extension();
  return ext == ".msh"     ? read_gmsh(path)
         : ext == ".vtk"   ? read_vtk(path)
         : ext == ".vtu"   ? read_vtu(path)
         : ext == ".pvtu"  ? read_pvtu(path)
         : ext == ".mesh"  ? read_medit(path)
         : is_exodus(path) ? read_exodus(path)
         : ext == ".cgns"  ? read_cgns(path)
                           : input_from_data(read_feat(path));
}

}  // namespace

PlexMesh load_mesh(const std::filesystem::path& path, MPI_Comm comm, bool keep_inverted) {
  return load_mesh(std::vector<std::filesystem::path>{path}, comm, keep_inverted);
}

PlexMesh load_mesh(const std::vector<std::filesystem::path>& paths, MPI_Comm comm,
                   bool keep_inverted, const std::function<void(InputMesh&)>& prepare) {
  InputMesh input;
  std::string source;
  for (const auto& path : paths) source += (source.empty() ? "" : " + ") + path.string();
  on_root(comm, [&] {
    if (paths.size() == 1) {
      input = read_input(paths[0]);
    } else {
      for (const auto& path : paths) {
        check_input_file(path);
        if (path.extension() != ".xml")
          fail("{}: only FEAT3 .xml meshes are read together with other files (chart files)",
               path.string());
      }
      input = input_from_data(read_feat(paths));
    }
    if (prepare) prepare(input);
  });
  return PlexMesh::from_input(input, source, comm, keep_inverted);
}

void write_mesh(const PlexMesh& mesh, const std::filesystem::path& path, const MeshFields& fields) {
  require_writable_format(path);
  const auto extension = path.extension();
  GatheredMesh gathered = gather_mesh(mesh, fields);
  make_room_for_data(gathered);
  on_root(mesh.comm(), [&] {
    const auto ext = path.extension();
    if (ext == ".mesh") require_medit_curved_types(gathered.mesh, path.string());
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
