#include "transport/time_coupling.hpp"

#include <cmath>
#include <stdexcept>

#include "transport/stencils.hpp"
#include "transport/transport_units.hpp"

namespace erythro::transport {

TimeCoupling plan_time_coupling(double dt_fluid_s, double h_um, double D_max_um2_s, double tau_target) {
  if (!(dt_fluid_s > 0.0) || !(h_um > 0.0) || !(D_max_um2_s > 0.0) || !(tau_target > 0.5)) {
    throw std::invalid_argument("plan_time_coupling: need dt > 0, h > 0, D > 0 and tau_target > 1/2");
  }
  const double ideal = dt_for_tau(h_um, D_max_um2_s, tau_target);
  TimeCoupling c;
  if (ideal >= dt_fluid_s) {
    c.fluid_per_transport = static_cast<int>(std::floor(ideal / dt_fluid_s));
    c.dt_transport_s = c.fluid_per_transport * dt_fluid_s;
  } else {
    c.transport_per_fluid = static_cast<int>(std::ceil(dt_fluid_s / ideal));
    c.dt_transport_s = dt_fluid_s / c.transport_per_fluid;
  }
  c.velocity_scale = c.dt_transport_s / dt_fluid_s;
  c.tau_max = TransportUnits{h_um, c.dt_transport_s}.tau(D_max_um2_s);
  return c;
}

void VelocityAverager::add(std::span<const double> ux, std::span<const double> uy) {
  if (ux.size() != sum_x_.size() || uy.size() != sum_y_.size()) {
    throw std::invalid_argument("VelocityAverager::add: field size does not match");
  }
  for (std::size_t n = 0; n < ux.size(); ++n) {
    sum_x_[n] += ux[n];
    sum_y_[n] += uy[n];
  }
  ++samples_;
}

void VelocityAverager::apply(TransportLattice& lat, double velocity_scale) {
  if (samples_ == 0) throw std::logic_error("VelocityAverager::apply: no velocity sample");
  const double f = velocity_scale / samples_;
  mean_x_.resize(sum_x_.size());
  mean_y_.resize(sum_y_.size());
  for (std::size_t n = 0; n < sum_x_.size(); ++n) {
    mean_x_[n] = f * sum_x_[n];
    mean_y_[n] = f * sum_y_[n];
    sum_x_[n] = sum_y_[n] = 0.0;
  }
  samples_ = 0;
  lat.set_velocity(mean_x_, mean_y_);
}

}  // namespace erythro::transport
