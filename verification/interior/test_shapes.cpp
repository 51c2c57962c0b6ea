#include "test_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/shapes.hpp"

namespace erythro::vv {

namespace {
constexpr double kPi = std::numbers::pi;
using geometry::Polygon;
using geometry::transformed;
}  // namespace

Polygon random_star(Uniform& u, int markers, double R, double amplitude, int modes, double cx, double cy) {
  std::vector<double> a(static_cast<std::size_t>(modes)), phi(a.size());
  double sum = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    a[k] = u();
    phi[k] = 2 * kPi * u();
    sum += a[k];
  }
  Polygon p;
  for (int m = 0; m < markers; ++m) {
    const double th = 2 * kPi * m / markers;
    double r = 1.0;
    for (std::size_t k = 0; k < a.size(); ++k) r += amplitude * a[k] / sum * std::cos((static_cast<double>(k) + 2.0) * th + phi[k]);
    p.x.push_back(cx + R * r * std::cos(th));
    p.y.push_back(cy + R * r * std::sin(th));
  }
  return p;
}

Polygon horseshoe(int markers, double R, double t, double gap, double angle, double cx, double cy) {
  // Outer arc (counter-clockwise), end cap, inner arc back (clockwise), end cap.
  const double span = 2 * kPi - gap, ro = R + 0.5 * t, ri = R - 0.5 * t;
  const int arc = std::max(4, markers * 2 / 5), cap = std::max(2, markers / 10);
  Polygon p;
  auto put = [&](double r, double th) {
    p.x.push_back(cx + r * std::cos(th + angle));
    p.y.push_back(cy + r * std::sin(th + angle));
  };
  const double th0 = 0.5 * gap;
  for (int k = 0; k < arc; ++k) put(ro, th0 + span * k / arc);
  for (int k = 0; k < cap; ++k) put(ro - t * k / cap, th0 + span);  // the end at th0 + span, outer → inner
  for (int k = 0; k < arc; ++k) put(ri, th0 + span * (arc - k) / arc);
  for (int k = 0; k < cap; ++k) put(ri + t * k / cap, th0);
  return p;
}

