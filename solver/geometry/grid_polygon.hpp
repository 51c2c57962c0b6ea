#pragma once
// A closed polygon on the node grid: node wrapping on a domain, even–odd crossings of a
// node row, area clipped to the walls or to a node's square, signed distance, and the
// nodes inside by ray casting. Lattice units, node (i, j) at (i + ½, j + ½).
// Used by the index field (interior/), the transport's area fractions (transport/) and
// the still-medium cells of a scene (simulation/).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/domain.hpp"
#include "geometry/polygon.hpp"

namespace erythro::geometry {

// i mod n in [0, n) on a periodic axis of n nodes. Nearly every node a kernel support or
// a band visits lies inside the axis or one period off: those skip the integer division.
inline int wrap_periodic(int i, int n) {
  if (i >= 0 && i < n) return i;
  if (i < 0 && i >= -n) return i + n;
  if (i >= n && i < 2 * n) return i - n;
  return ((i % n) + n) % n;
}

// Index of unwrapped node coordinate i on an axis of n nodes: i mod n when periodic,
// −1 when the node lies beyond a wall (non-periodic axis, i ∉ [0, n)).
inline int wrap_node(int i, int n, bool periodic) {
  if (i >= 0 && i < n) return i;
  return periodic ? wrap_periodic(i, n) : -1;
}

// Node index range [first, last] of unwrapped node coordinates whose centres k + ½ lie
// in [lo, hi] (first > last when empty).
inline void node_range(double lo, double hi, int& first, int& last) {
  // One rounding instruction each with SSE4.1 (the native build); a library call without.
  first = static_cast<int>(std::ceil(lo - 0.5));
  last = static_cast<int>(std::floor(hi - 0.5));
}

// x at which the edges cross the horizontal line y = py, sorted ascending (even–odd
// rule: edge (A, B) crosses when (A.y > py) ≠ (B.y > py)). Inside ⇔ #(x_c ≤ px) odd.
void row_crossings(const Polygon& p, double py, std::vector<double>& xs);

// |area| of the polygon clipped to the domain along its non-periodic axes ([0, nx] or
// [0, ny], Sutherland–Hodgman), taken with the polygon's orientation (positive for a
// counter-clockwise polygon). Periodic axes are not clipped.
double clipped_area(const Polygon& p, const Domain& d);
// Whether the box [x0, x1] × [y0, y1] lies within the walls (periodic axes have none):
// then clipped_area is the polygon's own signed area.
bool within_walls(const Domain& d, double x0, double x1, double y0, double y1);

// Area of the polygon inside the box [x0, x1] × [y0, y1] (Sutherland–Hodgman), with the
// polygon's orientation (positive for a counter-clockwise polygon); 0 when they miss.
// E.g. the area fraction of node (i, j)'s square: area_in_box(p, i, i + 1, j, j + 1).
double area_in_box(const Polygon& p, double x0, double x1, double y0, double y1);

// Shortest signed distance from (px, py) to the closed polygon's edges (segments),
// negative inside (even–odd rule), in the polygon's units. O(markers).
double signed_distance(const Polygon& p, double px, double py);

// Even–odd ray-casting interior mask (1 inside) of one polygon on a domain (periodic
// wrap aware: a node is inside when any of its periodic images lies inside).
std::vector<std::uint8_t> ray_cast_inside(const Polygon& p, const Domain& d);
// The same as a list of node indices (row by row over the polygon's rows), without a
// full-grid mask: O(rows spanned + interior nodes), ascending, each node once. `nodes`
// is cleared first.
void ray_cast_inside_nodes(const Polygon& p, const Domain& d, std::vector<std::size_t>& nodes);

}  // namespace erythro::geometry
