#include "richardson.hpp"

#include <cmath>
#include <stdexcept>

namespace erythro::vv {

Extrapolation richardson(const std::vector<double>& h, const std::vector<double>& q, double fallback_order) {
  const std::size_t n = h.size();
  if (n < 3 || q.size() != n) throw std::invalid_argument("richardson: need >= 3 levels");
  const double h1 = h[n - 3], h2 = h[n - 2], h3 = h[n - 1];
  const double q1 = q[n - 3], q2 = q[n - 2], q3 = q[n - 1];
  Extrapolation e;
  e.order = fallback_order;
  const double d12 = q1 - q2, d23 = q2 - q3;
  if (d23 != 0.0 && d12 / d23 > 0.0) {
    const double target = d12 / d23;
    auto ratio = [&](double p) { return (std::pow(h1, p) - std::pow(h2, p)) / (std::pow(h2, p) - std::pow(h3, p)); };
    double lo = 0.25, hi = 8.0;  // ratio(p) increases with p
    if (ratio(lo) <= target && target <= ratio(hi)) {
      for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (ratio(mid) < target ? lo : hi) = mid;
      }
      e.order = 0.5 * (lo + hi);
      e.observed = true;
    }
  }
  e.value = q3 + (q3 - q2) / (std::pow(h2 / h3, e.order) - 1.0);
  return e;
}

}  // namespace erythro::vv
