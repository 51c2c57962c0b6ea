#include "membrane/rest_shape.hpp"

#include <cmath>
#include <stdexcept>

namespace erythro::membrane {

RestShape RestShape::from_polygon(const geometry::Polygon& p) {
  const std::size_t n = p.size();
  if (n < 3) throw std::invalid_argument("RestShape: a closed membrane needs at least 3 markers");
  RestShape r;
  r.length.resize(n);
  r.dual.resize(n);
  r.turning.resize(n);
  for (std::size_t e = 0; e < n; ++e) {
    const std::size_t f = (e + 1) % n;
    r.length[e] = std::hypot(p.x[f] - p.x[e], p.y[f] - p.y[e]);
    if (!(r.length[e] > 0.0)) throw std::invalid_argument("RestShape: two consecutive markers coincide");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t im = (i + n - 1) % n, ip = (i + 1) % n;
    r.dual[i] = 0.5 * (r.length[im] + r.length[i]);
    r.turning[i] = turning_angle(p.x[i] - p.x[im], p.y[i] - p.y[im], p.x[ip] - p.x[i], p.y[ip] - p.y[i]);
  }
  r.area = geometry::signed_area(p);
  if (!(r.area > 0.0)) throw std::invalid_argument("RestShape: the polygon must be counter-clockwise with positive area");
  return r;
}

void RestShape::flatten_curvature() {
  for (double& t : turning) t = 0.0;
}

}  // namespace erythro::membrane
