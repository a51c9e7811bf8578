// The public API's vertex order: the vertices a process owns, by ascending input number
// (Mesh::vertex_numbers()), and the conversions of per-vertex values and facets between it
// and the MeshView's local order (owned and ghost vertices) that the layers below work in.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <neomesh/mesh.hpp>

#include "mesh/mesh_view.hpp"

namespace neomesh {

// This process' owned local vertices, ordered by their input number.
std::vector<PetscInt> owned_by_number(const MeshView& view);

// A vertex field given in vertex_numbers() order, in local order; ghosts get NaN (the
// writers take each vertex's value from its owner). Throws Error if the size does not fit.
Field local_vertex_field(const MeshView& view, const Field& field);
// A field per local vertex (`components` values each), in vertex_numbers() order.
Field public_vertex_field(const MeshView& view, std::string name, std::span<const double> local,
                          int components = 1);
// Facets given by local vertices (CSR), with input vertex numbers.
FacetGroup public_facet_group(const MeshView& view, std::string name,
                              std::span<const PetscInt> offsets,
                              std::span<const PetscInt> local_vertices);

}  // namespace neomesh
