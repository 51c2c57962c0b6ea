#pragma once
// Distance of a computed double from an exact value, in units in the last place of the exact
// value (long double, 64-bit mantissa): the accuracy measure of the portable elementary
// functions' unit tests (common/portable_exp.hpp, common/portable_hypot.hpp).
#include <cmath>

namespace erythro::testing {

inline double ulp_error(double got, long double exact) {
  const double nearest = static_cast<double>(exact);
  const double ulp = std::nextafter(nearest, INFINITY) - nearest;
  return static_cast<double>(std::fabs(static_cast<long double>(got) - exact) / ulp);
}

}  // namespace erythro::testing
