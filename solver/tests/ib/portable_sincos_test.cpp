// Unit tests of numeric::sin_cos_half_pi (common/portable_sincos.hpp), the cosine kernel's
// weights (model.md eq 2.4a): accuracy against long double, the four weights against φ, and the
// same bits from a vectorised loop as from single calls.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "common/portable_sincos.hpp"
#include "ib/kernel.hpp"

using erythro::numeric::sin_cos_half_pi;

TEST(PortableSinCos, AsAccurateAsTheLibraryOverTheUnitInterval) {
  const long double half_pi = std::numbers::pi_v<long double> / 2;
  long double worst_s = 0, worst_c = 0;
  double at_s = 0.0, at_c = 0.0;
  const int n = 2000000;
  for (int i = 0; i <= n; ++i) {
    const double x = double(i) / double(n) * (1.0 - 1e-12) + 1e-13 * std::sin(double(i));
    double s, c;
    sin_cos_half_pi(x, s, c);
    const long double es = std::fabs(s - std::sin(half_pi * x)), ec = std::fabs(c - std::cos(half_pi * x));
    if (es > worst_s) worst_s = es, at_s = x;
    if (ec > worst_c) worst_c = ec, at_c = x;
  }
  // 1.6e-16: 1.5 ulp of the values in [½, 1) (measured 1.47e-16 and 1.49e-16; the C library's sin and
  // cos of the rounded argument πx/2, the former weights, 1.33e-16 and 1.85e-16)
  const double bound = 1.6e-16;
  EXPECT_LE(static_cast<double>(worst_s), bound) << "sin at x = " << at_s;
  EXPECT_LE(static_cast<double>(worst_c), bound) << "cos at x = " << at_c;
  double s, c;
  sin_cos_half_pi(0.0, s, c);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(c, 1.0);
  sin_cos_half_pi(0.5, s, c);  // both √½
  EXPECT_NEAR(s, std::sqrt(0.5), 2e-16);
  EXPECT_NEAR(c, std::sqrt(0.5), 2e-16);
}

TEST(PortableSinCos, TheFourWeightsAreTheCosineKernel) {
  // eq 2.4a against φ of kernel.hpp (the C library's cosine) at r₀ = 1 + x.
  double worst = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double x = (i + 0.37) / 100000.0;
    double s, c;
    sin_cos_half_pi(x, s, c);
    const double w[4] = {0.25 * (1.0 - s), 0.25 * (1.0 + c), 0.25 * (1.0 + s), 0.25 * (1.0 - c)};
    for (int b = 0; b < 4; ++b)
      worst = std::max(worst, std::fabs(w[b] - erythro::ib::Cosine4::phi(1.0 + x - b)));
    EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1.0, 4.5e-16);
  }
  EXPECT_LT(worst, 1.2e-16);
}

TEST(PortableSinCos, VectorLoopGivesTheScalarBits) {
  std::vector<double> x(1003), vs(x.size()), vc(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 0.000997 * double(i) + 1e-9 * double(i % 7);
  double* __restrict os = vs.data();
  double* __restrict oc = vc.data();
  const double* __restrict in = x.data();
#pragma omp simd
  for (std::size_t i = 0; i < x.size(); ++i) sin_cos_half_pi(in[i], os[i], oc[i]);
  for (std::size_t i = 0; i < x.size(); ++i) {
    volatile double xi = x[i];  // one call at a time, not vectorised
    double s, c;
    sin_cos_half_pi(xi, s, c);
    ASSERT_EQ(vs[i], s) << i;
    ASSERT_EQ(vc[i], c) << i;
  }
}
