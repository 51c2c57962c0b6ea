#include "geometry/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace erythro::geometry {

double signed_area(const Polygon& p) { return signed_area(p.x, p.y); }

double signed_area(std::span<const double> x, std::span<const double> y) {
  const std::size_t n = x.size();
  double a = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    a += x[i] * y[j] - x[j] * y[i];
  }
  return 0.5 * a;
}

double perimeter(const Polygon& p) {
  const std::size_t n = p.size();
  double s = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    s += std::hypot(p.x[j] - p.x[i], p.y[j] - p.y[i]);
  }
  return s;
}

void centroid(const Polygon& p, double& cx, double& cy) {
  const std::size_t n = p.size();
  // Relative to marker 0 to avoid cancellation far from the origin.
  const double ox = p.x[0], oy = p.y[0];
  double a = 0.0, sx = 0.0, sy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const double xi = p.x[i] - ox, yi = p.y[i] - oy, xj = p.x[j] - ox, yj = p.y[j] - oy;
    const double c = xi * yj - xj * yi;
    a += c;
    sx += (xi + xj) * c;
    sy += (yi + yj) * c;
  }
  cx = ox + sx / (3.0 * a);
  cy = oy + sy / (3.0 * a);
}

AreaMoments area_moments(const Polygon& p, double ox, double oy) {
  AreaMoments m;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const double xi = p.x[i] - ox, yi = p.y[i] - oy, xj = p.x[j] - ox, yj = p.y[j] - oy;
    const double c = xi * yj - xj * yi;
    m.A += 0.5 * c;
    m.Sx += (xi + xj) * c / 6.0;
    m.Sy += (yi + yj) * c / 6.0;
    m.Sxx += (xi * xi + xi * xj + xj * xj) * c / 12.0;
    m.Syy += (yi * yi + yi * yj + yj * yj) * c / 12.0;
    m.Sxy += (xi * yj + 2.0 * xi * yi + 2.0 * xj * yj + xj * yi) * c / 24.0;
  }
  return m;
}

void taylor_deformation(const Polygon& p, double& D, double& theta_deg) {
  const std::vector<double>& x = p.x;
  const std::vector<double>& y = p.y;
  const std::size_t n = x.size();
  // Work relative to the marker mean to avoid cancellation, then shift to the centroid.
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) { mx += x[i]; my += y[i]; }
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  const auto [A, Sx, Sy, Sxx, Syy, Sxy] = area_moments(p, mx, my);
  const double cx = Sx / A, cy = Sy / A;
  const double Ixx = Sxx - A * cx * cx, Iyy = Syy - A * cy * cy, Ixy = Sxy - A * cx * cy;
  // Eigenvalues of the moment tensor; an ellipse with semi-axes L, B has I1/I2 = L²/B².
  const double mean = 0.5 * (Ixx + Iyy), dev = std::hypot(0.5 * (Ixx - Iyy), Ixy);
  const double l1 = std::sqrt(mean + dev), l2 = std::sqrt(std::max(mean - dev, 0.0));
  D = (l1 - l2) / (l1 + l2);
  theta_deg = 0.5 * std::atan2(2.0 * Ixy, Ixx - Iyy) * 180.0 / std::numbers::pi;
}

void make_counter_clockwise(Polygon& p) {
  if (signed_area(p) >= 0.0) return;
  std::reverse(p.x.begin() + 1, p.x.end());
  std::reverse(p.y.begin() + 1, p.y.end());
}

Polygon transformed(const Polygon& p, double scale, double angle, double cx, double cy) {
  const double c = std::cos(angle) * scale, s = std::sin(angle) * scale;
  Polygon q;
  q.x.resize(p.size());
  q.y.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    q.x[i] = c * p.x[i] - s * p.y[i] + cx;
    q.y[i] = s * p.x[i] + c * p.y[i] + cy;
  }
  return q;
}

}  // namespace erythro::geometry
