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
