#pragma once
// One run of the capsule-in-shear set-up (validation.capsule_shear): a circular
// neo-Hookean capsule (rest radius a, no bending, no prestress, no area penalty)
// centred between two walls moving at ±U (simple shear γ̇ = 2U/H), periodic in x,
// equal viscosity inside and outside (one fluid), run until the Taylor
// deformation D is steady or a strain cap is reached.
#include <string>
#include <vector>

#include "fluid/fluid_lattice.hpp"

#include "ib/kernel.hpp"

namespace erythro::vv {

struct CapsuleConfig {
  ib::KernelType kernel = ib::KernelType::cosine4;
  double radius = 6.0;         // a/h
  double capillary = 0.05;     // G = μγ̇a/E_s
  double reynolds = 0.1;       // particle Reynolds number γ̇a²/ν
  double height = 16.0;        // H/a (wall to wall)
  double length = 16.0;        // L_x/a (periodic)
  double tau = 1.0;            // BGK relaxation time (ν = (τ − ½)/3)
  double markers_per_radius = 12.0;  // n = round(12 a): spacing ≈ 0.52 h at rest
  double max_strain = 12.0;    // cap on γ̇t
  double min_strain = 4.0;     // never stop before this strain
  double steady_drift = 1e-4;  // stop when |ΔD| over the last strain unit is below this
};

struct CapsuleResult {
  bool diverged = false;
  long steps = 0;
  double strain = 0;       // γ̇t reached
  double shear_rate = 0;   // γ̇ (lattice)
  double modulus = 0;      // E_s (lattice)
  int markers = 0;
  double D = 0;            // Taylor deformation (L − B)/(L + B) from area moments
  double theta_deg = 0;    // inclination of the long axis to the flow (x) direction
  double drift = 0;        // |D(end) − D(end − 1 strain unit)|
  double tt_period = 0;    // tank-treading period × γ̇ (time for a marker to go once round)
  double area_change = 0;  // A_end/A_0 − 1
  double centre_drift = 0; // |y_c − H/2| / a at the end
  // Wall-time split (s) of the IB cycle.
  double t_forces = 0, t_zero = 0, t_spread = 0, t_fluid = 0, t_moments = 0, t_move = 0, wall_time_s = 0;
  std::vector<double> strain_history, D_history, theta_history;  // every 0.1 strain unit
};

CapsuleResult run_capsule(const CapsuleConfig& c);

// Simple shear between walls at y = 0 and ny moving at ∓U = ∓γ̇ ny/2 (BGK, τ), started
// from the undisturbed profile u = γ̇(y − H/2) with node y at j + ½ (lattice units).
fluid::FluidLattice make_shear_lattice(int nx, int ny, double gamma, double tau);

}  // namespace erythro::vv
