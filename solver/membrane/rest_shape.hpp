#pragma once
// The reference (stress-free) configuration of a membrane: what the discrete
// energy (membrane_energy.hpp) measures deformation against.
#include <vector>

#include "common/portable_atan2.hpp"
#include "geometry/polygon.hpp"

namespace erythro::membrane {

struct RestShape {
  std::vector<double> length;  // L_e: rest length of edge e (marker e → e + 1)
  std::vector<double> dual;    // D̄_i = (L_{i−1} + L_i)/2: rest dual length at marker i
  std::vector<double> turning; // θ0_i: rest turning angle at marker i (edge i−1 → edge i)
  double area = 0.0;           // A0: rest enclosed area (counter-clockwise positive)

  std::size_t size() const { return length.size(); }

  // Rest lengths, turning angles and area of a polygon. Its rest curvature is
  // κ0_i = θ0_i / D̄_i; call flatten_curvature() for a zero spontaneous curvature.
  static RestShape from_polygon(const geometry::Polygon& p);
  void flatten_curvature();
};

// Signed turning angle at the vertex between edges a and b (radians, in (−π, π];
// positive for a left, counter-clockwise turn): atan2(a × b, a · b) (docs/model.md eq 3.6a),
// inline so that the bending loop does not call the C library.
inline double turning_angle(double ax, double ay, double bx, double by) {
  return numeric::atan2_portable(ax * by - ay * bx, ax * bx + ay * by);
}

}  // namespace erythro::membrane