std::vector<CellScene> agreement_suite() {
  std::vector<CellScene> s;
  const geometry::Domain torus{Grid{96, 96}, true, true};
  const geometry::Domain channel{Grid{96, 64}, true, false};  // walls at y = 0 and y = 64
  // Smooth shapes at several sizes, orientations and sub-node offsets.
  {
    CellScene c{"smooth shapes", torus, {}};
    c.cells.push_back(transformed(geometry::circle(100, 11.3), 1, 0, 20.21, 22.77));
    c.cells.push_back(transformed(geometry::ellipse(120, 16.0, 7.5), 1, 0.7, 70.4, 24.1));
    c.cells.push_back(transformed(geometry::biconcave(100, 26.0), 1, 0.0, 48.3, 70.6));  // thesis size
    c.cells.push_back(transformed(geometry::biconcave(100, 13.0), 1, 1.9, 16.6, 70.2));
    c.cells.push_back(transformed(geometry::biconcave(60, 9.0), 1, -0.4, 84.9, 66.3));
    s.push_back(c);
  }
  // Randomly deformed star shapes (several Fourier modes), fixed seeds.
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    Uniform u(seed);
    CellScene c{"random stars seed " + std::to_string(seed), torus, {}};
    for (int k = 0; k < 4; ++k) {
      const double cx = 24.0 + 48.0 * (k % 2) + 4 * (u() - 0.5), cy = 24.0 + 48.0 * (k / 2) + 4 * (u() - 0.5);
      c.cells.push_back(random_star(u, 160, 10.0 + 6.0 * u(), 0.25 + 0.35 * u(), 2 + static_cast<int>(5 * u()), cx, cy));
    }
    s.push_back(c);
  }
  // Folded, strongly non-convex horseshoes (thin arms, narrow openings).
  for (std::uint64_t seed = 11; seed <= 14; ++seed) {
    Uniform u(seed);
    CellScene c{"folded horseshoes seed " + std::to_string(seed), torus, {}};
    for (int k = 0; k < 4; ++k)
      c.cells.push_back(horseshoe(240, 12.0 + 5.0 * u(), 5.0 + 5.0 * u(), 0.3 + 0.8 * u(), 2 * kPi * u(),
                                  24.0 + 48.0 * (k % 2) + 2 * u(), 24.0 + 48.0 * (k / 2) + 2 * u()));
    s.push_back(c);
  }
  // Cells across the periodic sides and the corner (coordinates unwrapped past the side).
  {
    CellScene c{"periodic crossings", torus, {}};
    c.cells.push_back(transformed(geometry::biconcave(100, 20.0), 1, 0.3, 1.7, 50.2));    // across x = 0
    c.cells.push_back(transformed(geometry::biconcave(100, 20.0), 1, 1.2, 50.4, 95.1));   // across y = 96
    c.cells.push_back(transformed(geometry::ellipse(100, 14.0, 9.0), 1, 0.5, 95.3, 0.6)); // across the corner
    Uniform u(21);
    c.cells.push_back(random_star(u, 140, 11.0, 0.45, 4, 140.0, 46.0));                   // unwrapped beyond nx
    s.push_back(c);
  }
  // Small cells (semi-axes 1.3 … 5 h: partly or wholly band; those without a start node fall
  // back to ray casting).
  {
    CellScene c{"small cells", torus, {}};
    Uniform u(31);
    for (int k = 0; k < 24; ++k)
      c.cells.push_back(transformed(geometry::ellipse(24, 1.3 + 3.7 * u(), 1.3 + 2.5 * u()), 1, 3 * u(),
                                    8.0 + 16.0 * (k % 6) + u(), 10.0 + 22.0 * (k / 6) + u()));
    s.push_back(c);
  }
  // Pairs closer than the band width (gaps 0.3 … 3.5 h: bands overlap).
  {
    CellScene c{"close pairs", torus, {}};
    for (int k = 0; k < 4; ++k) {
      const double gap = 0.3 + 1.05 * k, cy = 12.0 + 24.0 * k;
      c.cells.push_back(transformed(geometry::biconcave(100, 18.0), 1, 0.0, 30.0, cy));
      c.cells.push_back(transformed(geometry::biconcave(100, 18.0), 1, 0.0, 66.0 + gap, cy));  // tips 36 + gap apart
    }
    s.push_back(c);
  }
  // Cells close to the walls of a channel (within 0.4 … 1.5 h) and one cut by a wall.
  {
    CellScene c{"near walls", channel, {}};
    c.cells.push_back(transformed(geometry::ellipse(100, 14.0, 7.0), 1, 0.0, 20.0, 7.4));      // 0.4 h off y = 0
    Polygon top = transformed(geometry::biconcave(100, 18.0), 1, 0.0, 60.2, 0.0);
    const double ymax = *std::max_element(top.y.begin(), top.y.end());
    c.cells.push_back(transformed(top, 1, 0.0, 0.0, 64.0 - 1.5 - ymax));                         // 1.5 h off y = 64
    c.cells.push_back(transformed(geometry::circle(80, 9.0), 1, 0.0, 88.0, 4.0));              // cut by y = 0, across x = 96
    s.push_back(c);
  }
  return s;
}

CellScene biconcave_array(int n, int nx, int ny, double a) {
  CellScene s{std::to_string(n) + " biconcave cells on " + std::to_string(nx) + "x" + std::to_string(ny),
              geometry::Domain{Grid{nx, ny}, true, true}, {}};
  int cols = 1, rows = 1;
  while (cols * rows < n) (cols <= rows ? cols : rows) *= 2;
  const double dx = double(nx) / cols, dy = double(ny) / rows;
  for (int k = 0; k < n; ++k)
    s.cells.push_back(geometry::transformed(geometry::biconcave(100, a), 1.0, 0.5 * kPi + 0.05 * k,
                                            (k % cols + 0.5) * dx + 0.13, (k / cols + 0.5) * dy + 0.37));
  return s;
}

}  // namespace erythro::vv
