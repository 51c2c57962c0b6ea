// Results are bitwise identical for a given thread count, run after run, and (since
// every node's update is independent and reductions sum rows in a fixed order)
// also across thread counts (issue 2 §3).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <vector>

#include "fluid/fluid_lattice.hpp"

using namespace erythro;
using namespace erythro::fluid;

namespace {
// A 96 × 80 walled channel (large enough that the kernel forks threads), moving top
// wall, body force, per-node force and τ fields: every code path of the kernel.
std::vector<double> run(int threads, CollisionModel model) {
  omp_set_num_threads(threads);
  BoundaryConfig b;
  b.bottom.type = SideType::wall;
  b.top.type = SideType::moving_wall;
  b.top.ux = 0.03;
  const Grid g{96, 80};
  EXPECT_TRUE(g.worth_threading());
  FluidLattice lat(g, {model, 0.7, 3.0 / 16}, b);
  lat.set_uniform_force(1e-6, 0.0);
  lat.enable_force_field();
  lat.enable_tau_field();
  for (int y = 0; y < g.ny; ++y) {
    for (int x = 0; x < g.nx; ++x) {
      const auto n = g.index(x, y);
      lat.force_y()[n] = 1e-6 * std::sin(0.1 * x);
      lat.tau_field()[n] = 0.6 + 0.3 * (y > g.ny / 2);
    }
  }
  for (int s = 0; s < 200; ++s) lat.step();
  std::vector<double> out(lat.populations().begin(), lat.populations().end());
  out.push_back(lat.total_mass());
  return out;
}
}  // namespace

TEST(Determinism, SameThreadCountIsBitwiseIdentical) {
  for (auto model : {CollisionModel::bgk, CollisionModel::trt}) {
    const auto a = run(2, model), b = run(2, model);
    ASSERT_EQ(a, b);
  }
}

TEST(Determinism, OneAndTwoThreadsAreBitwiseIdentical) {
  for (auto model : {CollisionModel::bgk, CollisionModel::trt}) {
    const auto a = run(1, model), b = run(2, model);
    ASSERT_EQ(a, b);
  }
}
