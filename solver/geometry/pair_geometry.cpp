#include "geometry/pair_geometry.hpp"

#include <Eigen/Dense>
#include <algorithm>
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
  // Least squares n(u) ≈ Σ c_i P_i(u) on u ∈ [−1, 1] (Householder QR of the design matrix).
  Eigen::MatrixX4d P(static_cast<Eigen::Index>(s.size()), 4);
  Eigen::VectorXd normal(static_cast<Eigen::Index>(s.size()));
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double u = (s[k] - s0) / half;
    const auto row = static_cast<Eigen::Index>(k);
    P.row(row) << 1.0, u, 0.5 * (3 * u * u - 1), 0.5 * (5 * u * u * u - 3 * u);
    normal(row) = n[k];
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixX4d> qr(P);
  if (qr.rank() < 4) return r;
  const Eigen::Vector4d c = qr.solve(normal);
  r.bow = std::abs(c(2));
  r.sigmoid = std::abs(c(3));
  return r;
}
}  // namespace erythro::geometry
