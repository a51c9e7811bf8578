#include "solver/linear_solver.hpp"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include <omp.h>

#include "core/error.hpp"

namespace neomesh {

namespace {

// BoomerAMG is tuned only through the options database: neomesh's defaults go there unless
// the caller gave the option, for as long as the solver reads its options (the destructor
// takes them out again, so the database is left as the caller made it).
//
// The smoother in 2D is one sweep of l1-Gauss-Seidel down and one backward up (a symmetric
// V-cycle, as CG needs): PETSc's default symmetric SOR/Jacobi sweeps both ways on both legs,
// twice the work, and Chebyshev needs two products per sweep and an eigenvalue estimate.
// Square-midpoint 1024²: whole run 26.2 s (symmetric SOR/Jacobi), 20.9–23.5 s (Chebyshev),
// 17.2–17.4 s (l1-Gauss-Seidel), the same quasi-Newton and about as many CG iterations. In 3D
// Chebyshev stays: the same times on the fixed boxes, and the sliding annulus of hexahedra's
// block hierarchy needed 111 instead of 77 Riesz CG iterations with Gauss-Seidel (whole run
// 3.2–3.4 against 2.9–3.0 s; docs/benchmarks.md).
//
// In 3D, hypre's advice for 3D problems (HMIS coarsening, ext+i interpolation with at most 4
// entries per row, strong threshold 0.5) keeps the hierarchies sparse: on cube-midpoint 32³ the
// Riesz Laplacian's operator complexity was 5.4 with the 2D defaults, and both setups and
// V-cycles take half the time or less at the same CG iterations. In 2D the same options do not
// help (same time, more iterations). Aggressive coarsening on the finest level (2 paths) then
// halves the 3D setups again at the same iterations (hexes 40³: Riesz setup 0.42 → 0.13 s, whole
// run 2.28 → 1.82 s; tets 40³: 0.17 → 0.07 s, 2.04 → 1.88 s); in 2D it slowed the V-cycles
// (quads 300²: 0.58 → 0.65 s). With it, a strong threshold of 0.6 rather than 0.5 took a third
// fewer CG iterations on hexahedra (40³: Riesz and δ̃ solves and Riesz setup 0.80–0.89 →
// 0.56–0.65 s) and as many or fewer on tetrahedra (0.62 → 0.52 s).
class AmgDefaults {
 public:
  AmgDefaults(const std::string& prefix, int dim) {
    std::vector<std::pair<const char*, const char*>> defaults;
    if (dim == 3)
      defaults = {{"relax_type_all", "Chebyshev"}, {"coarsen_type", "HMIS"},
                  {"interp_type", "ext+i"},        {"P_max", "4"},
                  {"strong_threshold", "0.6"},     {"agg_nl", "1"},
                  {"agg_num_paths", "2"}};
    else
      defaults = {{"relax_type_down", "l1-Gauss-Seidel"},
                  {"relax_type_up", "backward-l1-Gauss-Seidel"}};
    // A smoother given for both legs (relax_type_all) is the caller's choice for each.
    const bool smoother_given = has_option(option_name(prefix, "relax_type_all"));
    for (const auto& [name, value] : defaults) {
      const std::string_view key = name;
      std::string option = option_name(prefix, name);
      if (has_option(option) || (smoother_given && key.starts_with("relax_type_"))) continue;
      NM_PETSC(PetscOptionsSetValue(nullptr, option.c_str(), value));
      set_.push_back(std::move(option));
    }
  }
  ~AmgDefaults() {
    for (const std::string& option : set_) PetscOptionsClearValue(nullptr, option.c_str());
  }
  AmgDefaults(const AmgDefaults&) = delete;
  AmgDefaults& operator=(const AmgDefaults&) = delete;

 private:
  static std::string option_name(const std::string& prefix, const char* name) {
    return "-" + prefix + "pc_hypre_boomeramg_" + name;
  }
  static bool has_option(const std::string& option) {
    PetscBool given = PETSC_FALSE;
    NM_PETSC(PetscOptionsHasName(nullptr, nullptr, option.c_str(), &given));
    return given;
  }

