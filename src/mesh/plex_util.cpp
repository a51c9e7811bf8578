#include "mesh/plex_util.hpp"

namespace neomesh {

std::vector<PetscInt> closure_vertices(DM dm, PetscInt point, PetscInt vStart, PetscInt vEnd) {
  PetscInt n = 0, *closure = nullptr;
  NM_PETSC(DMPlexGetTransitiveClosure(dm, point, PETSC_TRUE, &n, &closure));
  std::vector<PetscInt> vertices;
  for (PetscInt i = 0; i < n; ++i)
    if (closure[2 * i] >= vStart && closure[2 * i] < vEnd)
      vertices.push_back(closure[2 * i] - vStart);
  NM_PETSC(DMPlexRestoreTransitiveClosure(dm, point, PETSC_TRUE, &n, &closure));
  return vertices;
}

std::vector<std::uint8_t> ghost_points(DM dm) {
  PetscInt pStart, pEnd;
  NM_PETSC(DMPlexGetChart(dm, &pStart, &pEnd));
  std::vector<std::uint8_t> ghost(pEnd - pStart, 0);
  PetscSF sf;
  NM_PETSC(DMGetPointSF(dm, &sf));
  PetscInt nroots, nleaves;
  const PetscInt* ilocal;
  const PetscSFNode* iremote;
  NM_PETSC(PetscSFGetGraph(sf, &nroots, &nleaves, &ilocal, &iremote));
  for (PetscInt i = 0; nroots >= 0 && i < nleaves; ++i)
    ghost[(ilocal ? ilocal[i] : i) - pStart] = 1;
  return ghost;
}

}  // namespace neomesh
