// A DMPlex that a caller built (Mesh::from_dm) as an InputMesh on rank 0, so that it is
// validated and distributed like a file: cells in canonical order, vertices numbered by the
// DM's global vertex numbering (DMPlexGetVertexNumbering), which becomes their input number.
#pragma once

#include <string>

#include <petscdm.h>

#include "mesh/input_mesh.hpp"

namespace neomesh {

// Collective over the DM's communicator; the result is complete on rank 0 and empty elsewhere.
// Takes each process' owned cells (an overlap is skipped) and vertex coordinates; the DM may
// be interpolated or not. Labels are not taken over. Throws Error naming `name` for anything
// neomesh cannot use: not a DMPlex, a dimension other than 2 or 3, coordinates not one point
// per vertex (high order, periodic), an unsupported cell type.
InputMesh input_from_dm(DM dm, const std::string& name);

}  // namespace neomesh
