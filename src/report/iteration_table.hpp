// The thesis' iteration table (Tables 5.1, 5.9 ff.), printed row by row while a run goes:
//   k  Armijo  defect  ‖δ‖  F  η_k  α  Krylov(δ̃) residual(δ̃)  Krylov(s)  direction
// With the table off (--quiet is handled by the logger) a one-line progress summary per
// iteration can be printed instead.
#pragma once

#include <string>

#include <neomesh/result.hpp>

namespace neomesh {

std::string iteration_table_header();
std::string iteration_table_row(const IterationRecord& rec);
// "iteration 7: defect 3.8e-06, F 9.6e-17, 0.42 s"
std::string progress_line(const IterationRecord& rec);
// The line above the rows of a phase: an untangling round (solver/untangle.hpp), a round of
// lifting nearly flat corners (solver/worst_cells.hpp), or the Neo-Hookean optimization.
std::string untangling_phase_line(const IterationRecord& rec);

}  // namespace neomesh
