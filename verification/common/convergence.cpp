#include "common/convergence.hpp"

#include <Eigen/Dense>
#include <cmath>
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

}  // namespace erythro::vv
