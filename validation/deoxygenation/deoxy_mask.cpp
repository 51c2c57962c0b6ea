#include "deoxy_mask.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "geometry/grid_polygon.hpp"

namespace erythro::deoxy {
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

std::vector<NodeFraction> first_moment_weights(const geometry::Polygon& p, int nx, int ny,
                                               const std::vector<NodeFraction>& fractions) {
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
  std::vector<NodeFraction> out;
  out.reserve(w.size());
  for (const auto& [node, v] : w) out.push_back({node, v});
  return out;
}

}  // namespace erythro::deoxy

namespace erythro::deoxy {

double segment_fraction_inside(const geometry::Polygon& p, double x0, double y0, double x1, double y1) {
  // Parameters t ∈ (0, 1) where the segment crosses an edge; inside/outside alternate.
  std::vector<double> t;
  const double dx = x1 - x0, dy = y1 - y0;
  const std::size_t n = p.size();
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t b = a + 1 == n ? 0 : a + 1;
    const double ex = p.x[b] - p.x[a], ey = p.y[b] - p.y[a];
    const double den = dx * ey - dy * ex;
    if (den == 0.0) continue;
    const double qx = p.x[a] - x0, qy = p.y[a] - y0;
    const double s = (qx * ey - qy * ex) / den;  // along the segment
    const double u = (qx * dy - qy * dx) / den;  // along the edge
    if (s > 0.0 && s < 1.0 && u >= 0.0 && u < 1.0) t.push_back(s);
  }
  std::sort(t.begin(), t.end());
  bool inside = geometry::signed_distance(p, x0, y0) < 0.0;
  double last = 0.0, frac = 0.0;
  for (double s : t) {
    if (inside) frac += s - last;
    inside = !inside;
    last = s;
  }
  if (inside) frac += 1.0 - last;
  return frac;
}

std::vector<double> link_resistivities(const geometry::Polygon& p, int nx, int ny, double D_in, double D_out,
                                       const std::vector<double>& R_phi) {
  const auto idx = [nx](int x, int y) { return static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) + x; };
  std::vector<double> R = R_phi;
  // Target resistances of the +x and +y links of every node (NaN: not cut, off the grid).
  std::vector<double> Rx(R.size(), -1.0), Ry(R.size(), -1.0);
  std::vector<char> free_node(R.size(), 0);
  const auto [xmin, xmax] = std::minmax_element(p.x.begin(), p.x.end());
  const auto [ymin, ymax] = std::minmax_element(p.y.begin(), p.y.end());
  const int i0 = std::max(0, static_cast<int>(*xmin) - 2), i1 = std::min(nx - 1, static_cast<int>(*xmax) + 2);
  const int j0 = std::max(0, static_cast<int>(*ymin) - 2), j1 = std::min(ny - 1, static_cast<int>(*ymax) + 2);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const double cx = i + 0.5, cy = j + 0.5;
      if (i + 1 <= i1) {
        const double th = segment_fraction_inside(p, cx, cy, cx + 1.0, cy);
        Rx[idx(i, j)] = th / D_in + (1.0 - th) / D_out;
        if (th > 0.0 && th < 1.0) free_node[idx(i, j)] = free_node[idx(i + 1, j)] = 1;
      }
      if (j + 1 <= j1) {
        const double th = segment_fraction_inside(p, cx, cy, cx, cy + 1.0);
        Ry[idx(i, j)] = th / D_in + (1.0 - th) / D_out;
        if (th > 0.0 && th < 1.0) free_node[idx(i, j)] = free_node[idx(i, j + 1)] = 1;
      }
    }
  constexpr double mu = 0.1;
  for (int sweep = 0; sweep < 400; ++sweep)
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const std::size_t n = idx(i, j);
        if (!free_node[n]) continue;
        // ∂/∂R_n: Σ_links ((R_n + R_m)/2 − R*)·½ + μ (R_n − R^φ_n) = 0
        double num = mu * R_phi[n], den = mu;
        const auto link = [&](std::size_t m, double target) {
          if (target < 0.0) return;
          num += 0.5 * (target - 0.5 * R[m]);
          den += 0.25;
        };
        if (i + 1 <= i1) link(idx(i + 1, j), Rx[n]);
        if (i - 1 >= i0) link(idx(i - 1, j), Rx[idx(i - 1, j)]);
        if (j + 1 <= j1) link(idx(i, j + 1), Ry[n]);
        if (j - 1 >= j0) link(idx(i, j - 1), Ry[idx(i, j - 1)]);
        R[n] = std::clamp(num / den, 1.0 / D_out, 1.0 / D_in);
      }
  return R;
}

}  // namespace erythro::deoxy
