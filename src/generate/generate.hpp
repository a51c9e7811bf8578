// The thesis' test meshes (docs/cases.md, thesis chapters 5 and 6) as MeshData.
//
// Every generator returns cells in canonical local order (cell_type.hpp), all positively
// oriented, and names the sides of its boundary as VertexSets with distinct tags:
// "left"/"right" (x min/max), "bottom"/"top" (y), "front"/"back" (z) for boxes, "circle"
// for the disc, the three sides of the triangle, the four curves of the curved triangle mesh.
//
// Levels: the functions take what they build (cells per direction or refinements); the
// thesis' level conventions are the command line's business (app/generate.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/mesh_data.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

// [0,1]²: 2×2 quads with the centre vertex moved to (0.26, 0.26), each coarse quad
// subdivided as the bilinear image of a uniform (n/2)×(n/2) grid (thesis §5.2). n even ≥ 2;
// n = 16 is the mesh of Table 5.1 (thesis level 3).
MeshData square_midpoint(int cells_per_direction);

// [0,2]³: 2×2×2 hexes with the centre moved to (1.2, 1.2, 1.2), each coarse hex subdivided
// as the trilinear image of a uniform (n/2)³ grid (thesis §5.8). n even ≥ 2.
MeshData cube_midpoint(int cells_per_direction);

// Uniform n×n quads on [0,1]² whose interior vertices are displaced by up to
// amplitude·h (h = 1/n) in each coordinate, uniformly at random (thesis §5.5). Deterministic
// for a seed on every platform. 0 ≤ amplitude < 1/4 keeps every cell convex.
MeshData square_random(int cells_per_direction, double amplitude, unsigned seed);

// The "transition element" (thesis §5.6): [0,1]² split into the inner quad [1/4,3/4]² and
// four trapezoids, then refined uniformly `refinements` times: 5·4^r quads.
MeshData transition(int refinements);

// The unit disc (thesis §5.6 "Unitcircle", FEAT3's unit-circle-quad): the square core with
// corners (±1/2, 0), (0, ±1/2) and four trapezoids out to (±1, 0), (0, ±1), refined
// uniformly `refinements` times; after each refinement the new boundary vertices are
// projected radially onto the circle. 5·4^r quads.
MeshData circle_quad(int refinements);

// The equilateral triangle (0,0), (1,0), (1/2, √3/2) refined regularly `refinements` times
// into 4^r equilateral triangles; then each interior vertex, with probability 1/2, is moved
// by up to h/5 (h = 2^-r, the edge length) in each coordinate (thesis §5.7).
MeshData triangle_equilateral(int refinements, unsigned seed);

// The curved triangle mesh of thesis §5.7 "Nontrivial triangle mesh", built like FEAT3's
// unit-axe-tria: eight triangles on [0,1]² whose four sides are cubic Bézier curves from
// corner to corner with control points (1/4,-1/4), (3/4,-1/4) (bottom, bulging out),
// (3/4,1/4), (3/4,3/4) (right, bulging in), (3/4,5/4), (1/4,5/4) (top, out), (1/4,3/4),
// (1/4,1/4) (left, in). Refined `refinements` times; each new boundary vertex is placed on
// its curve at the mean parameter of its edge's end points. 8·4^r triangles; the mesh is
// symmetric under the point reflection about (1/2, 1/2).
MeshData triangle_curved(int refinements);

// [-1,1]^d with n cells per direction: quads, triangles (each square split along the
// diagonal through its lower left corner), hexes or tets (each cube split into the six
// tets around its diagonal from (-,-,-) to (+,+,+), so neighbouring cubes' faces match),
// wedges (each cube split in two by its vertical plane through (-,-) and (+,+)) or pyramids
// (each cube split into six, one on each face, with an extra vertex at the cube's centre).
MeshData box(CellType type, int cells_per_direction);

// The quarter annulus 1 ≤ r ≤ 2, 0 ≤ θ ≤ π/2 (2D), extruded to 0 ≤ z ≤ 1 (3D), with n cells
// across, n around (and n up): quads, triangles, hexes or tets split like box()'s. A mesh with
// curved boundaries for the benchmarks against Mesquite and TMOP (docs/benchmarks.md). Boundary
// parts "inner", "outer" (the arcs), "start", "end" (θ = 0, π/2) and "bottom", "top" (z).
MeshData quarter_annulus(CellType type, int cells_per_direction);

// The ring 1/2 ≤ r ≤ 1 (quadrilaterals or triangles) or the cylindrical shell 1/2 ≤ r ≤ 1,
// 0 ≤ z ≤ 1/2 (hexahedra) with `angular` cells around and `radial` cells across (and as many
// layers in z). The vertices sit at the angles θ(s) = 2πs + a sin 2πs, s = i/angular, so that
// the largest angular gap is `bunching` times the smallest (1: uniform). Boundary parts
// "inner", "outer" (and "bottom", "top").
MeshData ring(CellType type, int angular, int radial, double bunching);

// Displaces every interior vertex (not on boundary_vertices()) by up to amplitude·h in each
// coordinate, uniformly at random, in vertex order; deterministic for a seed on every
// platform. For lattice meshes of spacing h, 0 ≤ amplitude < 1/4 keeps quads and triangles
// valid; tets and hexes can invert near 1/4; up to amplitude < 1 makes tangled meshes.
void jitter(MeshData& mesh, double h, double amplitude, unsigned seed);

// Rotates the mesh counter-clockwise about the origin (2D) or the z axis (3D).
void rotate(MeshData& mesh, double degrees);

// Per vertex: 1 if it lies on a facet (edge in 2D, face in 3D) with one adjacent cell.
std::vector<std::uint8_t> boundary_vertices(const MeshData& mesh);

}  // namespace neomesh
