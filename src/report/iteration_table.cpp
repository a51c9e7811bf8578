#include "report/iteration_table.hpp"

#include <fmt/format.h>

namespace neomesh {

namespace {
// Untangling rows (F is the untangling energy there) end with the cells still inverted, or
// still nearly flat where the worst-cell phase lifts corners.
std::string untangling_note(const IterationRecord& rec) {
  if (rec.untangling_round == 0) return "";
  return fmt::format("  {} {}", rec.inverted,
                     rec.lifting_flat_corners ? "nearly flat" : "inverted");
}

const char* untangling_name(const IterationRecord& rec) {
  return rec.lifting_flat_corners ? "lifting nearly flat corners" : "untangling";
}
}  // namespace

std::string iteration_table_header() {
  return fmt::format("{:>4} {:>6} {:>10} {:>10} {:>10} {:>5} {:>5} {:>6} {:>9} {:>6} {:>5}", "k",
                     "armijo", "defect", "|delta|", "F", "eta", "alpha", "ksp_d", "res_d", "ksp_s",
                     "dir");
}

std::string iteration_table_row(const IterationRecord& rec) {
  const std::string ksp_delta = rec.delta_solved ? fmt::format("{}", rec.krylov_delta) : "-";
  const std::string res_delta = rec.delta_solved ? fmt::format("{:.2E}", rec.residual_delta) : "-";
  // s not solved: η estimated with one V-cycle (SolverOptions::Advanced::lazy_riesz).
  const std::string ksp_s = rec.s_solved ? fmt::format("{}", rec.krylov_s) : "-";
  // s! : δ̃ failed and α was cut; delta~ : CG stopped at negative curvature (truncated δ̃);
  // +s: δ̃ turned towards −s to pass the angle test.
  const char* direction = rec.blended        ? (rec.delta_truncated ? "delta~+s" : "delta+s")
                          : !rec.used_s      ? (rec.delta_truncated ? "delta~" : "delta")
                          : rec.delta_failed ? "s!"
                                             : "s";
  return fmt::format(
      "{:>4} {:>6} {:>10.2E} {:>10.2E} {:>10.2E} {:>5.2f} {:>5.2f} {:>6} {:>9} "
      "{:>6} {:>6}{}{}",
      rec.k, rec.armijo_steps, rec.defect, rec.direction_norm, rec.energy, rec.eta, rec.alpha,
      ksp_delta, res_delta, ksp_s, direction, rec.roundoff_step ? "  (round-off: full step)" : "",
      untangling_note(rec));
}

std::string untangling_phase_line(const IterationRecord& rec) {
  if (rec.untangling_round == 0) return "optimizing the Neo-Hookean energy:";
  return fmt::format("{}, round {} (epsilon {:.2e}):", untangling_name(rec), rec.untangling_round,
                     rec.epsilon);
}

std::string progress_line(const IterationRecord& rec) {
  return fmt::format("{}iteration {}: defect {:.2e}, F {:.4e}, {:.2f} s{}",
                     rec.untangling_round > 0 ? fmt::format("{} ", untangling_name(rec)) : "",
                     rec.k, rec.defect, rec.energy, rec.seconds, untangling_note(rec));
}

}  // namespace neomesh
