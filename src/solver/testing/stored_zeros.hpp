// A matrix with stored zeros, as the coupled Laplacian of a mesh with sliding vertices has
// them, for the serial and the 2-rank tests of without_stored_zeros.
#pragma once

#include "core/petsc.hpp"

namespace neomesh {

// The 2D five-point Laplacian of an m × m grid (Dirichlet rows at the edges) for two
// interlaced components, with the couplings between the components stored as zeros. Each rank
// owns the rows of a share of the vertices.
inline OwnedMat laplacian_with_stored_zeros(MPI_Comm comm, PetscInt m) {
  const PetscInt vertices = m * m;
  const int size = mpi_size(comm), rank = mpi_rank(comm);
  const PetscInt first = vertices * rank / size, end = vertices * (rank + 1) / size;
  OwnedMat A;
  NM_PETSC(MatCreateAIJ(comm, 2 * (end - first), 2 * (end - first), PETSC_DETERMINE,
                        PETSC_DETERMINE, 10, nullptr, 10, nullptr, A.out()));
  NM_PETSC(MatSetBlockSize(A, 2));
  for (PetscInt v = first; v < end; ++v) {
    const PetscInt i = v / m, j = v % m;
    const bool edge = i == 0 || j == 0 || i == m - 1 || j == m - 1;
    for (PetscInt a = 0; a < 2; ++a)
      for (const PetscInt w : {v - m, v - 1, v, v + 1, v + m}) {
        if (w < 0 || w >= vertices || (edge && w != v)) continue;
        for (PetscInt b = 0; b < 2; ++b) {
          const PetscScalar value = a != b ? 0.0 : w == v ? (edge ? 1.0 : 4.0) : -1.0;
          NM_PETSC(MatSetValue(A, 2 * v + a, 2 * w + b, value, INSERT_VALUES));
        }
      }
  }
  NM_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  NM_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  return A;
}

inline double stored_entries(Mat A) {
  MatInfo info;
  NM_PETSC(MatGetInfo(A, MAT_GLOBAL_SUM, &info));
  return info.nz_used;
}

// ‖A x − B x‖ for a random x.
inline double product_difference(Mat A, Mat B) {
  OwnedVec x, y, z;
  NM_PETSC(MatCreateVecs(A, x.out(), y.out()));
  NM_PETSC(VecDuplicate(y, z.out()));
  NM_PETSC(VecSetRandom(x, nullptr));
  NM_PETSC(MatMult(A, x, y));
  NM_PETSC(MatMult(B, x, z));
  NM_PETSC(VecAXPY(z, -1.0, y));
  double difference = 0.0;
  NM_PETSC(VecNorm(z, NORM_2, &difference));
  return difference;
}

}  // namespace neomesh
