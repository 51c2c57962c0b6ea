#pragma once
// atan2(y, x) in plain IEEE arithmetic (docs/model.md §3, eq 3.6a), for the membrane's turning
// angles: inline, so a loop over markers need not call the C library, and the same bits with
// any libm, in a vector loop or a scalar one, on any thread (like numeric::exp_portable and
// numeric::sin_cos_half_pi).
//
// Method: t = min(|x|, |y|) / max(|x|, |y|) ∈ [0, 1]; above tan(π/8), atan t = π/4 + atan r with
// r = (t − 1)/(t + 1), so |r| ≤ tan(π/8) either way. On it atan r = r (1 + u Q(u)), u = r²,
// where Q of degree 10 interpolates (atan √u/√u − 1)/u at the 11 Chebyshev nodes of
// [0, tan²(π/8)] (coefficients computed to 60 digits, then rounded to doubles): the polynomial
// 1 + u Q(u) is within 6.8e−18 of atan √u/√u there, 6 % of an ulp. The octant is then undone:
// π/2 − a when |y| > |x|, π − a when x is negative (−0 included), the sign of y last, together
// as k π/4 + σ atan r added once, k π/4 as two doubles (hi + lo). Measured against long double:
// within 2.5e−16 absolute over the whole circle (0.56 ulp of π) and 2 ulp relative for angles
// below π/8 (unit test PortableAtan2.*). The choices are selects through the bits (select_bits.hpp;
// both sides computed, the chosen one's bits kept), so a loop vectorises on AVX2 hosts too.
//
// Domain: finite arguments. atan2(±0, +0) = ±0 and atan2(±0, −0) = ±π, as in C.
#include <array>
#include <cmath>

#include "common/horner.hpp"
#include "common/select_bits.hpp"

namespace erythro::numeric {

inline double atan2_portable(double y, double x) {
  constexpr double kTanPiOver8 = 0x1.a827999fcef32p-2;                             // tan(π/8) = √2 − 1
  constexpr double kPi4Hi = 0x1.921fb54442d18p-1, kPi4Lo = 0x1.1a62633145c07p-55;  // π/4 = hi + lo
  const double ax = std::fabs(x), ay = std::fabs(y);
  const bool steep = ay > ax;
  const double small = select_bits(steep, ax, ay), big = select_bits(steep, ay, ax);
  const double t = select_bits(big > 0.0, small / big, 0.0);  // 0/0 computed at the origin, not chosen
  const bool upper = t > kTanPiOver8;
  const double r = select_bits(upper, (t - 1.0) / (t + 1.0), t);
  const double u = r * r;
  static constexpr std::array<double, 11> kQ = {
      -0x1.3a31b1c0fd3b7p-6,  // degree 10
      0x1.4162c02b1dda3p-5,  -0x1.a0999c632b6edp-5, 0x1.dfe6497e96323p-5,  -0x1.10fa77b1a6d57p-4, 0x1.3b1263064f6b9p-4,
      -0x1.745d0b28a7e37p-4, 0x1.c71c71853d7fap-4,  -0x1.2492492436201p-3, 0x1.999999999934cp-3,
      -0x1.5555555555555p-2,  // degree 0: −1/3
  };
  const double q = horner(u, kQ);
  const double a = std::fma(r * u, q, r);     // atan r
  // Undo the reductions: atan t = k π/4 + σ atan r with k = 1, σ = 1 above tan(π/8); then
  // π/2 − (…) when |y| > |x| and π − (…) when x is negative: one sum at the end.
  double k = upper ? 1.0 : 0.0, sigma = 1.0;
  k = select_bits(steep, 2.0 - k, k);
  sigma = select_bits(steep, -sigma, sigma);
  const bool left = std::copysign(1.0, x) < 0.0;  // x < 0 or x = −0 (signbit does not vectorise)
  k = select_bits(left, 4.0 - k, k);
  sigma = select_bits(left, -sigma, sigma);
  const double base_hi = k * kPi4Hi;
  const double base_lo = std::fma(k, kPi4Hi, -base_hi) + k * kPi4Lo;  // k π/4 − base_hi
  const double angle = (base_lo + sigma * a) + base_hi;
  return std::copysign(angle, y);
}

}  // namespace erythro::numeric
