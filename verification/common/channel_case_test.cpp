// The channel cases' statistics and series (common/channel_case.hpp) on numbers worked by hand.
#include "common/channel_case.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

using namespace erythro;

TEST(ChannelCase, BlockEstimateOfTwoLevels) {
  // Samples at t = 0 … 9: 1 in [0, 5), 3 in [5, 10); window [0, 10) in two blocks → means 1, 3.
  std::vector<double> t, y;
  for (int k = 0; k < 10; ++k) {
    t.push_back(k);
    y.push_back(k < 5 ? 1.0 : 3.0);
  }
  const vv::WindowEstimate e = vv::block_estimate(t, y, 0.0, 10.0, 2);
  EXPECT_DOUBLE_EQ(e.mean, 2.0);
  EXPECT_DOUBLE_EQ(e.se, 1.0);  // sqrt(((1-2)² + (3-2)²) / (1 · 2))
  EXPECT_THROW(vv::block_estimate(t, y, 0.0, 20.0, 4), std::runtime_error);  // blocks beyond the samples
}

TEST(ChannelCase, CombineSeedsByHand) {
  // Means 1, 2, 3, 4 with standard errors 1, 1, 1, 2: plain mean 2.5; weights 1, 1, 1, 1/4 →
  // weighted mean (1 + 2 + 3 + 1)/3.25 = 7/3.25; sample sd sqrt(5/3), se sqrt(5/12).
  const std::vector<vv::WindowEstimate> s{{1.0, 1.0}, {2.0, 1.0}, {3.0, 1.0}, {4.0, 2.0}};
  const vv::SeedEnsemble e = vv::combine_seeds(s, 3.182);
  const double wm = 7.0 / 3.25;
  EXPECT_DOUBLE_EQ(e.mean, 2.5);
  EXPECT_NEAR(e.weighted_mean, wm, 1e-15);
  EXPECT_NEAR(e.ci95, 3.182 * std::sqrt(5.0 / 12.0), 1e-14);
  const double chi2 = (1 - wm) * (1 - wm) + (2 - wm) * (2 - wm) + (3 - wm) * (3 - wm) + (4 - wm) * (4 - wm) / 4.0;
  EXPECT_NEAR(e.chi2, chi2, 1e-14);
  EXPECT_THROW(vv::combine_seeds({{1.0, 1.0}}, 12.71), std::invalid_argument);
}

TEST(ChannelCase, OneWayAnovaByHand) {
  // Groups {1, 2, 3}, {2, 3, 4}, {5, 6, 7}: means 2, 3, 6, grand mean 11/3; between
  // 3[(2 − 11/3)² + (3 − 11/3)² + (6 − 11/3)²] = 26 over 2; within 3 × 2 = 6 over 6: F = 13
  // (scipy.stats.f_oneway gives 13.0 with 2 and 6 degrees of freedom).
  const vv::OneWayAnova a = vv::one_way_anova({{1.0, 2.0, 3.0}, {2.0, 3.0, 4.0}, {5.0, 6.0, 7.0}});
  EXPECT_NEAR(a.F, 13.0, 1e-13);
  EXPECT_EQ(a.df_between, 2);
  EXPECT_EQ(a.df_within, 6);
  // Unequal sizes {0, 2}, {4}: grand mean 2, between 2·1² + 1·2² = 6 over 1, within 2 over 1: F = 3.
  EXPECT_NEAR(vv::one_way_anova({{0.0, 2.0}, {4.0}}).F, 3.0, 1e-14);
  EXPECT_THROW(vv::one_way_anova({{1.0, 2.0}}), std::invalid_argument);           // one group
  EXPECT_THROW(vv::one_way_anova({{1.0}, {2.0}}), std::invalid_argument);         // no within-group scatter
  EXPECT_THROW(vv::one_way_anova({{1.0, std::nan("")}, {2.0, 3.0}}), std::invalid_argument);
}

TEST(ChannelCase, DispersionAcrossSeriesShowsTheFullBins) {
  analysis::DispersionProfile p;
  p.lag = 0.05;  // s: 10 strain units at 200 1/s
  p.bins = {{0.0, 5.0, 300, 0.1, 1.5}, {5.0, 10.0, 50, 0.2, 9.0}, {10.0, 15.0, 250, -0.1, 2.5}};
  const io::Series s = vv::dispersion_across_series(p, 200.0, "dyy_across_g200", "D_yy across, 200 1/s");
  EXPECT_EQ(s.name, "dyy_across_g200");
  EXPECT_EQ(s.title, "D_yy across, 200 1/s (lag 10 strain units, eq 12.4b)");
  ASSERT_EQ(s.x.size(), 2u);  // the bin of 50 origins (below kAcrossMinPairs) is left out
  EXPECT_DOUBLE_EQ(s.x[0], 2.5);
  EXPECT_DOUBLE_EQ(s.x[1], 12.5);
  EXPECT_DOUBLE_EQ(s.y[0], 1.5);
  EXPECT_DOUBLE_EQ(s.y[1], 2.5);
  EXPECT_FALSE(s.log_x);
}
