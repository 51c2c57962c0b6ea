#include "membrane/polygon.hpp"

#include <algorithm>
#include <cmath>

namespace erythro::membrane {

double signed_area(const Polygon& p) {
  const std::size_t n = p.size();
  double a = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    a += p.x[i] * p.y[j] - p.x[j] * p.y[i];
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

}  // namespace erythro::membrane
