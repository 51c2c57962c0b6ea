#pragma once
// Result of a health scan (finite values, density positive, Mach below limit).
#include <string>

namespace erythro {

struct HealthReport {
  bool healthy = true;
  std::string quantity;  // e.g. "velocity_x", "density", "mach"
  long node_x = -1, node_y = -1;
  double value = 0.0;
  double limit = 0.0;  // the bound that was violated (NaN for non-finite)
  double max_speed = 0.0;  // healthy scan: max |u| over all nodes (lattice units)
  std::string hint;        // optional: which limit and its likely causes, for the message
};

}  // namespace erythro
