#pragma once
// Horner's scheme in fused multiply–adds, the polynomial evaluation the portable elementary
// functions share (numeric::exp_portable, sin_cos_half_pi, atan2_portable):
//   p = c[0];  p = fma(p, u, c[k]) for k = 1 … N − 1,
// so c[0] is the coefficient of the highest degree and c[N − 1] the constant term. Unrolled at
// compile time (no loop, no array read at run time once inlined), so a loop over markers or pairs
// around it still vectorises, and the operations are exactly those written out one by one.
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

namespace erythro::numeric {

template <std::size_t N>
[[gnu::always_inline]] inline double horner(double u, const std::array<double, N>& c) {
  static_assert(N >= 1, "a polynomial has at least its constant term");
  double p = c[0];
  const auto steps = [&]<std::size_t... K>(std::index_sequence<K...>) { ((p = std::fma(p, u, c[K + 1])), ...); };
  steps(std::make_index_sequence<N - 1>{});
  return p;
}

}  // namespace erythro::numeric
