// The thesis' test meshes (docs/cases.md): a square whose midpoint moved, random quads, the
// transition element, the disc, triangles, and the boxes [-1,1]^d of every cell type that the
// adaptivity cases use. Mesh::generate builds one; `neomesh generate` is its command line.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include <neomesh/cell_type.hpp>

namespace neomesh {

// What GenerateOptions::size counts for a case.
enum class GeneratedSize {
  Cells,      // cells per direction, ≥ 1
  EvenCells,  // cells per direction, even and ≥ 2: a coarse 2×2(×2) mesh, each cell subdivided
  Refinements,  // uniform refinements of a coarse mesh, ≥ 0 (each makes 4× the cells, 2D)
};

struct GeneratedCase {
  std::string_view name;  // "square-midpoint", ...
  CellType type;          // of every cell
  GeneratedSize size;
};

// The cases, in the order of docs/cases.md:
//   square-midpoint  [0,1]², the centre of 2×2 quads moved to (0.26, 0.26) (thesis §5.2)
//   cube-midpoint    [0,2]³, the centre of 2×2×2 hexes moved to (1.2, 1.2, 1.2) (§5.8)
//   square-random    [0,1]² of quads, interior vertices moved at random by `amplitude` (§5.5)
//   transition       [0,1]², an inner quad and four trapezoids, refined (5·4^r quads, §5.6)
//   circle-quad      the unit disc, refined with the boundary on the circle (5·4^r quads)
//   triangle-equilateral  4^r equilateral triangles, half the interior vertices moved (§5.7)
//   triangle-curved  8·4^r triangles with curved sides (§5.7)
//   box-quad, box-tri, box-hex, box-tet, box-wedge, box-pyramid  [-1,1]^d (2 triangles per
//                    square; 6 tets, 2 wedges or 6 pyramids per cube)
//   annulus-quad, annulus-tri, annulus-hex, annulus-tet  the quarter annulus 1 ≤ r ≤ 2,
//                    0 ≤ θ ≤ π/2 (extruded to 0 ≤ z ≤ 1 in 3D): curved boundaries
std::span<const GeneratedCase> generated_cases();

// Which test mesh Mesh::generate builds (the same on every process).
struct GenerateOptions {
  std::string name = "box-quad";  // one of generated_cases()
  int size = 4;                   // what the case's GeneratedSize counts
  double amplitude = 0.2;         // square-random: largest move per coordinate, in cell widths
  unsigned seed = 1;              // square-random, triangle-equilateral and jitter
  // Box and annulus cases: interior vertices moved at random by up to this many cell widths
  // (radial widths for the annulus) per coordinate; from 0.25 on cells may fold over (a
  // tangled mesh, kept as it is).
  double jitter = 0.0;
  double rotate_degrees = 0.0;  // counter-clockwise about the origin (2D) or the z axis (3D)

  // Throws OptionError for a field out of range ("amplitude must be in [0, 0.25) (got 0.3)",
  // "jitter applies to the box and annulus cases", "name must be one of ...").
  void validate() const;
};

}  // namespace neomesh
