// Unit tests of numeric::exp_portable (common/portable_exp.hpp): accuracy against long
// double, and the same bits from a vectorised loop as from single calls.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "common/portable_exp.hpp"
#include "tests/ulp_error.hpp"

using erythro::numeric::exp_portable;
using erythro::testing::ulp_error;

TEST(PortableExp, WithinOneUlpOverItsDomain) {
  double worst = 0.0, at = 0.0;
  const int n = 2000000;
  for (int i = 0; i <= n; ++i) {
    const double x = -700.0 + 1400.0 * double(i) / double(n) + 1e-7 * std::sin(double(i));
    const double e = ulp_error(exp_portable(x), std::exp(static_cast<long double>(x)));
    if (e > worst) {
      worst = e;
      at = x;
    }
  }
  // The Morse arguments (a few units) densely.
  for (int i = 0; i <= n; ++i) {
    const double x = -8.0 + 12.0 * double(i) / double(n);
    const double e = ulp_error(exp_portable(x), std::exp(static_cast<long double>(x)));
    if (e > worst) {
      worst = e;
      at = x;
    }
  }
  EXPECT_LT(worst, 1.0) << "at x = " << at;
  EXPECT_EQ(exp_portable(0.0), 1.0);
  EXPECT_EQ(exp_portable(1.0), std::exp(1.0));  // e itself is correctly rounded
}

TEST(PortableExp, VectorLoopGivesTheScalarBits) {
  std::vector<double> x(1003), vec(x.size()), one(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = -6.0 + 0.0091 * double(i) + 1e-9 * double(i % 7);
  double* __restrict out = vec.data();
  const double* __restrict in = x.data();
#pragma omp simd
  for (std::size_t i = 0; i < x.size(); ++i) out[i] = exp_portable(in[i]);
  for (std::size_t i = 0; i < x.size(); ++i) {
    volatile double xi = x[i];  // one call at a time, not vectorised
    one[i] = exp_portable(xi);
  }
  for (std::size_t i = 0; i < x.size(); ++i) ASSERT_EQ(vec[i], one[i]) << i;
}