  std::vector<std::string> set_;  // the options this put in
};

}  // namespace

OwnedMat without_stored_zeros(Mat A) {
  PetscInt first = 0, end = 0, first_column = 0, end_column = 0;
  NM_PETSC(MatGetOwnershipRange(A, &first, &end));
  NM_PETSC(MatGetOwnershipRangeColumn(A, &first_column, &end_column));
  std::vector<PetscInt> diagonal(end - first), off_diagonal(end - first);
  std::int64_t counts[2] = {0, 0};  // stored entries, zeros among them (over all ranks)
  for (PetscInt row = first; row < end; ++row) {
    PetscInt n = 0;
    const PetscInt* columns = nullptr;
    const PetscScalar* values = nullptr;
    NM_PETSC(MatGetRow(A, row, &n, &columns, &values));
    for (PetscInt i = 0; i < n; ++i) {
      if (values[i] == 0.0) {
        ++counts[1];
        continue;
      }
      const bool local = columns[i] >= first_column && columns[i] < end_column;
      ++(local ? diagonal : off_diagonal)[row - first];
    }
    counts[0] += n;
    NM_PETSC(MatRestoreRow(A, row, &n, &columns, &values));
  }
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(A));
  MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_INT64_T, MPI_SUM, comm);
  if (10 * counts[1] < counts[0]) return {};
  OwnedMat P;
  PetscInt rows = 0, columns = 0, global_rows = 0, global_columns = 0;
  NM_PETSC(MatGetLocalSize(A, &rows, &columns));
  NM_PETSC(MatGetSize(A, &global_rows, &global_columns));
  NM_PETSC(MatCreate(comm, P.out()));
  NM_PETSC(MatSetSizes(P, rows, columns, global_rows, global_columns));
  NM_PETSC(MatSetBlockSizesFromMats(P, A, A));
  NM_PETSC(MatSetType(P, MATAIJ));
  NM_PETSC(MatSeqAIJSetPreallocation(P, 0, diagonal.data()));
  NM_PETSC(MatMPIAIJSetPreallocation(P, 0, diagonal.data(), 0, off_diagonal.data()));
  std::vector<PetscInt> kept_columns;
  std::vector<PetscScalar> kept_values;
  for (PetscInt row = first; row < end; ++row) {
    PetscInt n = 0;
    const PetscInt* row_columns = nullptr;
    const PetscScalar* values = nullptr;
    NM_PETSC(MatGetRow(A, row, &n, &row_columns, &values));
    kept_columns.clear();
    kept_values.clear();
    for (PetscInt i = 0; i < n; ++i)
      if (values[i] != 0.0) {
        kept_columns.push_back(row_columns[i]);
        kept_values.push_back(values[i]);
      }
    NM_PETSC(MatRestoreRow(A, row, &n, &row_columns, &values));
    NM_PETSC(MatSetValues(P, 1, &row, static_cast<PetscInt>(kept_columns.size()),
                          kept_columns.data(), kept_values.data(), INSERT_VALUES));
  }
  NM_PETSC(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  NM_PETSC(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  return P;
}

LinearSolver::LinearSolver(MPI_Comm comm, LinearSolverKind kind, const std::string& prefix, int dim,
                           double rtol)
    : rtol_(rtol), kind_(kind), prefix_(prefix), dim_(dim) {
  NM_PETSC(KSPCreate(comm, ksp_.out()));
  NM_PETSC(KSPSetOptionsPrefix(ksp_, prefix.c_str()));
  PC pc = nullptr;
  NM_PETSC(KSPGetPC(ksp_, &pc));
  std::optional<AmgDefaults> amg_defaults;  // until KSPSetFromOptions has read them
  switch (kind) {
    case LinearSolverKind::Amg:
      NM_PETSC(KSPSetType(ksp_, KSPCG));
      NM_PETSC(PCSetType(pc, PCHYPRE));
      NM_PETSC(PCHYPRESetType(pc, "boomeramg"));
      amg_defaults.emplace(prefix, dim);
      break;
    case LinearSolverKind::Jacobi:
      NM_PETSC(KSPSetType(ksp_, KSPCG));
      NM_PETSC(PCSetType(pc, PCJACOBI));
      break;
    case LinearSolverKind::Direct:
      NM_PETSC(KSPSetType(ksp_, KSPPREONLY));
      NM_PETSC(PCSetType(pc, PCCHOLESKY));
      NM_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
      break;
  }
  // The thesis' stopping rule measures the true residual, not the preconditioned one.
  if (kind != LinearSolverKind::Direct) NM_PETSC(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED));
  NM_PETSC(KSPSetTolerances(ksp_, rtol, 0.0, PETSC_DEFAULT, PETSC_DEFAULT));
  NM_PETSC(KSPSetFromOptions(ksp_));
  NM_PETSC(KSPGetTolerances(ksp_, &rtol_, nullptr, nullptr, nullptr));
}

