// The order fit itself must be right before any case trusts it.
#include <gtest/gtest.h>

#include <cmath>

#include "common/convergence.hpp"

using namespace erythro;

TEST(Convergence, ExactPowerLawGivesItsOrder) {
  io::ConvergenceSeries s;
  s.h = {0.1, 0.05, 0.025, 0.0125};
  for (double h : s.h) s.error.push_back(3.0 * h * h);
  s.formal_order = 2.0;
  s.order_tolerance = 0.1;
  vv::fit_order(s);
  EXPECT_NEAR(s.observed_order, 2.0, 1e-12);
  EXPECT_TRUE(s.asymptotic);
  for (double p : s.local_orders) EXPECT_NEAR(p, 2.0, 1e-12);
}

TEST(Convergence, FirstOrderIsNotSecond) {
  io::ConvergenceSeries s;
  s.h = {0.1, 0.05, 0.025};
  for (double h : s.h) s.error.push_back(h);
  s.formal_order = 2.0;
  s.order_tolerance = 0.1;
  vv::fit_order(s);
  EXPECT_NEAR(s.observed_order, 1.0, 1e-12);
  EXPECT_FALSE(s.asymptotic);
}

TEST(Convergence, PreAsymptoticDetected) {
  io::ConvergenceSeries s;
  s.h = {0.1, 0.05, 0.025, 0.0125};
  for (double h : s.h) s.error.push_back(h * h + 1e-4);  // error floor
  s.formal_order = 2.0;
  s.order_tolerance = 0.15;
  vv::fit_order(s);
  EXPECT_FALSE(s.asymptotic);
}

TEST(Convergence, NeedsThreeLevels) {
  io::ConvergenceSeries s;
  s.h = {0.1, 0.05};
  s.error = {1, 0.25};
  EXPECT_THROW(vv::fit_order(s), std::invalid_argument);
}

TEST(LimitFit, ExactPowerLawGivesLimitAndOrder) {
  const std::vector<double> h{0.4, 0.3, 0.25, 0.2};
  std::vector<double> q;
  for (double x : h) q.push_back(1.4 + 2.7 * std::pow(x, 1.7));  // worked: q(0.4) = 1.4 + 2.7 * 0.2106 = 1.969
  const vv::LimitFit f = vv::fit_limit_and_order(h, q);
  EXPECT_NEAR(f.order, 1.7, 2e-3);
  EXPECT_NEAR(f.limit, 1.4, 2e-3);
  EXPECT_NEAR(f.coefficient, 2.7, 1e-2);
  EXPECT_LT(f.residual_rms, 1e-4);
}

TEST(LimitFit, DecreasingFromBelowGivesNegativeCoefficient) {
  const std::vector<double> h{0.4, 0.2, 0.1};
  const std::vector<double> q{0.25 - 0.16, 0.25 - 0.04, 0.25 - 0.01};  // 0.25 − h²
  const vv::LimitFit f = vv::fit_limit_and_order(h, q);
  EXPECT_NEAR(f.order, 2.0, 2e-3);
  EXPECT_NEAR(f.limit, 0.25, 1e-4);
  EXPECT_NEAR(f.coefficient, -1.0, 1e-2);
}

TEST(LimitFit, NeedsThreeLevels) {
  EXPECT_THROW(vv::fit_limit_and_order({0.4, 0.2}, {1.0, 0.5}), std::invalid_argument);
}
