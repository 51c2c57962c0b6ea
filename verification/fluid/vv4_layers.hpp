#pragma once
// Two-layer channel flows for verification.layered_viscosity: a periodic column of
// 1 × N nodes between halfway bounce-back walls at y = 0 and y = N (lattice units),
// kinematic viscosity ν1 below the interface y = a and ν2 above it (ρ = 1, so the
// dynamic viscosities μ = ρν have the same ratio), per-node τ = ½ + 3ν, run as the
// scene verification/fluid/layered_channel.toml ([[fluid.layers]]).
#include <string>
#include <vector>

#include "fluid/collision.hpp"

namespace erythro::vv {

enum class LayerFlow { couette, poiseuille };
std::string to_string(LayerFlow flow);

// Where the interface sits and what viscosity a node on it gets.
//  midpoint        : N even, interface y = N/2 halfway between rows N/2 − 1 and N/2.
//  node_harmonic   : N odd, interface through the centre of row J = (N−1)/2 (y = N/2),
//                    that row gets 1/ν = ½(1/ν1 + 1/ν2).
//  node_arithmetic : as above, ν = ½(ν1 + ν2).
//  node_lower      : as above, ν = ν1 (the row belongs to the lower layer).
enum class InterfacePlacement { midpoint, node_harmonic, node_arithmetic, node_lower };
std::string to_string(InterfacePlacement placement);

struct TwoLayerProblem {
  LayerFlow flow = LayerFlow::couette;
  InterfacePlacement placement = InterfacePlacement::midpoint;
  int N = 8;                    // nodes across; the channel width is H = N
  double nu_lower = 0.0, nu_upper = 0.0;
  double drive = 0.0;           // Couette: top-wall speed U; Poiseuille: force density F
  double interface_y() const { return 0.5 * N; }
  // Rows whose node centre lies within 2 spacings of the interface (2 rows on each
  // side; 5 rows when the interface runs through a row).
  bool near_interface(int row) const;
  // Rows in the outer halves of the two layers, |y − a| > H/4 (a fixed fraction of
  // the channel, so the region is the same at every resolution).
  bool far_from_interface(int row) const;
  double row_viscosity(int row) const;
};

// Exact piecewise solution at height y (derivation in layered_viscosity_test.cpp).
double two_layer_exact(const TwoLayerProblem& p, double y);

struct TwoLayerRun {
  std::vector<double> ux, exact;  // per row, middle column
  long steps = 0;
  double wall_time_s = 0.0;
  double error_l2 = 0.0;         // relative L2, all rows
  double error_near_linf = 0.0;  // max |e| over near_interface rows / max |u_exact|
  double error_far_l2 = 0.0;     // relative L2 over the far_from_interface rows
  // Residual of the derived discrete relations (layered_viscosity_test.cpp) at every
  // link, node stress σ_j = −(1 − ω_j/2)/(1 − ω_j) Σ c_x c_y f*_j from the stored
  // post-collision populations (ω_j ≠ 1):
  //  (i)  σ_{j+1} − σ_j + F = 0,  relative to max |σ_j|;
  //  (ii) u_{j+1} − u_j − ½(σ_j/ν_j + σ_{j+1}/ν_{j+1}) − 2F(τ−_{j+1} − τ−_j) = 0,
  //       relative to max |u|.
  double link_residual = 0.0;  // max of the two
  std::string scene_text;      // what ran
};

// Runs from rest to within `residual` of steady state and measures the errors (TRT with
// the scene's Λ = 3/16).
TwoLayerRun run_two_layer(const TwoLayerProblem& p, fluid::CollisionModel model, double residual);

}  // namespace erythro::vv
