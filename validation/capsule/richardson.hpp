#pragma once
// Richardson extrapolation of a quantity q(h) = q∞ + C h^p from the three finest
// levels of a resolution study with arbitrary refinement ratios.
#include <vector>

namespace erythro::vv {

struct Extrapolation {
  double value = 0;     // q∞
  double order = 0;     // observed order p (fallback_order if not determinable)
  bool observed = false;  // p solved from the data (monotone differences, p in [0.25, 8])
};

// h must be decreasing (coarse → fine). The order solves
//   (q1 − q2)/(q2 − q3) = (h1^p − h2^p)/(h2^p − h3^p)
// for the three finest levels (bisection); q∞ = q3 + (q3 − q2)/((h2/h3)^p − 1).
Extrapolation richardson(const std::vector<double>& h, const std::vector<double>& q, double fallback_order);

}  // namespace erythro::vv
