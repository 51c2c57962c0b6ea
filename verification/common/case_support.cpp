#include "common/case_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace erythro::vv {

std::string fmt(const char* format, double value) {
  char b[128];
  std::snprintf(b, sizeof b, format, value);
  return b;
}

double relative_l2(const std::vector<double>& a, const std::vector<double>& b) {
  double num = 0, den = 0;
  for (std::size_t k = 0; k < b.size(); ++k) {
    num += (a[k] - b[k]) * (a[k] - b[k]);
    den += b[k] * b[k];
  }
  return std::sqrt(num / den);
}

double relative_linf(const std::vector<double>& a, const std::vector<double>& b) {
  double num = 0, den = 0;
  for (std::size_t k = 0; k < b.size(); ++k) {
    num = std::max(num, std::abs(a[k] - b[k]));
    den = std::max(den, std::abs(b[k]));
  }
  return num / den;
}

io::Metric order_metric(const io::ConvergenceSeries& s, const std::string& reason) {
  return {"order " + s.name, "observed order (least squares), " + s.norm, "", s.observed_order, s.formal_order,
          s.order_tolerance, io::Comparison::absolute, reason};
}

io::Metric asymptotic_metric(const io::ConvergenceSeries& s) {
  return {"asymptotic " + s.name, "asymptotic-range check: " + s.asymptotic_rule, "", s.asymptotic ? 1.0 : 0.0, 1.0,
          0.0, io::Comparison::absolute,
          "the fitted order means something only when the finest levels are in the asymptotic range"};
}

void add_convergence_point(io::ConvergenceSeries& series, io::SpeedErrorSeries& speed, double h, double error,
                           double wall_time_s, const std::string& label) {
  series.h.push_back(h);
  series.error.push_back(error);
  speed.wall_time_s.push_back(wall_time_s);
  speed.error.push_back(error);
  speed.label.push_back(label);
}

}  // namespace erythro::vv
