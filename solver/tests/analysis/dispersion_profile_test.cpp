// analysis::dispersion_across and profile_lag (docs/model.md eq 12.4b) on trajectories whose
// answer is known: random walks whose diffusivity depends on the height (each bin recovers
// its own), cells drifting at known speeds (drift exact, no dispersion), and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "analysis/dispersion_profile.hpp"

using namespace erythro::analysis;

namespace {

// Walkers in [0, 10) reflected at both walls, Gaussian steps of variance 2 D(y) Δt with
// D = 0.2 below y = 5 and 0.05 above.
double diffusivity_at(double y) { return y < 5.0 ? 0.2 : 0.05; }

std::vector<std::vector<double>> walks_with_two_diffusivities(double dt) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> start(0.0, 10.0);
  std::vector<std::vector<double>> y(100, std::vector<double>(20000));
  for (auto& s : y) {
    double v = start(rng);
    for (double& e : s) {
      e = v;
      v += std::sqrt(2.0 * diffusivity_at(v) * dt) * unit(rng);
      if (v < 0.0) v = -v;
      if (v >= 10.0) v = 20.0 - v;
    }
  }
  return y;
}

}  // namespace

TEST(DispersionAcross, EachBinRecoversItsOwnDiffusivity) {
  constexpr double dt = 0.1;
  const auto y = walks_with_two_diffusivities(dt);
  const DispersionProfile p = dispersion_across(y, dt, 1, 0.0, 10.0, 10);
  ASSERT_EQ(p.bins.size(), 10u);
  EXPECT_DOUBLE_EQ(p.lag, dt);
  long pairs = 0;
  for (const DispersionBin& b : p.bins) pairs += b.pairs;
  EXPECT_EQ(pairs, 100L * 19999L);  // every origin inside [0, 10) lands in one bin
  // Bins 1–8 lie five step widths or more from the walls: their steps are never reflected,
  // so D_b is D(y) up to the sampling error, about √(2/n) < 0.7 % with n > 4e4 pairs.
  for (int b = 1; b <= 8; ++b) {
    const DispersionBin& bin = p.bins[b];
    ASSERT_GT(bin.pairs, 40000) << b;
    const double D = diffusivity_at(bin.y_from);
    EXPECT_NEAR(bin.D, D, 0.03 * D) << "bin " << b;
    // the mean step is zero; its standard error is √(2DΔt / n)
    EXPECT_LT(std::abs(bin.drift) * dt, 5.0 * std::sqrt(2.0 * D * dt / static_cast<double>(bin.pairs))) << b;
  }
  // At the walls the reflection pushes the cells inwards: an upward drift at the bottom,
  // a downward one at the top.
  EXPECT_GT(p.bins.front().drift, 0.0);
  EXPECT_LT(p.bins.back().drift, 0.0);
}

TEST(DispersionAcross, SteadyDriftIsExactAndDisperseless) {
  // Cell 0 rises at 1e-3 per Δt near y = 0.5, cell 1 sinks at 2e-3 per Δt near y = 3.5;
  // over 200 samples neither leaves its bin of [0, 4) in four.
  std::vector<std::vector<double>> y(2, std::vector<double>(200));
  for (std::size_t t = 0; t < 200; ++t) {
    y[0][t] = 0.4 + 1e-3 * static_cast<double>(t);
    y[1][t] = 3.7 - 2e-3 * static_cast<double>(t);
  }
  const DispersionProfile p = dispersion_across(y, 2.0, 7, 0.0, 4.0, 4);
  EXPECT_DOUBLE_EQ(p.lag, 14.0);
  EXPECT_EQ(p.bins[0].pairs, 193);
  EXPECT_EQ(p.bins[3].pairs, 193);
  EXPECT_NEAR(p.bins[0].drift, 1e-3 / 2.0, 1e-12);
  EXPECT_NEAR(p.bins[3].drift, -2e-3 / 2.0, 1e-12);
  EXPECT_NEAR(p.bins[0].D, 0.0, 1e-12);
  EXPECT_NEAR(p.bins[3].D, 0.0, 1e-12);
  for (int b : {1, 2}) {  // no origin: no value rather than a zero that looks measured
    EXPECT_EQ(p.bins[b].pairs, 0);
    EXPECT_TRUE(std::isnan(p.bins[b].drift));
    EXPECT_TRUE(std::isnan(p.bins[b].D));
  }
  EXPECT_DOUBLE_EQ(p.bins[3].y_to, 4.0);
}

TEST(DispersionAcross, ProfileLagFollowsTheWholeChannelMsd) {
  Dispersion d;
  d.msd = {{1.0, 1.0, 2.0, 10}, {2.0, 3.0, 1.6, 10}, {3.0, 4.0, 1.15, 10}, {4.0, 4.5, 0.4, 10}};
  EXPECT_DOUBLE_EQ(profile_lag(d), 3.0);  // no window: the first lag with α ≤ 1.2
  d.found = true;
  d.lag_from = 2.0;
  EXPECT_DOUBLE_EQ(profile_lag(d), 2.0);  // the window's first lag
  Dispersion ballistic;
  ballistic.msd = {{1.0, 1.0, 2.0, 10}, {2.0, 4.0, 2.0, 10}};
  EXPECT_DOUBLE_EQ(profile_lag(ballistic), 2.0);  // never past the ballistic start: the longest lag
  EXPECT_THROW(profile_lag(Dispersion{}), std::invalid_argument);
}

TEST(DispersionAcross, RejectsBadInput) {
  const std::vector<std::vector<double>> y{{0.0, 1.0, 2.0}, {1.0, 1.0, 1.0}};
  EXPECT_THROW(dispersion_across({}, 1.0, 1, 0.0, 1.0, 2), std::invalid_argument);
  EXPECT_THROW(dispersion_across(y, 0.0, 1, 0.0, 1.0, 2), std::invalid_argument);
  EXPECT_THROW(dispersion_across(y, 1.0, 0, 0.0, 1.0, 2), std::invalid_argument);
  EXPECT_THROW(dispersion_across(y, 1.0, 3, 0.0, 1.0, 2), std::invalid_argument);
  EXPECT_THROW(dispersion_across(y, 1.0, 1, 0.0, 1.0, 0), std::invalid_argument);
  EXPECT_THROW(dispersion_across(y, 1.0, 1, 1.0, 1.0, 2), std::invalid_argument);
  EXPECT_THROW(dispersion_across({{0.0, 1.0}, {0.0}}, 1.0, 1, 0.0, 1.0, 2), std::invalid_argument);
}
