#pragma once
// Polygon geometry behind the index field (index_field.hpp): node wrapping on a
// domain, even–odd crossings of a node row, clipped area. Lattice units, node (i, j)
// at (i + ½, j + ½).
#include <cmath>
#include <cstddef>
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

// x at which the edges cross the horizontal line y = py, sorted ascending (even–odd
// rule: edge (A, B) crosses when (A.y > py) ≠ (B.y > py)). Inside ⇔ #(x_c ≤ px) odd.
void row_crossings(const membrane::Polygon& p, double py, std::vector<double>& xs);

// Node index range [first, last] of unwrapped node coordinates whose centres k + ½ lie
// in [lo, hi] (first > last when empty).
inline void node_range(double lo, double hi, int& first, int& last) {
  // ceil / floor by truncation (std::ceil is a library call without SSE4.1).
  const double a = lo - 0.5, b = hi - 0.5;
  first = static_cast<int>(a);
  if (static_cast<double>(first) < a) ++first;
  last = static_cast<int>(b);
  if (static_cast<double>(last) > b) --last;
}

// |area| of the polygon clipped to the domain along its non-periodic axes ([0, nx] or
// [0, ny], Sutherland–Hodgman), taken with the polygon's orientation (positive for a
// counter-clockwise polygon). Periodic axes are not clipped.
double clipped_area(const membrane::Polygon& p, const ib::Domain& d);

}  // namespace erythro::interior

