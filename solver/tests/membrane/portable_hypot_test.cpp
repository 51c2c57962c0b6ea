// Unit tests of numeric::hypot_portable (common/portable_hypot.hpp): within one ulp of the
// exact value, the C library's bits where the library uses the same method, and the same
// bits from a vectorised loop as from single calls.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "common/portable_hypot.hpp"
#include "tests/ulp_error.hpp"

using erythro::numeric::hypot_portable;
using erythro::testing::ulp_error;

namespace {

// Arguments as the membrane and contact loops see them (edge vectors and forces of a few
// lattice units down to 1e-12), ratios near 1 and near 2 (the kernel's two branches), and
// wide exponents.
std::vector<std::pair<double, double>> arguments() {
  std::mt19937_64 g(20261204);
  std::uniform_real_distribution<double> u(-3.0, 3.0), e(-60.0, 60.0);
  std::vector<std::pair<double, double>> a;
  for (int i = 0; i < 1000000; ++i) a.emplace_back(u(g), u(g));
  for (int i = 0; i < 300000; ++i) {
    a.emplace_back(std::ldexp(u(g), int(e(g))), std::ldexp(u(g), int(e(g))));
    const double x = u(g);
    a.emplace_back(x, x * (1.0 + 1e-3 * u(g)));
    a.emplace_back(x, 0.5 * x * (1.0 + 1e-8 * u(g)));
  }
  return a;
}

}  // namespace

TEST(PortableHypot, WithinOneUlp) {
  double worst = 0.0;
  for (const auto& [x, y] : arguments()) {
    const long double exact = std::sqrt(static_cast<long double>(x) * x + static_cast<long double>(y) * y);
    worst = std::max(worst, ulp_error(hypot_portable(x, y), exact));
  }
  EXPECT_LT(worst, 1.0);
}

TEST(PortableHypot, SpecialArgumentsAsTheLibrary) {
  const double inf = INFINITY;
  EXPECT_EQ(hypot_portable(0.0, 0.0), 0.0);
  EXPECT_EQ(hypot_portable(-2.5, 0.0), 2.5);  // a horizontal or vertical edge: exact
  EXPECT_EQ(hypot_portable(0.0, -1e-3), 1e-3);
  EXPECT_EQ(hypot_portable(3.0, 4.0), 5.0);
  EXPECT_EQ(hypot_portable(1e300, 1e300), std::hypot(1e300, 1e300));
  EXPECT_EQ(hypot_portable(1e-300, 3e-300), std::hypot(1e-300, 3e-300));
  EXPECT_EQ(hypot_portable(inf, 1.0), inf);
  EXPECT_TRUE(std::isnan(hypot_portable(NAN, 1.0)));
}

// Against the C library's hypot. The GNU C library (2.35 and later) uses the same method
// without fused multiply-add on x86-64: there the two agree bit for bit, which is why
// replacing the library call in the membrane and contact loops changed no result. Any other
// library is within its own ulp of the exact value, as this function is, so the two are at
// most one representable number apart.
TEST(PortableHypot, AgreesWithTheLibrary) {
#if defined(__GLIBC__) && defined(__x86_64__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 35))
  constexpr bool kSameMethod = true;
#else
  constexpr bool kSameMethod = false;
#endif
  std::size_t differ = 0, apart = 0;
  for (const auto& [x, y] : arguments()) {
    const double ours = hypot_portable(x, y), library = std::hypot(x, y);
    differ += ours != library;
    apart += ours != library && std::nextafter(ours, library) != library;
  }
  EXPECT_EQ(apart, 0u);
  if (kSameMethod) {
    EXPECT_EQ(differ, 0u);
  }
}

TEST(PortableHypot, VectorLoopGivesTheScalarBits) {
  const auto args = arguments();
  const std::size_t n = 100003;
  std::vector<double> x(n), y(n), vec(n);
  for (std::size_t i = 0; i < n; ++i) std::tie(x[i], y[i]) = args[i * 7];
  double* __restrict out = vec.data();
  const double* __restrict px = x.data();
  const double* __restrict py = y.data();
#pragma omp simd
  for (std::size_t i = 0; i < n; ++i) out[i] = hypot_portable(px[i], py[i]);
  for (std::size_t i = 0; i < n; ++i) {
    volatile double xi = x[i];  // one call at a time, not vectorised
    ASSERT_EQ(std::bit_cast<std::uint64_t>(vec[i]), std::bit_cast<std::uint64_t>(hypot_portable(xi, y[i]))) << i;
  }
}

// A zero component stays on the fast path: the other's magnitude, the library's bits (C Annex
// F: hypot(x, ±0) = |x|), for every size of x, subnormal, infinite and NaN included.
TEST(PortableHypot, ZeroComponentAsTheLibrary) {
  const double inf = INFINITY;
  for (const double x : {0.0, -0.0, 4.9e-324, 1e-310, 0x1p-500, 1e-100, 0.7, 3.0, 1e100, 0x1p600, 1.7e308, inf, -inf}) {
    for (const double zero : {0.0, -0.0}) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(hypot_portable(x, zero)), std::bit_cast<std::uint64_t>(std::hypot(x, zero)))
          << x;
      EXPECT_EQ(std::bit_cast<std::uint64_t>(hypot_portable(zero, x)), std::bit_cast<std::uint64_t>(std::hypot(zero, x)))
          << x;
    }
  }
  EXPECT_TRUE(std::isnan(hypot_portable(NAN, 0.0)));
  EXPECT_TRUE(std::isnan(hypot_portable(0.0, NAN)));
}

// The edge lengths of a closed polygon: hypot_portable's bits for each edge, whether every
// edge is in the fast path's range (a ring with horizontal and vertical edges among them) or
// one is not (two coincident vertices' tiny neighbour: the whole polygon again, by the call).
TEST(PortableHypot, ClosedPolygonLengthsAreTheCallsBits) {
  const std::size_t n = 37;
  std::vector<double> x(n), y(n), len(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = 2.0 * 3.141592653589793 * double(k) / double(n);
    x[k] = 10.0 + 3.0 * std::cos(t);
    y[k] = 7.0 + 2.0 * std::sin(t);
  }
  y[5] = y[4];  // a horizontal edge
  x[9] = x[8];  // a vertical one
  auto check = [&] {
    erythro::numeric::closed_polygon_lengths(x.data(), y.data(), n, len.data());
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t f = k + 1 == n ? 0 : k + 1;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(len[k]),
                std::bit_cast<std::uint64_t>(hypot_portable(x[f] - x[k], y[f] - y[k])))
          << k;
    }
  };
  check();
  x[20] = x[19] + 1e-300;  // an edge far below the kernel's range
  y[20] = y[19] + 3e-301;
  check();
}
