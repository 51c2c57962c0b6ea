#include "transport/heme_weights.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "geometry/grid_polygon.hpp"

namespace erythro::transport {
namespace {

// ∫_0^1 f(s) ds, composite 3-point Gauss–Legendre on 8 equal panels.
template <class F>
double integrate01(const F& f) {
  constexpr int panels = 8;
  const double g = std::sqrt(0.6) / 2.0;  // nodes ½ ± ½√(3/5), weights 5/18, 8/18, 5/18
  double s = 0.0;
  for (int k = 0; k < panels; ++k) {
    const double a = double(k) / panels, w = 1.0 / panels, m = a + 0.5 * w;
    s += w * (5.0 * f(m - g * w) + 8.0 * f(m) + 5.0 * f(m + g * w)) / 18.0;
  }
  return s;
}

}  // namespace

Moment first_moment(const geometry::Polygon& p, int i, int j, double phi) {
  const double sign = geometry::signed_area(p) >= 0.0 ? 1.0 : -1.0;
  const double X = i, Y = j;
  const double Ax = integrate01([&](double s) { return sign * geometry::area_in_box(p, X, X + s, Y, Y + 1.0); });
  const double Ay = integrate01([&](double s) { return sign * geometry::area_in_box(p, X, X + 1.0, Y, Y + s); });
  return {0.5 * phi - Ax, 0.5 * phi - Ay};
}

std::vector<AreaFraction> first_moment_weights(const geometry::Polygon& p, int nx, int ny,
                                               const std::vector<AreaFraction>& fractions) {
  std::map<std::size_t, double> w;
  const auto add = [&](int x, int y, double v) {
    if (v <= 0.0 || x < 0 || y < 0 || x >= nx || y >= ny) return;  // the cell lies well inside the box
    w[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(x)] += v;
  };
  for (const auto& f : fractions) {
    const int i = static_cast<int>(f.node % static_cast<std::size_t>(nx));
    const int j = static_cast<int>(f.node / static_cast<std::size_t>(nx));
    if (f.phi >= 1.0) {
      add(i, j, f.phi);
      continue;
    }
    const Moment m = first_moment(p, i, j, f.phi);
    const double dx = std::clamp(m.mx / f.phi, -0.5, 0.5), dy = std::clamp(m.my / f.phi, -0.5, 0.5);
    const int sx = dx >= 0.0 ? 1 : -1, sy = dy >= 0.0 ? 1 : -1;
    const double ax = std::fabs(dx), ay = std::fabs(dy);
    add(i, j, f.phi * (1.0 - ax) * (1.0 - ay));
    add(i + sx, j, f.phi * ax * (1.0 - ay));
    add(i, j + sy, f.phi * (1.0 - ax) * ay);
    add(i + sx, j + sy, f.phi * ax * ay);
  }
  std::vector<AreaFraction> out;
  out.reserve(w.size());
  for (const auto& [node, v] : w) out.push_back({node, v});
  return out;
}

}  // namespace erythro::transport
