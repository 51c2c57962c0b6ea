#pragma once
// √(x² + y²) in plain IEEE arithmetic (docs/model.md §3 eq 3.7a, "Lengths"), inline, so that
// the membrane and contact loops do not call the C library once per edge and a loop over
// many arguments can vectorise. The method is Borges's corrected hypot (C. F. Borges, "An
// improved algorithm for hypot(a,b)", 2019, arXiv:1904.09481, the variant without fused
// multiply–add): h = √(a² + b²) rounded, then one correction −(t1 + t2)/(2h) with t1 + t2
// the rounding error of h², evaluated without cancellation. The GNU C library's hypot (2.35
// on) uses the same method without FMA on x86-64, so on such a system this gives its bits
// for every argument in the common range (unit test PortableHypot.*): switching the hot
// loops from std::hypot to this changed no result.
//
// Common range (the kernel's): max(|x|, |y|) ≤ 2^511, min(|x|, |y|) ≥ 2^−459 and the
// smaller above 2^−54 times the larger. The fast path adds a zero component (the result is the
// other's magnitude, exactly). Outside it (a ratio beyond 2^54, huge, tiny, infinite or NaN
// arguments) the result is std::hypot's: the sum |x| + |y| when one term is negligible, else
// the library call.
#include <cmath>
#include <cstddef>

#include "common/select_bits.hpp"

namespace erythro::numeric {

// The corrected square root for a ≥ b > 0 in the common range: the rounded h = √(a²+b²),
// then h − (t1 + t2)/(2h), where t1 + t2 = h² − a² − b² written in two ways so that no
// subtraction cancels: around b when h ≤ 2b (δ = h − b), around a otherwise (δ = h − a).
// Both are computed and one is selected through the bits (select_bits.hpp), so a loop of these
// has no branch.
inline double hypot_kernel(double a, double b) {
  const double h = std::sqrt(a * a + b * b);
  const double db = h - b, da = h - a;
  const double t1_near = a * (2.0 * db - a);
  const double t2_near = (db - 2.0 * (a - b)) * db;
  const double t1_far = 2.0 * da * (a - 2.0 * b);
  const double t2_far = (4.0 * da - b) * b + da * da;
  const bool near = h <= 2.0 * b;
  const double t = select_bits(near, t1_near + t2_near, t1_far + t2_far);
  return h - t / (2.0 * h);
}

// Whether (a, b), a ≥ b ≥ 0, lies in the common range of the fast path.
// (`&`, not `&&`: three comparisons without branches, so a loop that tests every argument
// still vectorises.)
inline bool hypot_common_range(double a, double b) {
  constexpr double kLarge = 0x1p511, kTiny = 0x1p-459, kEps = 0x1p-54;
  return (a <= kLarge) & (b >= kTiny) & (b > a * kEps);
}

// The fast path: the common range, or b = 0, whose result is a exactly (std::hypot(x, ±0) is
// |x|, C Annex F): a horizontal or vertical edge, or a zero force, stays on it.
inline bool hypot_fast_range(double a, double b) { return hypot_common_range(a, b) | (b == 0.0); }
// (The kernel is computed for b = 0 too, and not chosen: select_bits.hpp, so a loop of these has
// no branch on AVX2 hosts either.)
inline double hypot_fast(double a, double b) { return select_bits(b == 0.0, a, hypot_kernel(a, b)); }

// a = max(|x|, |y|), b = min(|x|, |y|): the ordered arguments of the paths above.
inline void ordered_magnitudes(double x, double y, double& a, double& b) {
  const double ax = std::fabs(x), ay = std::fabs(y);
  a = ax < ay ? ay : ax;
  b = ax < ay ? ax : ay;
}

// |(x, y)| by the fast path, for a loop that vectorises: `outside` is set when (x, y) lies beyond
// the path's range, and the caller then does the loop again with hypot_portable (whose bits the
// fast path gives wherever it applies).
inline double hypot_fast_flagged(double x, double y, int& outside) {
  double a, b;
  ordered_magnitudes(x, y, a, b);
  outside |= hypot_fast_range(a, b) ? 0 : 1;
  return hypot_fast(a, b);
}

inline double hypot_portable(double x, double y) {
  double a, b;
  ordered_magnitudes(x, y, a, b);
  if (hypot_fast_range(a, b)) [[likely]]
    return hypot_fast(a, b);
  return std::hypot(x, y);
}

// The edge lengths of a closed polygon of n ≥ 1 vertices: len[k] = |X_{k+1} − X_k| for k < n − 1
// and len[n − 1] = |X_0 − X_{n−1}|, each hypot_portable's bits. The open edges go through the
// branch-free fast path in a loop that vectorises; should one of them lie outside its range
// (coincident vertices, say), they are all done again with hypot_portable itself.
inline void closed_polygon_lengths(const double* __restrict x, const double* __restrict y, std::size_t n,
                                   double* __restrict len) {
  int outside = 0;
  for (std::size_t k = 0; k + 1 < n; ++k) len[k] = hypot_fast_flagged(x[k + 1] - x[k], y[k + 1] - y[k], outside);
  if (outside != 0)
    for (std::size_t k = 0; k + 1 < n; ++k) len[k] = hypot_portable(x[k + 1] - x[k], y[k + 1] - y[k]);
  len[n - 1] = hypot_portable(x[0] - x[n - 1], y[0] - y[n - 1]);
}

}  // namespace erythro::numeric
