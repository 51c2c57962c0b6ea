#pragma once
// Doubly periodic double shear layer (Minion & Brown 1997, J Comput Phys 138:734;
// the layer with width parameter 30, δ = L/30), used by verification.stability_map. Lattice units, L × L nodes,
// node (x, y) at ((x + ½), (y + ½)):
//   u = U tanh((y − L/4)/δ)      for y ≤ L/2,
//   u = U tanh((3L/4 − y)/δ)     for y > L/2,
//   v = ε U sin(2π (x/L + 1/4)),  δ = L/30, ε = 0.05, ρ = 1.
// Two thin shear layers roll up into vortices within about one convective time L/U;
// at δ ≈ 2h (L = 64) the layers are under-resolved, which is what makes the set-up a
// stress test of a collision operator's stability at low viscosity.
#include <string>

#include "fluid/fluid_lattice.hpp"

namespace erythro::vv {

struct ShearLayerSpec {
  fluid::CollisionConfig collision;
  int L = 64;                     // nodes per side
  double U = 0.05;                // lattice velocity amplitude
  double convective_times = 2.0;  // run length in units of L/U
  long check_interval = 16;       // health check every K steps (and at the end)
  double max_mach = 1.0;          // |u|/c_s above this counts as diverged
};

struct ShearLayerRun {
  bool stable = true;
  long steps = 0;          // steps run (the step of the failing health check if diverged)
  long steps_planned = 0;
  std::string diagnosis;   // "" when stable; else "step S: quantity = v at node (x, y) ..."
  double wall_time_s = 0.0;
};

void initialize_double_shear_layer(fluid::FluidLattice& lattice, double U);

// Runs the layer and stops at the first unhealthy check (FluidLattice::check_health).
ShearLayerRun run_double_shear_layer(const ShearLayerSpec& spec);

// "step 1200: velocity_x = nan at node (12, 3) is not finite" (health report, lattice units).
std::string describe_health(long step, const HealthReport& report);

}  // namespace erythro::vv
