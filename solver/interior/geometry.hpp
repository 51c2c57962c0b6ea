#pragma once
// The index field's own geometry (index_field.hpp): eq 26 in and beyond the band, and
// the node box of a cell (BoxAxis). The polygon-on-grid helpers it builds on live in
// geometry/grid_polygon.hpp. Lattice units, node (i, j) at (i + ½, j + ½).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "geometry/grid_polygon.hpp"

namespace erythro::interior {

using geometry::node_range;
using geometry::wrap_node;

// Eq 26 (thesis §II.4) inside the band, |d| < w (w = 2h): H(d) = ½[1 + d/w + (1/π) sin(πd/w)].
// Branch-free (a loop over a row of distances vectorises); outside the band the value is
// meaningless, and eq26 below adds the 0 / 1 beyond it.
inline double eq26_in_band(double d, double half_width) {
  const double r = d / half_width;
  // sin(πr) for |r| < 1 by symmetry sin(πr) = sin(π(1 − r)) reduced to |x| ≤ π/2 and the
  // Taylor series to x²¹ (truncation < 2e-18): libm-free, about 3× faster, same to 1 ulp.
  const double rr = r > 0.5 ? 1.0 - r : r < -0.5 ? -1.0 - r : r;
  const double x = std::numbers::pi * rr, x2 = x * x;
  double p = 1.0 / 51090942171709440000.0;  // 1/21!
  constexpr double kInvFact[] = {1.0 / 121645100408832000.0, 1.0 / 355687428096000.0, 1.0 / 1307674368000.0,
                                 1.0 / 6227020800.0, 1.0 / 39916800.0, 1.0 / 362880.0, 1.0 / 5040.0, 1.0 / 120.0,
                                 1.0 / 6.0, 1.0};  // 1/19! … 1/1!
  for (double c : kInvFact) p = c - x2 * p;
  return 0.5 * (1.0 + r + rr * p);  // x·p/π = rr·p
}

// Eq 26 everywhere: 0 for d ≤ −w, 1 for d ≥ w, eq26_in_band between. Inline for the band
// pass; interior::smoothed_heaviside is the public name.
inline double eq26(double d, double half_width) {
  if (d <= -half_width) return 0.0;
  if (d >= half_width) return 1.0;
  return eq26_in_band(d, half_width);
}

// One axis of a cell's node box (band_pass.cpp): the unwrapped node coordinates
// [origin, origin + size) that can lie within reach of the cell's edges, clipped at walls.
// A periodic axis whose box would be wider than the domain is folded: the box is then the
// whole axis (origin 0, size n) indexed by the wrapped coordinate, so that no node has two
// box entries. Otherwise each box entry is one node and no index is wrapped in the box.
struct BoxAxis {
  int origin = 0, size = 0, n = 0;
  bool periodic = false, folded = false;

  // The box of node centres in [lo, hi] on an axis of n nodes.
  static BoxAxis covering(double lo, double hi, int n, bool periodic) {
    int a, b;
    node_range(lo, hi, a, b);
    if (!periodic) {
      a = std::max(a, 0);
      b = std::min(b, n - 1);
    }
    BoxAxis ax{a, std::max(0, b - a + 1), n, periodic, false};
    if (periodic && ax.size > n) ax = {0, n, n, true, true};
    return ax;
  }
  // Box index of unwrapped node coordinate c; −1 outside the box (beyond a wall).
  int index(int c) const {
    if (folded) return wrap_node(c, n, true);
    const int b = c - origin;
    return b >= 0 && b < size ? b : -1;
  }
  // Node index on the axis of box index b.
  int node(int b) const { return folded ? b : wrap_node(origin + b, n, periodic); }
  // Box index of the neighbour of b at offset ±1; −1 beyond a wall.
  int neighbour(int b, int step) const {
    const int c = b + step;
    if (folded) return c < 0 ? c + n : c >= n ? c - n : c;
    return c >= 0 && c < size ? c : -1;
  }
};

}  // namespace erythro::interior

