#pragma once
// A closed polygon of membrane markers, structure of arrays; edge e joins marker
// e to marker e + 1 (mod n). Counter-clockwise order gives a positive area.
#include <cstddef>
#include <span>
#include <vector>

namespace erythro::geometry {

struct Polygon {
  std::vector<double> x, y;
  std::size_t size() const { return x.size(); }
};

// Shoelace area ½ Σ (x_i y_{i+1} − x_{i+1} y_i), positive when counter-clockwise.
double signed_area(const Polygon& p);
double signed_area(std::span<const double> x, std::span<const double> y);  // the same on coordinate spans
double perimeter(const Polygon& p);
// Area centroid (exact for the polygon).
void centroid(const Polygon& p, double& cx, double& cy);
// Area moments of the closed polygon with coordinates taken relative to (ox, oy), by
// Green's theorem with c_i = x_i y_{i+1} − x_{i+1} y_i: A = ½Σc, ∫x dA = Σ(x_i + x_{i+1})c/6,
// ∫x² dA = Σ(x_i² + x_i x_{i+1} + x_{i+1}²)c/12,
// ∫xy dA = Σ(x_i y_{i+1} + 2x_i y_i + 2x_{i+1} y_{i+1} + x_{i+1} y_i)c/24 (same for y).
struct AreaMoments {
  double A = 0, Sx = 0, Sy = 0, Sxx = 0, Syy = 0, Sxy = 0;
};
AreaMoments area_moments(const Polygon& p, double ox = 0.0, double oy = 0.0);
// Taylor deformation D = (l1 − l2)/(l1 + l2) and orientation θ (degrees, of the major
// axis from +x) from the eigenvalues l1² ≥ l2² of the polygon's second area-moment
// tensor about its centroid (an ellipse with semi-axes L ≥ B gives l1/l2 = L/B).
void taylor_deformation(const Polygon& p, double& D, double& theta_deg);

// Reverses the marker order (keeping marker 0 first) if the polygon is clockwise.
void make_counter_clockwise(Polygon& p);

// Scales by s about the origin, rotates by angle (radians, counter-clockwise)
// about the origin, then translates by (cx, cy): X ← R(angle)·s·X + c.
Polygon transformed(const Polygon& p, double scale, double angle, double cx, double cy);

}  // namespace erythro::geometry
