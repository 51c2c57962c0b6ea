#include "aggregation/repulsion.hpp"

#include <limits>
#include <stdexcept>
#include <string>

namespace erythro::aggregation {

void check(const RepulsionParameters& p) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("repulsion parameters: " + what); };
  if (!std::isfinite(p.pressure) || !(p.pressure > 0.0))
    fail("the pressure P must be finite and > 0, got " + std::to_string(p.pressure));
  if (!std::isfinite(p.range) || !(p.range > 0.0)) fail("the range d must be finite and > 0, got " + std::to_string(p.range));
}

Repulsion::Repulsion(const RepulsionParameters& p) : p_(p) { check(p); }

// eq 4.13
double wall_energy(const RepulsionParameters& p, double s) {
  const double d = p.range;
  if (!(s < d)) return 0.0;
  if (!(s > 0.0)) return std::numeric_limits<double>::infinity();
  const double a = std::sqrt((d - s) * (d + s));
  return p.pressure * (2.0 * d * d * std::atan(a / s) / s - 4.0 * d * std::asinh(a / s) + 2.0 * a);
}

double wall_energy_derivative(const RepulsionParameters& p, double s) {
  const double d = p.range;
  if (!(s < d)) return 0.0;
  if (!(s > 0.0)) return -std::numeric_limits<double>::infinity();
  const double a = std::sqrt((d - s) * (d + s));
  return -2.0 * p.pressure * (d * d * std::atan(a / s) / (s * s) - a / s);
}

}  // namespace erythro::aggregation
