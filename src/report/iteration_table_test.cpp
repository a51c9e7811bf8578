#include "report/iteration_table.hpp"

#include <gtest/gtest.h>

namespace neomesh {
namespace {

IterationRecord untangling_row(bool lifting) {
  IterationRecord rec;
  rec.k = 3;
  rec.untangling_round = 2;
  rec.epsilon = 0.01;
  rec.inverted = 7;
  rec.lifting_flat_corners = lifting;
  return rec;
}

TEST(IterationTable, UntanglingRowsCountInvertedCells) {
  const IterationRecord rec = untangling_row(false);
  EXPECT_EQ(untangling_phase_line(rec), "untangling, round 2 (epsilon 1.00e-02):");
  EXPECT_TRUE(iteration_table_row(rec).ends_with("  7 inverted"));
  EXPECT_TRUE(progress_line(rec).starts_with("untangling iteration 3:"));
}

// The worst-cell phase lifts nearly flat corners with the untangling energy: its rows must not
// read as if the optimum had inverted cells.
TEST(IterationTable, LiftingRowsCountNearlyFlatCells) {
  const IterationRecord rec = untangling_row(true);
  EXPECT_EQ(untangling_phase_line(rec), "lifting nearly flat corners, round 2 (epsilon 1.00e-02):");
  EXPECT_TRUE(iteration_table_row(rec).ends_with("  7 nearly flat"));
  EXPECT_TRUE(progress_line(rec).starts_with("lifting nearly flat corners iteration 3:"));
  EXPECT_EQ(iteration_table_row(rec).find("inverted"), std::string::npos);
}

TEST(IterationTable, NeoHookeanRowsHaveNoCount) {
  IterationRecord rec;
  rec.k = 1;
  EXPECT_EQ(untangling_phase_line(rec), "optimizing the Neo-Hookean energy:");
  EXPECT_EQ(iteration_table_row(rec).find("inverted"), std::string::npos);
}

}  // namespace
}  // namespace neomesh
