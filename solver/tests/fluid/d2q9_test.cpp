// Unit checks of the D2Q9 velocity set and equilibrium (docs/model.md §1).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "lattice/d2q9.hpp"

using namespace erythro::d2q9;

TEST(D2Q9, WeightsSumToOneAndIsotropy) {
  double sum = 0, sxx = 0, sxy = 0, syy = 0, sx = 0;
  for (int i = 0; i < Q; ++i) {
    sum += w[i];
    sx += w[i] * cx[i];
    sxx += w[i] * cx[i] * cx[i];
    syy += w[i] * cy[i] * cy[i];
    sxy += w[i] * cx[i] * cy[i];
  }
  EXPECT_DOUBLE_EQ(sum, 1.0);
  EXPECT_DOUBLE_EQ(sx, 0.0);
  EXPECT_DOUBLE_EQ(sxx, cs2);
  EXPECT_DOUBLE_EQ(syy, cs2);
  EXPECT_DOUBLE_EQ(sxy, 0.0);
}

TEST(D2Q9, OppositeDirections) {
  for (int i = 0; i < Q; ++i) {
    EXPECT_EQ(cx[opposite[i]], -cx[i]);
    EXPECT_EQ(cy[opposite[i]], -cy[i]);
    EXPECT_EQ(w[opposite[i]], w[i]);
  }
}

TEST(D2Q9, EquilibriumMomentsAreExact) {
  const double rho = 1.03, ux = 0.04, uy = -0.07;
  double m0 = 0, mx = 0, my = 0, pxx = 0, pxy = 0;
  for (int i = 0; i < Q; ++i) {
    const double f = equilibrium(i, rho, ux, uy);
    m0 += f;
    mx += f * cx[i];
    my += f * cy[i];
    pxx += f * cx[i] * cx[i];
    pxy += f * cx[i] * cy[i];
  }
  EXPECT_NEAR(m0, rho, 1e-15);
  EXPECT_NEAR(mx, rho * ux, 1e-15);
  EXPECT_NEAR(my, rho * uy, 1e-15);
  EXPECT_NEAR(pxx, rho * cs2 + rho * ux * ux, 1e-15);  // Π^eq = ρ c_s² I + ρ u u
  EXPECT_NEAR(pxy, rho * ux * uy, 1e-15);
}

TEST(D2Q9, DotWithADirectionEqualsTheWrittenOutProduct) {
  // dot_c writes c_1·a and c_2·a without their zero term: the same value as cx·a_x + cy·a_y
  // for every a, and the same bits unless the kept component is −0 (then only the sign of the
  // zero result may differ); every other direction exactly as written.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> values{0.0, -0.0, 1.0, -1.0, 1e-300, -1e-300, 0.1, -0.1};
  for (int k = 0; k < 1000; ++k) values.push_back(u(rng) * std::pow(10.0, static_cast<int>(rng() % 30) - 15));
  auto negative_zero = [](double v) { return v == 0.0 && std::signbit(v); };
  for (int i = 0; i < Q; ++i)
    for (const double ax : values)
      for (const double ay : values) {
        const double written = cx[i] * ax + cy[i] * ay, fast = dot_c(i, ax, ay);
        ASSERT_EQ(fast, written) << i << " " << ax << " " << ay;
        if ((i == 1 && negative_zero(ax)) || (i == 2 && negative_zero(ay))) continue;
        ASSERT_EQ(std::bit_cast<std::uint64_t>(fast), std::bit_cast<std::uint64_t>(written)) << i << " " << ax << " " << ay;
      }
}
