#include <neomesh/generate.hpp>

#include <array>
#include <cmath>
#include <string>

#include <neomesh/error.hpp>
#include <neomesh/mesh.hpp>

#include "core/memory.hpp"
#include "core/petsc.hpp"
#include "generate/generate.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh {

namespace {

// A case with the generator that builds it from its size (rank 0 only), and the width of the
// domain across the lattice's first direction (0: not a lattice), which jitter divides by the
// cells per direction.
struct Generator {
  GeneratedCase what;
  MeshData (*make)(int size, const GenerateOptions& options);
  double lattice_width = 0.0;
};

template <CellType Type>
MeshData make_box(int n, const GenerateOptions&) {
  return box(Type, n);
}
template <CellType Type>
MeshData make_annulus(int n, const GenerateOptions&) {
  return quarter_annulus(Type, n);
}

constexpr std::array<Generator, 17> kGenerators = {{
    {{"square-midpoint", CellType::Quadrilateral, GeneratedSize::EvenCells},
     [](int n, const GenerateOptions&) { return square_midpoint(n); }},
    {{"cube-midpoint", CellType::Hexahedron, GeneratedSize::EvenCells},
     [](int n, const GenerateOptions&) { return cube_midpoint(n); }},
    {{"square-random", CellType::Quadrilateral, GeneratedSize::Cells},
     [](int n, const GenerateOptions& o) { return square_random(n, o.amplitude, o.seed); }},
    {{"transition", CellType::Quadrilateral, GeneratedSize::Refinements},
     [](int r, const GenerateOptions&) { return transition(r); }},
    {{"circle-quad", CellType::Quadrilateral, GeneratedSize::Refinements},
     [](int r, const GenerateOptions&) { return circle_quad(r); }},
    {{"triangle-equilateral", CellType::Triangle, GeneratedSize::Refinements},
     [](int r, const GenerateOptions& o) { return triangle_equilateral(r, o.seed); }},
    {{"triangle-curved", CellType::Triangle, GeneratedSize::Refinements},
     [](int r, const GenerateOptions&) { return triangle_curved(r); }},
    {{"box-quad", CellType::Quadrilateral, GeneratedSize::Cells},
     make_box<CellType::Quadrilateral>,
     2.0},
    {{"box-tri", CellType::Triangle, GeneratedSize::Cells}, make_box<CellType::Triangle>, 2.0},
    {{"box-hex", CellType::Hexahedron, GeneratedSize::Cells}, make_box<CellType::Hexahedron>, 2.0},
    {{"box-tet", CellType::Tetrahedron, GeneratedSize::Cells},
     make_box<CellType::Tetrahedron>,
     2.0},
    {{"box-wedge", CellType::Wedge, GeneratedSize::Cells}, make_box<CellType::Wedge>, 2.0},
    {{"box-pyramid", CellType::Pyramid, GeneratedSize::Cells}, make_box<CellType::Pyramid>, 2.0},
    {{"annulus-quad", CellType::Quadrilateral, GeneratedSize::Cells},
     make_annulus<CellType::Quadrilateral>,
     1.0},
    {{"annulus-tri", CellType::Triangle, GeneratedSize::Cells},
     make_annulus<CellType::Triangle>,
     1.0},
    {{"annulus-hex", CellType::Hexahedron, GeneratedSize::Cells},
     make_annulus<CellType::Hexahedron>,
     1.0},
    {{"annulus-tet", CellType::Tetrahedron, GeneratedSize::Cells},
     make_annulus<CellType::Tetrahedron>,
     1.0},
}};

constexpr std::array<GeneratedCase, kGenerators.size()> kCases = [] {
  std::array<GeneratedCase, kGenerators.size()> cases{};
  for (std::size_t i = 0; i < kGenerators.size(); ++i) cases[i] = kGenerators[i].what;
  return cases;
}();

const Generator* find_generator(const std::string& name) {
  for (const Generator& g : kGenerators)
    if (g.what.name == name) return &g;
  return nullptr;
}

void check_size(const GeneratedCase& c, int size) {
  switch (c.size) {
    case GeneratedSize::Cells:
      if (size < 1) throw OptionError("size", fmt::format("must be >= 1 (got {})", size));
      return;
    case GeneratedSize::EvenCells:
      if (size < 2 || size % 2 != 0)
        throw OptionError("size", fmt::format("must be even and >= 2 (got {})", size));
      return;
    case GeneratedSize::Refinements:
      if (size < 0) throw OptionError("size", fmt::format("must be >= 0 (got {})", size));
      return;
  }
}

}  // namespace

std::span<const GeneratedCase> generated_cases() {
  return kCases;
}

void GenerateOptions::validate() const {
  const Generator* generator = find_generator(name);
  if (!generator) {
    std::string names;
    for (const GeneratedCase& c : kCases)
      names += fmt::format("{}{}", names.empty() ? "" : ", ", c.name);
    throw OptionError("name", fmt::format("must be one of {} (got '{}')", names, name));
  }
  check_size(generator->what, size);
  if (!std::isfinite(rotate_degrees))
    throw OptionError("rotate_degrees",
                      fmt::format("must be a finite number, in degrees (got {})", rotate_degrees));
  if (!(amplitude >= 0.0 && amplitude < 0.25))
    throw OptionError("amplitude", fmt::format("must be in [0, 0.25) (got {})", amplitude));
  if (jitter != 0.0 && generator->lattice_width == 0.0)
    throw OptionError("jitter", "applies to the box and annulus cases");
  if (!(jitter >= 0.0 && jitter < 1.0))
    throw OptionError("jitter", fmt::format("must be in [0, 1) (got {})", jitter));
}

Mesh Mesh::generate(const GenerateOptions& options, MPI_Comm comm) {
  options.validate();
  const Generator& generator = *find_generator(options.name);
  const double before = resident_bytes();
  MeshData data;
  if (mpi_rank(comm) == 0) {
    data = generator.make(options.size, options);
    if (options.jitter > 0.0)
      jitter(data, generator.lattice_width / options.size, options.jitter, options.seed);
    if (options.rotate_degrees != 0.0) rotate(data, options.rotate_degrees);
  }
  return Mesh(std::make_unique<PlexMesh>(
                  PlexMesh::from_data(data, options.name, comm, /*keep_inverted=*/true)),
              before);
}

}  // namespace neomesh
