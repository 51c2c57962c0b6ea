#pragma once
// Cell shapes as closed polygons, centred at the origin, counter-clockwise, with
// markers EQUALLY SPACED IN ARC LENGTH of the smooth curve (not in its parameter).
// Place, rotate and scale them with geometry::transformed (polygon.hpp).
#include <array>

#include "geometry/polygon.hpp"

namespace erythro::geometry {

// Circle of radius r; marker 0 at (r, 0).
Polygon circle(int markers, double r);

// Ellipse with semi-axes a (along x) and b (along y); marker 0 at (a, 0).
Polygon ellipse(int markers, double a, double b);

// Evans–Fung biconcave section (docs/model.md eq 3.9, thesis eq 29):
//   x = a sin χ, y = (a/2) cos χ (c0 + c1 sin²χ + c2 sin⁴χ), χ ∈ [−π/2, 3π/2].
// a = equivalent radius (3.91 µm for a human RBC, docs/parameters.md); the long axis
// lies along x, marker 0 at (−a, 0).
struct EvansFung {
  double c0 = 0.207161, c1 = 2.002558, c2 = -1.122762;  // full precision (docs/parameters.md)
};
Polygon biconcave(int markers, double a, EvansFung coefficients = {});

}  // namespace erythro::geometry
