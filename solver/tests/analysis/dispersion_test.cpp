// analysis::transverse_dispersion (docs/model.md eq 12.4) on trajectories whose answer is
// known: free random walks (MSD = 2Dτ, D recovered), straight motion (ballistic: α = 2, no
// diffusive window), and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "analysis/dispersion.hpp"

using namespace erythro::analysis;

TEST(Dispersion, RandomWalksGiveTheirDiffusivity) {
  // 200 walkers, 4000 steps of Δt = 0.5, Gaussian steps of variance 2DΔt, D = 0.3.
  constexpr double D = 0.3, dt = 0.5;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> step(0.0, std::sqrt(2.0 * D * dt));
  std::vector<std::vector<double>> y(200, std::vector<double>(4000));
  for (auto& s : y) {
    double v = 0.0;
    for (double& e : s) e = (v += step(rng));
  }
  DispersionOptions o;
  o.max_lag_fraction = 0.05;  // lags up to 200 steps: ~4000 origins each, 1-2 % noise
  const Dispersion d = transverse_dispersion(y, dt, o);
  ASSERT_TRUE(d.found);
  EXPECT_NEAR(d.D, D, 0.05 * D);
  EXPECT_EQ(d.lag_from, dt);  // diffusive from the first lag
  for (const MsdPoint& p : d.msd) EXPECT_NEAR(p.slope, 1.0, 0.1) << p.lag;
}

TEST(Dispersion, StraightMotionIsBallisticAndHasNoDiffusiveWindow) {
  std::vector<std::vector<double>> y(3, std::vector<double>(500));
  for (std::size_t c = 0; c < y.size(); ++c)
    for (std::size_t t = 0; t < y[c].size(); ++t) y[c][t] = 0.01 * static_cast<double>((c + 1) * t);
  const Dispersion d = transverse_dispersion(y, 1.0);
  EXPECT_FALSE(d.found);
  EXPECT_EQ(d.D, 0.0);
  for (const MsdPoint& p : d.msd) EXPECT_NEAR(p.slope, 2.0, 1e-9) << p.lag;
}

TEST(Dispersion, AtOneLagTakesTheNearestLag) {
  Dispersion d;
  d.msd = {{1.0, 4.0, 2.0, 10}, {2.0, 6.0, 0.6, 10}, {4.0, 8.0, 0.4, 10}};
  EXPECT_DOUBLE_EQ(dispersion_at_lag(d, 2.0), 1.5);  // 6 / (2·2)
  EXPECT_DOUBLE_EQ(dispersion_at_lag(d, 3.4), 1.0);  // nearest is 4: 8 / (2·4)
  EXPECT_DOUBLE_EQ(dispersion_at_lag(d, 0.1), 2.0);  // below the grid: the first lag
  EXPECT_DOUBLE_EQ(dispersion_at_lag(d, 1e9), 1.0);  // beyond it: the last
  EXPECT_THROW(dispersion_at_lag(Dispersion{}, 1.0), std::invalid_argument);
}

TEST(Dispersion, RejectsBadInput) {
  EXPECT_THROW(transverse_dispersion({}, 1.0), std::invalid_argument);
  EXPECT_THROW(transverse_dispersion({{0.0, 1.0, 2.0}}, 0.0), std::invalid_argument);
  EXPECT_THROW(transverse_dispersion({{0.0, 1.0, 2.0}, {0.0, 1.0}}, 1.0), std::invalid_argument);
}
