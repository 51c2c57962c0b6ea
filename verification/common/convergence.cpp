#include "common/convergence.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace erythro::vv {

double least_squares_slope(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  if (n < 2 || y.size() != n) throw std::invalid_argument("least_squares_slope: need two or more points");
  // y ≈ c0 + c1 x in the least-squares sense (Householder QR of the design matrix [1 x]).
  Eigen::MatrixX2d A(static_cast<Eigen::Index>(n), 2);
  A.col(0).setOnes();
  A.col(1) = Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(n));
  const Eigen::Map<const Eigen::VectorXd> b(y.data(), static_cast<Eigen::Index>(n));
  return A.colPivHouseholderQr().solve(b)(1);
}

void fit_order(io::ConvergenceSeries& s) {
  if (s.h.size() < 3) throw std::invalid_argument("fit_order: a convergence study needs at least three resolutions");
  std::vector<double> lh, le;
  for (std::size_t k = 0; k < s.h.size(); ++k) {
    lh.push_back(std::log(s.h[k]));
    le.push_back(std::log(s.error[k]));
  }
  s.observed_order = least_squares_slope(lh, le);
  s.local_orders.clear();
  bool monotone = true;
  for (std::size_t k = 0; k + 1 < s.h.size(); ++k) {
    const double p = std::log(s.error[k] / s.error[k + 1]) / std::log(s.h[k] / s.h[k + 1]);
    s.local_orders.push_back(p);
    if (!(p > 0.0)) monotone = false;
  }
  const double finest = s.local_orders.back();
  s.asymptotic = monotone && std::abs(finest - s.formal_order) <= s.order_tolerance;
  std::ostringstream rule;
  rule << "finest local order within +-" << s.order_tolerance << " of the formal order " << s.formal_order
       << " and error decreasing at every refinement";
  s.asymptotic_rule = rule.str();
}

LimitFit fit_limit_and_order(const std::vector<double>& h, const std::vector<double>& q, double p_min, double p_max) {
  const std::size_t n = h.size();
  if (n < 3 || q.size() != n) throw std::invalid_argument("fit_limit_and_order: need three or more levels");
  if (!(p_min > 0.0 && p_max > p_min)) throw std::invalid_argument("fit_limit_and_order: need 0 < p_min < p_max");
  LimitFit best;
  double best_ss = std::numeric_limits<double>::infinity();
  const long steps = std::lround((p_max - p_min) / 1e-3);
  for (long k = 0; k <= steps; ++k) {
    const double p = p_min + (p_max - p_min) * static_cast<double>(k) / static_cast<double>(steps);
    // q ≈ q0 + C x with x = h^p: the closed-form straight-line least squares.
    double sx = 0.0, sy = 0.0;
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i) {
      x[i] = std::pow(h[i], p);
      sx += x[i];
      sy += q[i];
    }
    const double mx = sx / static_cast<double>(n), my = sy / static_cast<double>(n);
    double sxx = 0.0, sxy = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      sxx += (x[i] - mx) * (x[i] - mx);
      sxy += (x[i] - mx) * (q[i] - my);
    }
    if (!(sxx > 0.0)) continue;
    const double c = sxy / sxx, q0 = my - c * mx;
    double ss = 0.0;
    for (std::size_t i = 0; i < n; ++i) ss += (q[i] - q0 - c * x[i]) * (q[i] - q0 - c * x[i]);
    if (ss < best_ss) {
      best_ss = ss;
      best = {q0, c, p, std::sqrt(ss / static_cast<double>(n))};
    }
  }
  if (!std::isfinite(best_ss)) throw std::invalid_argument("fit_limit_and_order: the levels' h are all equal");
  return best;
}

}  // namespace erythro::vv
