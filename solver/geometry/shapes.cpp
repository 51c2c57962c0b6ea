#include "geometry/shapes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace erythro::geometry {

namespace {

// 8-point Gauss–Legendre nodes and weights on [−1, 1].
constexpr std::array<double, 8> kGlX = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                        -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                        0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kGlW = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                        0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                        0.2223810344533745, 0.1012285362903763};

struct Point {
  double x, y, dx, dy;  // position and derivative with respect to the parameter
};

// Markers at equal arc length s_k = k L / n of a closed curve t ∈ [t0, t1), t0 ↦ marker 0.
// Arc length s(t) = ∫ |X'(t)| dt by composite 8-point Gauss–Legendre on fine panels,
// inverted by Newton's method (ds/dt = |X'|); the spacing is exact to ~1e−13 L.
template <class Curve>
Polygon equal_arc(int n, double t0, double t1, Curve curve) {
  if (n < 3) throw std::invalid_argument("membrane shape: a closed polygon needs at least 3 markers");
  auto speed = [&](double t) {
    const Point p = curve(t);
    return std::hypot(p.dx, p.dy);
  };
  auto arc = [&](double a, double b) {
    double s = 0.0;
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    for (std::size_t q = 0; q < kGlX.size(); ++q) s += kGlW[q] * speed(mid + half * kGlX[q]);
    return s * half;
  };
  const int panels = std::max(256, 16 * n);
  const double dt = (t1 - t0) / panels;
  std::vector<double> s(static_cast<std::size_t>(panels) + 1, 0.0);
  for (int k = 0; k < panels; ++k) s[k + 1] = s[k] + arc(t0 + k * dt, t0 + (k + 1) * dt);
  const double L = s.back();
  Polygon poly;
  poly.x.resize(static_cast<std::size_t>(n));
  poly.y.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double target = L * k / n;
    const auto it = std::upper_bound(s.begin(), s.end(), target);
    const int p = std::clamp(static_cast<int>(it - s.begin()) - 1, 0, panels - 1);
    const double tp = t0 + p * dt;
    double t = tp + dt * (target - s[p]) / (s[p + 1] - s[p]);
    for (int iter = 0; iter < 30; ++iter) {
      const double step = (s[p] + arc(tp, t) - target) / speed(t);
      t -= step;
      if (std::abs(step) < 1e-15 * (t1 - t0)) break;
    }
    const Point q = curve(t);
    poly.x[k] = q.x;
    poly.y[k] = q.y;
  }
  make_counter_clockwise(poly);
  return poly;
}

}  // namespace

Polygon circle(int markers, double r) {
  if (markers < 3) throw std::invalid_argument("geometry::circle: needs at least 3 markers");
  Polygon p;
  for (int k = 0; k < markers; ++k) {
    const double t = 2.0 * std::numbers::pi * k / markers;
    p.x.push_back(r * std::cos(t));
    p.y.push_back(r * std::sin(t));
  }
  return p;
}

Polygon ellipse(int markers, double a, double b) {
  return equal_arc(markers, 0.0, 2.0 * std::numbers::pi, [a, b](double t) {
    return Point{a * std::cos(t), b * std::sin(t), -a * std::sin(t), b * std::cos(t)};
  });
}

Polygon biconcave(int markers, double a, EvansFung c) {
  // Thesis eq 29; χ runs from −π/2 (marker 0 at (−a, 0)) over the top to 3π/2.
  return equal_arc(markers, -0.5 * std::numbers::pi, 1.5 * std::numbers::pi, [a, c](double chi) {
    const double s = std::sin(chi), co = std::cos(chi), s2 = s * s;
    const double g = c.c0 + c.c1 * s2 + c.c2 * s2 * s2;
    const double dg = (2.0 * c.c1 * s + 4.0 * c.c2 * s2 * s) * co;
    return Point{a * s, 0.5 * a * co * g, a * co, 0.5 * a * (-s * g + co * dg)};
  });
}

}  // namespace erythro::geometry
