#include "common/convergence.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace erythro::vv {

double least_squares_slope(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  if (n < 2 || y.size() != n) throw std::invalid_argument("least_squares_slope: need two or more points");
  double mx = 0, my = 0;
  for (std::size_t k = 0; k < n; ++k) {
    mx += x[k];
    my += y[k];
  }
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxy = 0, sxx = 0;
  for (std::size_t k = 0; k < n; ++k) {
    sxy += (x[k] - mx) * (y[k] - my);
    sxx += (x[k] - mx) * (x[k] - mx);
  }
  return sxy / sxx;
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
