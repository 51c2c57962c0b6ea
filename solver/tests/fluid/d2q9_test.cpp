// Unit checks of the D2Q9 velocity set and equilibrium (docs/model.md §1).
#include <gtest/gtest.h>

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
