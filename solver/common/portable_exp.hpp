#pragma once
// e^x in plain IEEE arithmetic (docs/model.md §4 eq 4.8a, "The exponential of the pair laws"), so
// that a loop over many arguments vectorises and every lane gives the bits of the scalar
// call: the same result in a vector loop, a scalar loop, on any thread. The library's
// std::exp is a call the compiler cannot vectorise, and its vector variants round
// differently from it.
//
// Method (Cody–Waite reduction, Taylor polynomial): x = k ln 2 + r with k = round(x/ln 2),
// |r| ≤ ln 2 / 2, e^x = 2^k e^r. k is rounded by adding 1.5·2^52 (its integer then sits
// in the low bits of the sum), r = (x − k ln2_hi) − k ln2_lo with ln2_hi's last 11 bits
// zero (k ln2_hi exact for |k| < 2^11), e^r by its Taylor series to r^13/13! (remainder
// < 5e−18 relative at |r| = 0.347) in Horner form with fused multiply–adds, and 2^k
// written into the exponent bits. Accuracy: within 1 ulp of the exact value, measured
// against long double over [−700, 700] (unit test PortableExp.*).
//
// Domain: |x| ≤ 700 (2^k stays a normal number). Callers: the Morse law (arguments
// β(r0 − r) with 0 < r < r_c, a few units).
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "common/horner.hpp"

namespace erythro::numeric {

inline double exp_portable(double x) {
  constexpr double kLog2e = 1.4426950408889634074;
  constexpr double kShifter = 0x1.8p52;                  // 1.5·2^52: x·log2e + it rounds to an integer
  constexpr double kLn2Hi = 0x1.62e42fefa3800p-1;        // ln 2, last 11 bits of the mantissa zero
  constexpr double kLn2Lo = 0x1.ef35793c76730p-45;       // ln 2 − kLn2Hi
  const double kd = x * kLog2e + kShifter;
  const double k = kd - kShifter;
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;
  static constexpr std::array<double, 14> kTaylor = {
      // 1/n!, n = 13 … 0
      1.0 / 6227020800.0,
      1.0 / 479001600.0,
      1.0 / 39916800.0,
      1.0 / 3628800.0,
      1.0 / 362880.0,
      1.0 / 40320.0,
      1.0 / 5040.0,
      1.0 / 720.0,
      1.0 / 120.0,
      1.0 / 24.0,
      1.0 / 6.0,
      0.5,
      1.0,
      1.0,
  };
  const double p = horner(r, kTaylor);
  // 2^k: kd's bits are those of 1.5·2^52 plus k (|k| < 2^51), so k + 1023 shifted into the
  // exponent field is bits(kd) − bits(1.5·2^52) + 1023, in wrapping unsigned arithmetic.
  const std::uint64_t biased = std::bit_cast<std::uint64_t>(kd) - std::bit_cast<std::uint64_t>(kShifter) + 1023u;
  return p * std::bit_cast<double>(biased << 52);
}

}  // namespace erythro::numeric
