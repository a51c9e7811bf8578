#include "mesh/cell_type.hpp"

namespace neomesh {

std::string_view plural_name(CellType type) {
  return facts(type).plural;
}

}  // namespace neomesh
