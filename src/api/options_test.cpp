#include <neomesh/options.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <neomesh/error.hpp>

namespace neomesh {
namespace {

// Every choice's name parses back to it, the default comes first, and an unknown name is an
// error listing them all.
template <typename E>
void expect_names_round_trip(E (*parse)(std::string_view), E default_value) {
  const std::vector<std::string> names = choice_names<E>();
  ASSERT_GE(names.size(), 2u);
  EXPECT_EQ(names.front(), name(default_value));
  for (const std::string& n : names) EXPECT_EQ(name(parse(n)), n);
  try {
    parse("nonsense");
    FAIL() << "no error for an unknown name";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'nonsense'"), std::string::npos) << message;
    for (const std::string& n : names) EXPECT_NE(message.find(n), std::string::npos) << message;
  }
}

TEST(OptionChoices, EveryNameParsesBackAndTheDefaultComesFirst) {
  expect_names_round_trip(parse_boundary_mode, BoundaryOptions().mode);
  expect_names_round_trip(parse_surface_geometry, BoundaryOptions().surface_geometry);
  expect_names_round_trip(parse_linear_solver, SolverOptions().linear_solver);
  expect_names_round_trip(parse_riesz_laplacian, SolverOptions().advanced.riesz);
  expect_names_round_trip(parse_hessian_preconditioner, SolverOptions().advanced.hessian_pc);
  expect_names_round_trip(parse_rejected_direction, SolverOptions().advanced.rejected_direction);
  expect_names_round_trip(parse_size_mode, SmoothOptions().sizes);
  expect_names_round_trip(parse_target_mode, SmoothOptions().targets);
}

TEST(EnergyOptions, KappaBelowZeroMeansLambda) {
  EXPECT_EQ((EnergyOptions{.lambda = 4.0, .kappa = -1.0}).effective_kappa(), 4.0);
  EXPECT_EQ((EnergyOptions{.lambda = 4.0, .kappa = 2.0}).effective_kappa(), 2.0);
}

// validate() names the field, the range and the value; inf and nan are refused as such.
std::string error_of(const auto& options) {
  try {
    options.validate();
  } catch (const OptionError& e) {
    return e.what();
  }
  return "(valid)";
}

TEST(OptionRanges, ValidateNamesTheFieldTheRangeAndTheValue) {
  EXPECT_EQ(error_of(SolverOptions{.advanced = {.eta = 2.0}}),
            "solver.advanced.eta must be in (0, 1) (got 2)");
  EXPECT_EQ(error_of(SolverOptions{.advanced = {.alpha0 = 0.0}}),
            "solver.advanced.alpha0 must be in (0, 1] (got 0)");
  EXPECT_EQ(error_of(SolverOptions{.advanced = {.kmin = -1}}),
            "solver.advanced.kmin must be 0 or more (got -1)");
  EXPECT_EQ(error_of(EnergyOptions{.lambda = -1.0}), "energy.lambda must be positive (got -1)");
  EXPECT_EQ(error_of(EnergyOptions{.kappa = HUGE_VAL}),
            "energy.kappa must be a finite number, positive (or -1 for kappa = lambda) (got inf)");
  EXPECT_EQ(error_of(EnergyOptions{.gauss_points = 6}),
            "energy.gauss_points must be between 1 and 5 (got 6)");
  EXPECT_EQ(error_of(SizeFieldOptions{.max_ratio = 1.0}),
            "field.max_ratio must be above 1, or 0 for no bound (got 1)");
  EXPECT_EQ(error_of(PicardOptions{.relaxation = 2.0}),
            "picard.relaxation must be in (0, 1] (got 2)");
  AdaptOptions adapt;
  adapt.warm_updates = -1;
  EXPECT_EQ(error_of(adapt), "warm_updates must be 0 or more (got -1)");
  BoundaryOptions fixed{BoundaryMode::Fixed};
  fixed.shapes = {{"hole", "circle:0,0,1"}};
  EXPECT_EQ(error_of(fixed),
            "boundary.shapes need sliding boundary vertices (with fixed ones nothing slides on "
            "them)");
  EXPECT_EQ(error_of(SmoothOptions{}), "(valid)");
  EXPECT_EQ(error_of(AdaptOptions::thesis()), "(valid)");
}

}  // namespace
}  // namespace neomesh
