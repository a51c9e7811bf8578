#include <neomesh/options.hpp>

#include <gtest/gtest.h>

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
  expect_names_round_trip(parse_linear_solver, SolverOptions().linear_solver);
  expect_names_round_trip(parse_riesz_laplacian, SolverOptions().riesz);
  expect_names_round_trip(parse_hessian_preconditioner, SolverOptions().hessian_pc);
  expect_names_round_trip(parse_rejected_direction, SolverOptions().rejected_direction);
  expect_names_round_trip(parse_size_mode, SmoothOptions().sizes);
  expect_names_round_trip(parse_target_mode, SmoothOptions().targets);
}

TEST(EnergyOptions, KappaBelowZeroMeansLambda) {
  EXPECT_EQ((EnergyOptions{.lambda = 4.0, .kappa = -1.0}).effective_kappa(), 4.0);
  EXPECT_EQ((EnergyOptions{.lambda = 4.0, .kappa = 2.0}).effective_kappa(), 2.0);
}

}  // namespace
}  // namespace neomesh
