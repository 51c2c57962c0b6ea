#pragma once
// sin(πx/2) and cos(πx/2) for 0 ≤ x ≤ 1 in plain IEEE arithmetic (docs/model.md §2, eq 2.4a),
// for the cosine kernel's weights: one call per marker and axis gives all four weights. Like
// numeric::exp_portable it is inline fused multiply–adds only, so a loop over markers need not
// call the C library, and the weights are the same bits with any libm, in a vector loop or a
// scalar one, on any thread.
//
// Method: by symmetry, sin(πx/2) = cos(πy/2) and cos(πx/2) = sin(πy/2) with y = 1 − x (exact for
// x ≥ ½), so both come from y = min(x, 1 − x) ∈ [0, ½], where the Taylor series of sin(πy/2) to
// degree 17 and of cos(πy/2) to degree 18 leave out less than 8.3e−20 and 3.3e−21. Horner form
// in u = y²; the coefficients ±(π/2)ⁿ/n! are the correctly rounded doubles of the exact values
// (computed to 60 digits). Accuracy: within 1.5e−16 absolute of the exact values over [0, 1]
// (1.3 ulp of the values in [½, 1); the C library's sin and cos of the rounded πx/2, which the
// weights used before, 1.3e−16 and 1.9e−16), measured against long double (unit test
// PortableSinCos.*). The choice between x and 1 − x is a select, so a loop still vectorises.
#include <array>
#include <cmath>

#include "common/horner.hpp"
#include "common/select_bits.hpp"

namespace erythro::numeric {

inline void sin_cos_half_pi(double x, double& s, double& c) {
  const bool low = x <= 0.5;
  const double y = select_bits(low, x, 1.0 - x);  // a vector loop of these on AVX2 too (select_bits.hpp)
  const double u = y * y;
  // sin(πy/2)/y and cos(πy/2) as polynomials in u = y², highest degree first.
  static constexpr std::array<double, 9> kSin = {
      0x1.aaec32af93359p-38,  // degree 17 (of the sine)
      -0x1.6fadb9f155744p-31, 0x1.e8f434d018d63p-25, -0x1.e3074fde8871fp-19, 0x1.50783487ee782p-13,
      -0x1.32d2cce62bd86p-8,  0x1.466bc6775aae2p-4,  -0x1.4abbce625be53p-1,
      0x1.921fb54442d18p+0,  // degree 1: π/2
  };
  static constexpr std::array<double, 10> kCos = {
      -0x1.2a0c591af8314p-41,  // degree 18
      0x1.20c62c2f2d7f5p-34,
      -0x1.b6e24f44b128fp-28,
      0x1.f9d38a3763cc3p-22,
      -0x1.a6d1f2a204a8cp-16,
      0x1.e1f506891babbp-11,
      -0x1.55d3c7e3cbffap-6,
      0x1.03c1f081b5ac4p-2,
      -0x1.3bd3cc9be45dep+0,
      1.0,  // degree 0
  };
  const double sin_y = y * horner(u, kSin);
  const double cos_y = horner(u, kCos);
  s = low ? sin_y : cos_y;
  c = low ? cos_y : sin_y;
}

}  // namespace erythro::numeric
