#pragma once
// Coupling of the fluid and transport time steps (issue 7 item 2, module side;
// docs/transport.md §9). Both lattices share the grid spacing h; their time steps
// differ because ν ≫ D (plasma ν ≈ 1.2e6 µm²/s against D_NO = 3300 µm²/s): at equal
// Δt the transport τ would sit at ½ + O(1e-3). One transport step therefore spans n
// fluid steps (sub-cycling of the fluid), or, when D ≫ ν, m transport steps run per
// fluid step. The advecting velocity in transport lattice units is u_f × Δt_T/Δt_f.
#include <cstddef>
#include <span>
#include <vector>

#include "transport/transport_lattice.hpp"

namespace erythro::transport {

struct TimeCoupling {
  int fluid_per_transport = 1;  // fluid steps per transport step
  int transport_per_fluid = 1;  // transport steps per fluid step (one of the two is 1)
  double dt_transport_s = 0.0;
  double velocity_scale = 1.0;  // u_T(lattice) = velocity_scale × u_f(lattice) = Δt_T/Δt_f
  double tau_max = 0.0;         // transport τ of the largest diffusivity
};

// Integer ratio of the two time steps that puts the τ of the largest diffusivity at
// or just below tau_target (≥ 0.5 + margin is the caller's check, transport_units.hpp).
TimeCoupling plan_time_coupling(double dt_fluid_s, double h_um, double D_max_um2_s, double tau_target = 1.0);

// Mean of the fluid velocity over the fluid steps of one transport step (the
// advecting field of the transport step: time-centred to second order for smooth
// flows), handed to a TransportLattice in its lattice units.
class VelocityAverager {
 public:
  explicit VelocityAverager(std::size_t nodes) : sum_x_(nodes, 0.0), sum_y_(nodes, 0.0) {}
  void add(std::span<const double> ux, std::span<const double> uy);  // fluid lattice units
  int samples() const { return samples_; }
  // Sets lat's velocity to velocity_scale × mean and starts a new average.
  void apply(TransportLattice& lat, double velocity_scale);

 private:
  std::vector<double> sum_x_, sum_y_, mean_x_, mean_y_;
  int samples_ = 0;
};

}  // namespace erythro::transport