void LinearSolver::set_operator(Mat A, bool same_values) {
  // hypre keeps every stored entry, zeros too, in its copy of A, its Galerkin products and its
  // smoothers: the hierarchy is built for A without them, the same operator. A kept hierarchy
  // (same_values) needs no new copy, nor a scan of A for zeros.
  PetscBool had_operator = PETSC_FALSE;
  NM_PETSC(KSPGetOperatorsSet(ksp_, &had_operator, nullptr));
  if (builds_amg_hierarchy() && (!same_values || !had_operator))
    amg_matrix_ = without_stored_zeros(A);
  if (components_) {
    const Mat per_component = components_->kind() == ComponentOperators::Own ? A : maij_scalar(A);
    if (!per_component)
      fail("internal error: a per-component preconditioner for a matrix that is no MAIJ");
    components_->set_operator(per_component, same_values);
    // Its copies in hypre's format multiply: A is not kept.
    if (components_->product()) A = components_->product();
  }
  NM_PETSC(KSPSetOperators(ksp_, A, amg_matrix_ ? amg_matrix_.get() : A));
  NM_PETSC(KSPSetReusePreconditioner(ksp_, same_values ? PETSC_TRUE : PETSC_FALSE));
}

bool LinearSolver::copies_operator() const {
  return components_ && components_->product();
}

void LinearSolver::multiply(Vec x, Vec y) const {
  Mat A = nullptr;
  NM_PETSC(KSPGetOperators(ksp_, &A, nullptr));
  NM_PETSC(MatMult(A, x, y));
}

void LinearSolver::setup() {
  NM_PETSC(KSPSetUp(ksp_));
  if (components_) components_->setup();
}

void LinearSolver::precondition_per_component(ComponentOperators kind) {
  if (kind_ != LinearSolverKind::Amg)
    fail("internal error: a per-component preconditioner for a solver other than AMG");
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(ksp_.get()));
  const auto scalar_preconditioner = [&] {
    OwnedPC scalar;
    NM_PETSC(PCCreate(comm, scalar.out()));
    NM_PETSC(PCSetOptionsPrefix(scalar, prefix_.c_str()));
    NM_PETSC(PCSetType(scalar, PCHYPRE));
    NM_PETSC(PCHYPRESetType(scalar, "boomeramg"));
    const AmgDefaults defaults(prefix_, dim_);  // while it reads them
    NM_PETSC(PCSetFromOptions(scalar));
    return scalar;
  };
  std::vector<OwnedPC> scalars;
  scalars.push_back(scalar_preconditioner());
  PetscBool hypre = PETSC_FALSE;
  NM_PETSC(
      PetscObjectTypeCompare(reinterpret_cast<PetscObject>(scalars[0].get()), PCHYPRE, &hypre));
  const char* hypre_type = nullptr;
  if (hypre) NM_PETSC(PCHYPREGetType(scalars[0], &hypre_type));
  const bool boomeramg = hypre_type && std::string_view(hypre_type) == "boomeramg";
  // Components are preconditioned at once on threads (component_preconditioner.hpp) only on
  // one rank (on several, hypre would exchange messages from threads; on one it sends none),
  // not while PETSc logs events (it counts them in shared tables), and not with another
  // preconditioner that -<prefix>pc_ options chose (not checked for it).
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const bool concurrent = ranks == 1 && !PetscLogPLB && boomeramg;
  const int count = kind == ComponentOperators::Own ? dim_
                    : concurrent                    ? std::min(dim_, omp_get_max_threads())
                                                    : 1;
  while (static_cast<int>(scalars.size()) < count) scalars.push_back(scalar_preconditioner());
  components_ = std::make_unique<ComponentPreconditioner>(std::move(scalars), dim_, kind, boomeramg,
                                                          concurrent);
  PC pc = nullptr;
  NM_PETSC(KSPGetPC(ksp_, &pc));
  components_->install(pc);
}

namespace {

PetscErrorCode apply_other(PC shell, Vec x, Vec y) {
  PetscFunctionBeginUser;
  void* other = nullptr;
  PetscCall(PCShellGetContext(shell, &other));
  PetscCall(PCApply(static_cast<PC>(other), x, y));
  PetscFunctionReturn(0);
}

}  // namespace

