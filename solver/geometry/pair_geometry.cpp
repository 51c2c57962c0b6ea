#include "geometry/pair_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace erythro::geometry {

double min_marker_gap(const Polygon& a, const Polygon& b) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) best = std::min(best, std::hypot(a.x[i] - b.x[j], a.y[i] - b.y[j]));
  return best;
}

EquivalentEllipse equivalent_ellipse(std::span<const Polygon> cells) {
  // Area moments of the pair (each polygon counter-clockwise), area_moments.
  double A = 0, Sx = 0, Sy = 0, Sxx = 0, Syy = 0, Sxy = 0;
  for (const Polygon& p : cells) {
    const AreaMoments m = area_moments(p);
    A += m.A, Sx += m.Sx, Sy += m.Sy, Sxx += m.Sxx, Syy += m.Syy, Sxy += m.Sxy;
  }
  EquivalentEllipse e;
  e.area = A;
  e.cx = Sx / A;
  e.cy = Sy / A;
  const double mxx = Sxx - A * e.cx * e.cx, myy = Syy - A * e.cy * e.cy, mxy = Sxy - A * e.cx * e.cy;
  const double mean = 0.5 * (mxx + myy), dev = std::hypot(0.5 * (mxx - myy), mxy);
  const double l1 = mean + dev, l2 = mean - dev;
  e.axis_ratio = l2 > 0 ? std::sqrt(l1 / l2) : std::numeric_limits<double>::infinity();
  e.angle_deg = 0.5 * std::atan2(2.0 * mxy, mxx - myy) * 180.0 / std::numbers::pi;
  return e;
}

ContactShape contact_shape(const Polygon& a, std::span<const char> in_contact, double cx, double cy,
                           double ex, double ey) {
  ContactShape r;
  std::vector<double> s, n;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!in_contact[i]) continue;
    s.push_back((a.x[i] - cx) * -ey + (a.y[i] - cy) * ex);
    n.push_back((a.x[i] - cx) * ex + (a.y[i] - cy) * ey);
  }
  r.points = static_cast<int>(s.size());
  if (r.points < 5) return r;
  const auto [lo, hi] = std::minmax_element(s.begin(), s.end());
  const double s0 = 0.5 * (*lo + *hi), half = 0.5 * (*hi - *lo);
  r.length = 2.0 * half;
  if (!(half > 0)) return r;
  // Normal equations of the Legendre fit (4 × 4, well conditioned on [−1, 1]).
  std::array<std::array<double, 5>, 4> M{};
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double u = (s[k] - s0) / half;
    const std::array<double, 4> P{1.0, u, 0.5 * (3 * u * u - 1), 0.5 * (5 * u * u * u - 3 * u)};
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) M[i][j] += P[i] * P[j];
      M[i][4] += P[i] * n[k];
    }
  }
  for (int col = 0; col < 4; ++col) {  // Gaussian elimination with partial pivoting
    int piv = col;
    for (int i = col + 1; i < 4; ++i)
      if (std::abs(M[i][col]) > std::abs(M[piv][col])) piv = i;
    std::swap(M[col], M[piv]);
    if (std::abs(M[col][col]) < 1e-300) return r;
    for (int i = 0; i < 4; ++i) {
      if (i == col) continue;
      const double f = M[i][col] / M[col][col];
      for (int j = col; j < 5; ++j) M[i][j] -= f * M[col][j];
    }
  }
  r.bow = std::abs(M[2][4] / M[2][2]);
  r.sigmoid = std::abs(M[3][4] / M[3][3]);
  return r;
}

}  // namespace erythro::geometry
