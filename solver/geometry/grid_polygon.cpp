#include "geometry/grid_polygon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace erythro::geometry {

void row_crossings(const Polygon& p, double py, std::vector<double>& xs) {
  xs.clear();
  const std::size_t n = p.size();
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t b = a + 1 == n ? 0 : a + 1;
    const double ya = p.y[a], yb = p.y[b];
    if ((ya > py) == (yb > py)) continue;
    xs.push_back(p.x[a] + (py - ya) * (p.x[b] - p.x[a]) / (yb - ya));
  }
  std::sort(xs.begin(), xs.end());
}

namespace {
// One Sutherland–Hodgman pass: keeps the part of the polygon with s·(coordinate − c) ≥ 0.
void clip(std::vector<double>& x, std::vector<double>& y, bool along_x, double c, double s) {
  std::vector<double> ox, oy;
  const std::size_t n = x.size();
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t b = a + 1 == n ? 0 : a + 1;
    const double fa = s * ((along_x ? x[a] : y[a]) - c), fb = s * ((along_x ? x[b] : y[b]) - c);
    if (fa >= 0) {
      ox.push_back(x[a]);
      oy.push_back(y[a]);
    }
    if ((fa >= 0) != (fb >= 0)) {
      const double t = fa / (fa - fb);
      ox.push_back(x[a] + t * (x[b] - x[a]));
      oy.push_back(y[a] + t * (y[b] - y[a]));
    }
  }
  x.swap(ox);
  y.swap(oy);
}
}  // namespace

bool within_walls(const Domain& d, double x0, double x1, double y0, double y1) {
  return (d.periodic_x || (x0 >= 0.0 && x1 <= d.grid.nx)) && (d.periodic_y || (y0 >= 0.0 && y1 <= d.grid.ny));
}

double clipped_area(const Polygon& p, const Domain& d) {
  // Nothing to clip (the usual case): no copy.
  const auto [x0, x1] = std::minmax_element(p.x.begin(), p.x.end());
  const auto [y0, y1] = std::minmax_element(p.y.begin(), p.y.end());
  if (within_walls(d, *x0, *x1, *y0, *y1)) return signed_area(p);
  Polygon q = p;
  if (!d.periodic_x) {
    clip(q.x, q.y, true, 0.0, 1.0);
    clip(q.x, q.y, true, d.grid.nx, -1.0);
  }
  if (!d.periodic_y) {
    clip(q.x, q.y, false, 0.0, 1.0);
    clip(q.x, q.y, false, d.grid.ny, -1.0);
  }
  return q.size() < 3 ? 0.0 : signed_area(q);
}

double area_in_box(const Polygon& p, double x0, double x1, double y0, double y1) {
  Polygon q = p;
  clip(q.x, q.y, true, x0, 1.0);
  if (q.size() >= 3) clip(q.x, q.y, true, x1, -1.0);
  if (q.size() >= 3) clip(q.x, q.y, false, y0, 1.0);
  if (q.size() >= 3) clip(q.x, q.y, false, y1, -1.0);
  return q.size() < 3 ? 0.0 : signed_area(q);
}

double signed_distance(const Polygon& p, double px, double py) {
  const std::size_t n = p.size();
  if (n < 2) throw std::invalid_argument("signed_distance: polygon needs at least 2 markers");
  double best = std::numeric_limits<double>::infinity();
  int crossings = 0;
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t b = a + 1 == n ? 0 : a + 1;
    const double ex = p.x[b] - p.x[a], ey = p.y[b] - p.y[a];
    const double qx = px - p.x[a], qy = py - p.y[a];
    const double len2 = ex * ex + ey * ey;
    const double t = len2 > 0 ? std::clamp((qx * ex + qy * ey) / len2, 0.0, 1.0) : 0.0;
    const double dx = qx - t * ex, dy = qy - t * ey;
    best = std::min(best, dx * dx + dy * dy);
    // Even–odd: count edges crossing the horizontal ray from (px, py) towards +x.
    if ((p.y[a] > py) != (p.y[b] > py) && p.x[a] + (py - p.y[a]) * ex / ey > px) ++crossings;
  }
  const double d = std::sqrt(best);
  return crossings % 2 ? -d : d;
}

std::vector<std::uint8_t> ray_cast_inside(const Polygon& p, const Domain& d) {
  std::vector<std::uint8_t> mask(d.grid.size(), 0);
  std::vector<std::size_t> nodes;
  ray_cast_inside_nodes(p, d, nodes);
  for (std::size_t k : nodes) mask[k] = 1;
  return mask;
}

void ray_cast_inside_nodes(const Polygon& p, const Domain& d, std::vector<std::size_t>& nodes) {
  const Grid& g = d.grid;
  nodes.clear();
  if (p.size() < 3) return;
  const auto [ymin, ymax] = std::minmax_element(p.y.begin(), p.y.end());
  int j0 = 0, j1 = 0;
  node_range(*ymin, *ymax, j0, j1);
  std::vector<double> xs;
  for (int j = j0; j <= j1; ++j) {
    const int jj = wrap_node(j, g.ny, d.periodic_y);
    if (jj < 0) continue;
    row_crossings(p, j + 0.5, xs);
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
      // Inside ⇔ x_c[2k] ≤ i + ½ < x_c[2k+1].
      const int i0 = static_cast<int>(std::ceil(xs[k] - 0.5));
      const int i1 = static_cast<int>(std::ceil(xs[k + 1] - 0.5)) - 1;
      for (int i = i0; i <= i1; ++i) {
        const int ii = wrap_node(i, g.nx, d.periodic_x);
        if (ii >= 0) nodes.push_back(g.index(ii, jj));
      }
    }
  }
  // Rows in order give ascending indices; a wrap across a periodic side does not, and
  // a node reached through two images must be listed once.
  if (!std::is_sorted(nodes.begin(), nodes.end())) {
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  }
}

}  // namespace erythro::geometry