void LinearSolver::precondition_with(const LinearSolver& other) {
  PC pc = nullptr, other_pc = nullptr;
  NM_PETSC(KSPGetPC(ksp_, &pc));
  NM_PETSC(KSPGetPC(other.ksp_, &other_pc));
  NM_PETSC(PCSetType(pc, PCSHELL));
  NM_PETSC(PCShellSetContext(pc, other_pc));
  NM_PETSC(PCShellSetApply(pc, apply_other));
  NM_PETSC(PCShellSetName(pc, "the Riesz solve's preconditioner"));
}

// Not with a shell PC: per component, or another solver's preconditioner.
bool LinearSolver::builds_amg_hierarchy() const {
  if (kind_ != LinearSolverKind::Amg) return false;
  PC pc = nullptr;
  NM_PETSC(KSPGetPC(ksp_, &pc));
  PetscBool shell = PETSC_FALSE;
  NM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCSHELL, &shell));
  return !shell;
}

LinearSolver::Outcome LinearSolver::solve(Vec b, Vec x, double atol) {
  NM_PETSC(KSPSetTolerances(ksp_, rtol_, atol, PETSC_DEFAULT, PETSC_DEFAULT));
  NM_PETSC(VecZeroEntries(x));
  NM_PETSC(KSPSolve(ksp_, b, x));
  KSPConvergedReason reason;
  NM_PETSC(KSPGetConvergedReason(ksp_, &reason));
  PetscInt its = 0;
  NM_PETSC(KSPGetIterationNumber(ksp_, &its));
  Outcome out;
  out.converged = reason > 0;
  out.indefinite = reason == KSP_DIVERGED_INDEFINITE_MAT || reason == KSP_DIVERGED_INDEFINITE_PC;
  out.iterations = static_cast<int>(its);
  if (kind_ != LinearSolverKind::Direct) {
    // CG's own residual norm (unpreconditioned, KSPSetNormType): what its test compared.
    NM_PETSC(KSPGetResidualNorm(ksp_, &out.residual));
    return out;
  }
  // Preonly (direct) computes no residual: b − A x, in a vector kept for the next solve.
  if (!residual_) NM_PETSC(VecDuplicate(b, residual_.out()));
  Mat A = nullptr;
  NM_PETSC(KSPGetOperators(ksp_, &A, nullptr));
  NM_PETSC(MatMult(A, x, residual_));
  NM_PETSC(VecAYPX(residual_, -1.0, b));
  NM_PETSC(VecNorm(residual_, NORM_2, &out.residual));
  return out;
}

void LinearSolver::apply_preconditioner(Vec b, Vec x) {
  setup();
  PC pc = nullptr;
  NM_PETSC(KSPGetPC(ksp_, &pc));
  NM_PETSC(PCApply(pc, b, x));
}

namespace {

// "hypre boomeramg", "cholesky (mumps)", "jacobi".
std::string describe(PC pc) {
  PCType pc_type = nullptr;
  NM_PETSC(PCGetType(pc, &pc_type));
  std::string pc_name = pc_type ? pc_type : "none";
  if (pc_name == PCHYPRE) {
    const char* hypre = nullptr;
    NM_PETSC(PCHYPREGetType(pc, &hypre));
    pc_name += fmt::format(" {}", hypre ? hypre : "");
  } else if (pc_name == PCCHOLESKY || pc_name == PCLU) {
    MatSolverType package = nullptr;
    NM_PETSC(PCFactorGetMatSolverType(pc, &package));
    pc_name += fmt::format(" ({})", package ? package : "petsc");
  }
  return pc_name;
}

}  // namespace

std::string LinearSolver::description() const {
  KSPType ksp_type = nullptr;
  PC pc = nullptr;
  NM_PETSC(KSPGetType(ksp_, &ksp_type));
  NM_PETSC(KSPGetPC(ksp_, &pc));
  std::string pc_name = describe(pc);
  if (components_)
    pc_name =
        fmt::format("{} of {} for each of {} components", describe(components_->scalar()),
                    components_->kind() == ComponentOperators::Own ? "each component's matrix,"
                                                                   : "the scalar matrix, once",
                    components_->components());
  double rtol = 0.0;
  PetscInt max_it = 0;
  NM_PETSC(KSPGetTolerances(ksp_, &rtol, nullptr, nullptr, &max_it));
  return fmt::format("KSP {}, PC {}, rtol {:g}, at most {} iterations", ksp_type, pc_name, rtol,
                     max_it);
}

}  // namespace neomesh
