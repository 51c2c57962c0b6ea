#include "transport/transport_units.hpp"

#include <cmath>
#include <sstream>

#include "transport/stencils.hpp"

namespace erythro::transport {

double TransportUnits::tau(double D_um2_s) const { return tau_for_diffusivity(diffusivity(D_um2_s)); }

double dt_for_tau(double h_um, double D_um2_s, double tau) { return (tau - 0.5) * kCs2 * h_um * h_um / D_um2_s; }

std::vector<std::string> check_transport_units(const TransportUnits& units, double D_um2_s, double k_max_per_s,
                                               double u_max_um_s, const TransportLimits& limits) {
  std::vector<std::string> problems;
  auto say = [&](auto&&... parts) {
    std::ostringstream s;
    (s << ... << parts);
    problems.push_back(s.str());
  };
  if (!(units.h_um > 0.0) || !(units.dt_s > 0.0)) {
    say("lattice spacing and time step must be positive (h = ", units.h_um, " um, dt = ", units.dt_s, " s)");
    return problems;
  }
  const double tau = units.tau(D_um2_s);
  if (!(tau - 0.5 >= limits.min_tau_margin)) {
    say("tau = ", tau, " for D = ", D_um2_s, " um^2/s: tau - 1/2 must be at least ", limits.min_tau_margin,
        " (increase dt or refine less)");
  }
  if (tau > limits.max_tau) say("tau = ", tau, " for D = ", D_um2_s, " um^2/s exceeds ", limits.max_tau, " (reduce dt)");
  const double k = units.rate(k_max_per_s);
  if (k > limits.max_rate_per_step) {
    say("reaction rate ", k_max_per_s, " 1/s gives k dt = ", k, " > ", limits.max_rate_per_step, " per step");
  }
  const double u = units.velocity(u_max_um_s);
  if (std::fabs(u) > limits.max_velocity) {
    say("speed ", u_max_um_s, " um/s is ", u, " in lattice units, above ", limits.max_velocity);
  }
  return problems;
}

}  // namespace erythro::transport
