#pragma once
// Physical ↔ lattice units for transport (docs/transport.md §5). Physical: µm, s, µM,
// µm²/s. Lattice: h = Δt = 1; concentrations keep their unit (µM), since eq T1 is
// linear in C. Conversions:
//   D_lat = D dt/h²,  k_lat = k dt,  q_lat = q dt,  J_lat = J dt/h,  u_lat = u dt/h.
#include <string>
#include <vector>

namespace erythro::transport {

struct TransportUnits {
  double h_um = 0.2;    // lattice spacing, µm
  double dt_s = 1e-5;   // time step, s

  double diffusivity(double D_um2_s) const { return D_um2_s * dt_s / (h_um * h_um); }
  double rate(double k_per_s) const { return k_per_s * dt_s; }
  double source(double q_uM_s) const { return q_uM_s * dt_s; }
  double flux(double J_uM_um_s) const { return J_uM_um_s * dt_s / h_um; }
  double velocity(double u_um_s) const { return u_um_s * dt_s / h_um; }
  double tau(double D_um2_s) const;  // ½ + 3 D_lat
};

struct TransportLimits {
  double min_tau_margin = 0.02;  // τ − ½ ≥ this (BGK ADE stability/accuracy)
  double max_tau = 5.0;          // larger τ: the O(τ²) error terms dominate
  double max_rate_per_step = 0.1;  // k dt: explicit reactions resolve the time scale
  double max_velocity = 0.1;     // |u_lat|: positivity of g^eq needs < 1/3
};

// Sentences naming each violated limit (empty: all fine) for a species of
// diffusivity D, largest first-order rate k_max (1/s) and largest speed u_max (µm/s).
std::vector<std::string> check_transport_units(const TransportUnits& units, double D_um2_s, double k_max_per_s,
                                               double u_max_um_s, const TransportLimits& limits = {});

// Time step giving relaxation time τ for diffusivity D at spacing h (diffusive scaling).
double dt_for_tau(double h_um, double D_um2_s, double tau);

}  // namespace erythro::transport
