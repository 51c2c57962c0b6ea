#pragma once
// Polygon geometry behind the index field (index_field.hpp): node wrapping on a
// domain, even–odd crossings of a node row, clipped area. Lattice units, node (i, j)
// at (i + ½, j + ½).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "ib/domain.hpp"
#include "membrane/polygon.hpp"

namespace erythro::interior {

// Index of unwrapped node coordinate i on an axis of n nodes: i mod n when periodic,
// −1 when the node lies beyond a wall (non-periodic axis, i ∉ [0, n)).
inline int wrap_node(int i, int n, bool periodic) {
  if (i >= 0 && i < n) return i;
  if (!periodic) return -1;
  if (i < 0 && i >= -n) return i + n;  // one period off: no integer division
  if (i >= n && i < 2 * n) return i - n;
  return ((i % n) + n) % n;
}

// Node index range [first, last] of unwrapped node coordinates whose centres k + ½ lie
// in [lo, hi] (first > last when empty).
inline void node_range(double lo, double hi, int& first, int& last) {
  // One rounding instruction each with SSE4.1 (the native build); a library call without.
  first = static_cast<int>(std::ceil(lo - 0.5));
  last = static_cast<int>(std::floor(hi - 0.5));
}

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

// x at which the edges cross the horizontal line y = py, sorted ascending (even–odd
// rule: edge (A, B) crosses when (A.y > py) ≠ (B.y > py)). Inside ⇔ #(x_c ≤ px) odd.
void row_crossings(const membrane::Polygon& p, double py, std::vector<double>& xs);

// |area| of the polygon clipped to the domain along its non-periodic axes ([0, nx] or
// [0, ny], Sutherland–Hodgman), taken with the polygon's orientation (positive for a
// counter-clockwise polygon). Periodic axes are not clipped.
double clipped_area(const membrane::Polygon& p, const ib::Domain& d);
// Whether the box [x0, x1] × [y0, y1] lies within the walls (periodic axes have none):
// then clipped_area is the polygon's own signed area.
bool within_walls(const ib::Domain& d, double x0, double x1, double y0, double y1);

// Area of the polygon inside the box [x0, x1] × [y0, y1] (Sutherland–Hodgman), with the
// polygon's orientation (positive for a counter-clockwise polygon); 0 when they miss.
// E.g. the area fraction of node (i, j)'s square: area_in_box(p, i, i + 1, j, j + 1).
double area_in_box(const membrane::Polygon& p, double x0, double x1, double y0, double y1);

}  // namespace erythro::interior

