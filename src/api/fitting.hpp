// What fitting to a LevelSet (Mesh::interface, Optimizer::adapt with a LevelSet) needs from the
// layers below: φ as a function of the mesh's dimension.
#pragma once

#include <neomesh/level_set.hpp>

#include "boundary/shape.hpp"

namespace neomesh {

// φ for a mesh of dimension `dim`, at the level set's time.
LevelSetFunction level_set_function(const LevelSet& phi, int dim);

}  // namespace neomesh
