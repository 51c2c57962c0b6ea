// Reaction rate functions (reactions.hpp, eqs R1–R5) and the Hill curve.
#include <gtest/gtest.h>

#include <cmath>

#include "transport/hb_kinetics.hpp"
#include "transport/reactions.hpp"

using namespace erythro::transport;

TEST(Reactions, HillSaturation) {
  EXPECT_DOUBLE_EQ(hill_saturation(26.8), 0.5);
  EXPECT_EQ(hill_saturation(0.0), 0.0);
  EXPECT_NEAR(hill_saturation(100.0), 1.0 / (1.0 + std::pow(26.8 / 100.0, 2.7)), 1e-15);
  EXPECT_GT(hill_saturation(1e6), 1.0 - 1e-12);
  // Monotone, and the Hill slope: d ln(S/(1−S)) / d ln P = n.
  const double P1 = 10.0, P2 = 11.0, S1 = hill_saturation(P1), S2 = hill_saturation(P2);
  EXPECT_LT(S1, S2);
  EXPECT_NEAR(std::log((S2 / (1 - S2)) / (S1 / (1 - S1))) / std::log(P2 / P1), 2.7, 1e-12);
}

TEST(Reactions, NoProduction) {
  EXPECT_DOUBLE_EQ(no_production(4.7, 50.0), 25.0);  // half maximum at K_m
  EXPECT_EQ(no_production(0.0, 50.0), 0.0);
  EXPECT_EQ(no_production(-1.0, 50.0), 0.0);  // no production from a negative overshoot
  EXPECT_NEAR(no_production(1e9, 50.0), 50.0, 1e-6);
  EXPECT_DOUBLE_EQ(no_r_max_from_shear(2.4), 50.0);
  EXPECT_DOUBLE_EQ(no_r_max_from_shear(1.2), 25.0);
}

TEST(Reactions, FirstOrderAndScavenging) {
  EXPECT_DOUBLE_EQ(first_order_consumption(2.0, 1.5), 3.0);
  EXPECT_NEAR(no_scavenging_rate(), 1.4e5 * 20.3e-3, 1e-9);  // 2842 1/s
  EXPECT_DOUBLE_EQ(no_core_scavenging_rate(382.5, 25.0, 0.0), 382.5);
  EXPECT_NEAR(no_core_scavenging_rate(382.5, 25.0, 5.0), 0.5 * 382.5 * (1.0 + 625.0 / 400.0), 1e-12);
}

TEST(Reactions, InhibitedOxygenConsumption) {
  EXPECT_DOUBLE_EQ(o2_consumption(1.0, 0.0, 50.0), 25.0);           // P = K_m, no NO
  EXPECT_DOUBLE_EQ(o2_consumption(2.0, 27e-3, 50.0), 25.0);         // C_NO = C_ref doubles K_m
  EXPECT_LT(o2_consumption(5.0, 0.1, 50.0), o2_consumption(5.0, 0.0, 50.0));  // NO inhibits
  EXPECT_EQ(o2_consumption(0.0, 0.0, 50.0), 0.0);
  EXPECT_NEAR(o2_consumption(1e9, 0.0, 50.0), 50.0, 1e-6);          // zero order at high P
}
