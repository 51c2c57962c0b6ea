#pragma once
// c ? a : b, chosen through the bits: the same value, bit for bit, with a and b both computed.
// Written as `c ? a : b`, a loop of such choices vectorises on processors with masked vector
// operations (AVX-512) but, on those without them (AVX2), GCC keeps it as a branch: under the
// default -ftrapping-math it may not compute, in every lane, a floating-point operation that the
// branch would skip (docs/performance-coupled-step.md, "Vector loops on AVX2 hosts" and "The membrane's loops
// on AVX2 hosts"). For hot loops, marked `omp simd` or vectorised by the compiler on its own,
// whose every lane must give the bits of the scalar code.
#include <bit>
#include <cstdint>

namespace erythro::numeric {

[[gnu::always_inline]] inline double select_bits(bool c, double a, double b) {
  const std::uint64_t keep = std::uint64_t{0} - static_cast<std::uint64_t>(c);  // all ones when c
  return std::bit_cast<double>((std::bit_cast<std::uint64_t>(a) & keep) | (std::bit_cast<std::uint64_t>(b) & ~keep));
}

}  // namespace erythro::numeric
