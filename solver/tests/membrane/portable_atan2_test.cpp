// Unit tests of numeric::atan2_portable (common/portable_atan2.hpp), the membrane's turning angle
// (model.md eq 3.6a): accuracy against long double over the whole circle and for small angles,
// C's signed zeros and ±π, and the same bits from a vectorised loop as from single calls.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "common/portable_atan2.hpp"

using erythro::numeric::atan2_portable;

namespace {
long double exact(double y, double x) { return std::atan2(static_cast<long double>(y), static_cast<long double>(x)); }
}  // namespace

TEST(PortableAtan2, WithinAFewUlpOverTheWholeCircle) {
  // Angles spread over (−π, π] at radii from 1e-3 to 1e3, and the octant edges |y| = |x|, y = 0, x = 0.
  std::mt19937_64 gen(5);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi), log_r(-3.0, 3.0);
  long double worst = 0;
  double at_y = 0.0, at_x = 0.0;
  for (int i = 0; i < 2000000; ++i) {
    const double a = angle(gen), r = std::pow(10.0, log_r(gen));
    const double y = r * std::sin(a), x = r * std::cos(a);
    const long double e = std::fabs(atan2_portable(y, x) - exact(y, x));
    if (e > worst) worst = e, at_y = y, at_x = x;
  }
  for (double s : {1.0, -1.0})
    for (double c : {1.0, -1.0}) {
      EXPECT_NEAR(atan2_portable(s, c), static_cast<double>(exact(s, c)), 2.5e-16);
      EXPECT_NEAR(atan2_portable(s * 0.3, c), static_cast<double>(exact(s * 0.3, c)), 2.5e-16);
    }
  // 2.5e-16: the final sum's half ulp (2.2e-16 near π) plus the reduction's and the polynomial's
  // rounding; measured 2.43e-16, 1.1 ulp of an angle near 1.1. The C library's atan2 is correctly
  // rounded, within half an ulp.
  EXPECT_LE(static_cast<double>(worst), 2.5e-16) << "at y = " << at_y << ", x = " << at_x;
}

TEST(PortableAtan2, RelativelyAccurateForSmallTurningAngles) {
  // A membrane's turning angles are small (θ ≲ 0.3 at the V&V resolutions): relative error ≤ 2 ulp.
  long double worst = 0;
  for (int i = 1; i <= 1000000; ++i) {
    const double a = 0.39 * std::pow(1e-12, double(i) / 1e6);  // from 0.39 down to 3.9e-13
    const double y = std::sin(a), x = std::cos(a);
    const long double ex = exact(y, x);
    worst = std::max(worst, std::fabs((atan2_portable(y, x) - ex) / ex));
    worst = std::max(worst, std::fabs((atan2_portable(-y, x) + ex) / ex));
  }
  EXPECT_LE(static_cast<double>(worst), 2.0 * 0x1p-53);
}

TEST(PortableAtan2, SignedZerosAndPiAsInC) {  // exactly C's values: π and π/2 are the doubles nearest them
  EXPECT_EQ(atan2_portable(0.0, 1.0), 0.0);
  EXPECT_TRUE(std::signbit(atan2_portable(-0.0, 1.0)));
  EXPECT_EQ(atan2_portable(0.0, 0.0), 0.0);
  EXPECT_EQ(atan2_portable(0.0, -1.0), std::numbers::pi);
  EXPECT_EQ(atan2_portable(-0.0, -1.0), -std::numbers::pi);
  EXPECT_EQ(atan2_portable(0.0, -0.0), std::numbers::pi);
  EXPECT_EQ(atan2_portable(1.0, 0.0), std::numbers::pi / 2);
  EXPECT_EQ(atan2_portable(-1.0, 0.0), -std::numbers::pi / 2);
  EXPECT_TRUE(std::isnan(atan2_portable(std::nan(""), 1.0)));
}

TEST(PortableAtan2, VectorLoopGivesTheScalarBits) {
  std::vector<double> y(1003), x(y.size()), v(y.size());
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double a = -3.1 + 0.0062 * double(i);
    y[i] = std::sin(a) * (1.0 + 1e-3 * double(i % 7));
    x[i] = std::cos(a);
  }
  double* __restrict out = v.data();
  const double* __restrict iy = y.data();
  const double* __restrict ix = x.data();
#pragma omp simd
  for (std::size_t i = 0; i < y.size(); ++i) out[i] = atan2_portable(iy[i], ix[i]);
  for (std::size_t i = 0; i < y.size(); ++i) {
    volatile double yi = y[i];  // one call at a time, not vectorised
    ASSERT_EQ(v[i], atan2_portable(yi, x[i])) << i;
  }
}
