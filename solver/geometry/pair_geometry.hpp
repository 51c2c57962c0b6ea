#pragma once
// Geometry of a pair of cells (a doublet, thesis ch. III; docs/model.md §6), in the
// polygons' length unit: the smallest membrane gap, the equivalent ellipse of the cells
// together, and the shape of a contact line. The second cell is expected next to the
// first (the caller applies the minimum image on periodic axes). Used by the pair probe
// (simulation/probes/pair_probe.hpp).
#include <span>

#include "geometry/polygon.hpp"

namespace erythro::geometry {

// Smallest marker-to-marker distance between two polygons.
double min_marker_gap(const Polygon& a, const Polygon& b);

// Equivalent ellipse of the union of the cells (second area moments about the joint
// centroid, shoelace formulas): axis ratio sqrt(μ_max/μ_min), which is a/b for an
// ellipse (∫x²dA = πa³b/4, ∫y²dA = πab³/4), and the major-axis angle (deg, (−90, 90]).
struct EquivalentEllipse {
  double axis_ratio = 1.0, angle_deg = 0.0, cx = 0.0, cy = 0.0, area = 0.0;
};
EquivalentEllipse equivalent_ellipse(std::span<const Polygon> cells);

// Contact line of cell `a` (thesis §III.2 contact: markers whose aggregation force
// exceeds 1.2 % of the largest, `in_contact`), in the frame of the line of centres
// e (from a to b) and its normal t: n(s) = (X − C)·e against s = (X − C)·t, fitted by
// least squares with Legendre polynomials P0..P3 on the contact's [s_min, s_max].
// |c3| (the odd cubic: an S, sigmoid contact) and |c2| (the even bow: dimples not
// closed or a cupped contact) are the deviations from a straight line at the
// contact's ends. points < 5 → both 0 (no contact line to fit).
struct ContactShape {
  int points = 0;
  double sigmoid = 0.0, bow = 0.0, length = 0.0;
};
ContactShape contact_shape(const Polygon& a, std::span<const char> in_contact, double cx, double cy,
                           double ex, double ey);

}  // namespace erythro::geometry
