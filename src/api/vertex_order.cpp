#include "api/vertex_order.hpp"

#include <algorithm>
#include <limits>

#include "core/error.hpp"

namespace neomesh {

std::vector<PetscInt> owned_by_number(const MeshView& view) {
  std::vector<PetscInt> owned;
  for (PetscInt u = 0; u < view.num_vertices; ++u)
    if (view.owned[u]) owned.push_back(u);
  std::sort(owned.begin(), owned.end(), [&view](PetscInt a, PetscInt b) {
    return view.input_vertex[a] < view.input_vertex[b];
  });
  return owned;
}

Field local_vertex_field(const MeshView& view, const Field& field) {
  const std::vector<PetscInt> owned = owned_by_number(view);
  const auto n = static_cast<std::size_t>(field.components);
  if (field.components < 1 || field.values.size() != owned.size() * n)
    fail("vertex field '{}' has {} values for {} vertices of this process ({} each)", field.name,
         field.values.size(), owned.size(), field.components);
  Field local{field.name,
              std::vector<double>(view.num_vertices * n, std::numeric_limits<double>::quiet_NaN()),
              field.components};
  for (std::size_t i = 0; i < owned.size(); ++i)
    std::copy_n(field.values.begin() + i * n, n, local.values.begin() + owned[i] * n);
  return local;
}

Field public_vertex_field(const MeshView& view, std::string name, std::span<const double> local,
                          int components) {
  Field out{std::move(name), {}, components};
  for (PetscInt u : owned_by_number(view))
    for (int j = 0; j < components; ++j) out.values.push_back(local[u * components + j]);
  return out;
}

FacetGroup public_facet_group(const MeshView& view, std::string name,
                              std::span<const PetscInt> offsets,
                              std::span<const PetscInt> local_vertices) {
  FacetGroup group{std::move(name), {offsets.begin(), offsets.end()}, {}};
  for (PetscInt u : local_vertices) group.vertices.push_back(view.input_vertex[u]);
  return group;
}

}  // namespace neomesh
