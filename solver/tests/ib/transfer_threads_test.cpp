// Spreading is race-free and bitwise reproducible: rows are gathered by one thread
// each in a fixed order, so the result does not depend on the thread count.
#include <gtest/gtest.h>
#include <omp.h>

#include <random>
#include <vector>

#include "ib/transfer.hpp"

using namespace erythro;
using namespace erythro::ib;
using geometry::Domain;

namespace {
std::vector<double> spread_with(int threads, KernelType t, bool periodic) {
  omp_set_num_threads(threads);
  const Domain d{Grid{128, 96}, true, periodic};
  EXPECT_TRUE(d.grid.worth_threading());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> px(-20.0, 150.0), py(periodic ? -30.0 : 0.5, periodic ? 130.0 : 95.5),
      f(-1.0, 1.0);
  std::vector<double> X, Y, Fx, Fy;
  for (int k = 0; k < 4000; ++k) {
    X.push_back(px(rng));
    Y.push_back(py(rng));
    Fx.push_back(f(rng));
    Fy.push_back(f(rng));
  }
  Transfer tr(t, d);
  std::vector<double> fx(d.grid.size(), 0.0), fy(d.grid.size(), 0.0);
  tr.spread(X, Y, Fx, Fy, fx, fy);
  tr.spread(X, Y, Fy, Fx, fx, fy);  // second call reuses the scratch buffers
  fx.insert(fx.end(), fy.begin(), fy.end());
  return fx;
}
}  // namespace

TEST(TransferThreads, BitwiseIdenticalAcrossRunsAndThreadCounts) {
  for (KernelType t : kAllKernels) {
    for (bool periodic : {true, false}) {
      const auto a = spread_with(2, t, periodic), b = spread_with(2, t, periodic);
      ASSERT_EQ(a, b) << to_string(t);
      const auto one = spread_with(1, t, periodic), three = spread_with(3, t, periodic);
      ASSERT_EQ(a, one) << to_string(t);
      ASSERT_EQ(a, three) << to_string(t);
    }
  }
}
