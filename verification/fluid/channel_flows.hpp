#pragma once
// Wall-bounded channel flows used by several fluid cases: a periodic strip of
// nx × N nodes between halfway bounce-back walls at y = 0 and y = N (lattice units).
#include <vector>

#include "fluid/fluid_lattice.hpp"

namespace erythro::vv {

struct ChannelResult {
  std::vector<double> ux;  // velocity profile across the channel (one column)
  long steps = 0;
  double wall_time_s = 0.0;
};

// Steps needed for a flow started from rest between walls N apart to come within
// `residual` (relative) of steady state: the slowest mode sin(πy/N) decays like
// exp(−ν(π/N)² t), so t = ln(1/residual) N² / (ν π²).
long steps_to_steady_state(int N, double nu, double residual);

// Runs `steps` steps and returns the velocity profile of the middle column.
ChannelResult run_channel(fluid::FluidLattice& lattice, long steps);

// Exact force-driven Poiseuille profile at node centres y = j + ½: u = F y (N − y) / (2ν).
std::vector<double> poiseuille_exact(int N, double force, double nu);

}  // namespace erythro::vv
