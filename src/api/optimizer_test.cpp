// Optimizer::evaluate: the energy and Q where smooth() would start, with no vertex moved.
#include <neomesh/optimizer.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <gtest/gtest.h>

#include <neomesh/error.hpp>
#include <neomesh/generate.hpp>

namespace neomesh {
namespace {

const std::vector<double>& field(const std::vector<Field>& fields, const std::string& name) {
  const auto it =
      std::find_if(fields.begin(), fields.end(), [&](const Field& f) { return f.name == name; });
  if (it == fields.end()) throw std::runtime_error("no field " + name);
  return it->values;
}

SmoothOptions fixed_uniform() {
  SmoothOptions options;
  options.boundary = BoundaryOptions{BoundaryMode::Fixed};
  options.sizes = SizeMode::Uniform;
  options.targets = TargetMode::Ideal;
  return options;
}

TEST(OptimizerEvaluate, EnergyAndQWhereSmoothStarts) {
  Mesh mesh = Mesh::generate({.name = "square-midpoint", .size = 8});
  const std::vector<double> before = mesh.coordinates();
  Optimizer optimizer(mesh);
  EXPECT_TRUE(optimizer.cell_fields().empty());
  const double energy = optimizer.evaluate(fixed_uniform());
  EXPECT_EQ(mesh.coordinates(), before);

  // Uniform sizes: every cell's desired volume is 1/64 of the unit square, Q = 64 · volume.
  const std::vector<Field> fields = optimizer.cell_fields(), quality = mesh.quality_by_cell();
  const std::vector<double>& q = field(fields, "Q");
  const std::vector<double>& volume = field(quality, "volume");
  ASSERT_EQ(q.size(), volume.size());
  for (std::size_t c = 0; c < q.size(); ++c) EXPECT_NEAR(q[c], 64 * volume[c], 1e-12);
  // F is the sum of the cells' energies; smooth() starts there and goes down.
  const std::vector<double>& cell_energy = field(fields, "energy");
  EXPECT_NEAR(std::accumulate(cell_energy.begin(), cell_energy.end(), 0.0), energy, 1e-10 * energy);
  const Result result = optimizer.smooth(fixed_uniform());
  EXPECT_NEAR(result.initial_energy, energy, 1e-10 * energy);
  EXPECT_LT(result.final_energy, energy);
}

TEST(OptimizerEvaluate, TangledMeshIsMeasuredNotRefused) {
  Mesh mesh = Mesh::generate({.name = "box-quad", .size = 16, .jitter = 0.9});
  SmoothOptions options = fixed_uniform();
  options.untangle = false;  // would make smooth() refuse the mesh
  Optimizer optimizer(mesh);
  EXPECT_EQ(optimizer.evaluate(options), std::numeric_limits<double>::infinity());
  const std::vector<Field> fields = optimizer.cell_fields(), quality = mesh.quality_by_cell();
  const std::vector<double>& energy = field(fields, "energy");
  const std::vector<double>& inverted = field(quality, "inverted");
  for (std::size_t c = 0; c < energy.size(); ++c)
    if (inverted[c] == 0) {
      EXPECT_TRUE(std::isfinite(energy[c])) << c;
    }
}

TEST(OptimizerEvaluate, OptionsOutOfRangeAreAnOptionError) {
  Mesh mesh = Mesh::generate({.name = "box-quad", .size = 2});
  SmoothOptions options;
  options.energy.lambda = -1;
  EXPECT_THROW(Optimizer(mesh).evaluate(options), OptionError);
}

}  // namespace
}  // namespace neomesh
