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
bool wall_evaluate(const RepulsionParameters& p, double s, double& W, double& dW) {
  const double d = p.range;
  if (!(s < d)) {
    W = dW = 0.0;
    return false;
  }
  if (!(s > 0.0)) {
    W = std::numeric_limits<double>::infinity();
    dW = -W;
    return true;
  }
  const double a = std::sqrt((d - s) * (d + s)), angle = std::atan(a / s);
  W = p.pressure * (2.0 * d * d * angle / s - 4.0 * d * std::asinh(a / s) + 2.0 * a);
  dW = -2.0 * p.pressure * (d * d * angle / (s * s) - a / s);
  return true;
}

double wall_energy(const RepulsionParameters& p, double s) {
  double W = 0.0, dW = 0.0;
  wall_evaluate(p, s, W, dW);
  return W;
}

double wall_energy_derivative(const RepulsionParameters& p, double s) {
  double W = 0.0, dW = 0.0;
  wall_evaluate(p, s, W, dW);
  return dW;
}

}  // namespace erythro::aggregation
