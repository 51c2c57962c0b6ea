#pragma once
// Shared by the issue-3 fluid cases (Taylor–Green, Womersley, manufactured solution,
// Galilean/symmetry checks): consistent initial populations from a known flow field,
// and error norms of two-component fields.
#include <span>
#include <vector>

#include "fluid/fluid_lattice.hpp"

namespace erythro::vv {

// A flow field on the nodes, with its velocity gradient (for the non-equilibrium part).
struct FlowField {
  std::vector<double> rho, ux, uy;
  std::vector<double> dux_dx, dux_dy, duy_dx, duy_dy;  // empty: equilibrium only
  explicit FlowField(std::size_t n = 0);
  void resize(std::size_t n, bool with_gradients);
  void drop_gradients();  // equilibrium-only initialisation
};

// Overwrites the stored populations of `lattice` with a state consistent with `field`
// at t = 0. The stored populations are POST-collision ones (the pull step streams
// them, then collides), so, with the Chapman–Enskog non-equilibrium part
// f_neq = −τ w_i ρ Q_i:∇u / c_s² of the pre-collision populations (Krüger et al.
// 2017, The Lattice Boltzmann Method, ch. 5 on initial conditions; Mei et al. 2006,
// Comput Fluids 35:855), the stored value is
//   f*_i = f_eq_i(ρ, u) + (1 − 1/τ) f_neq_i = f_eq_i − (τ − 1) 3 w_i ρ Q_i:∇u,
//   Q_i = c_i c_i − c_s² I,
// plus w_i 3 c_i·F/2 when a force F acts, so that Σ c_i f*_i = ρu + F/2 as after a
// Guo collision. τ is the viscous (symmetric) relaxation time, τ+ for TRT. Without
// gradients only the equilibrium (and force) part is set.
void initialize_post_collision(fluid::FluidLattice& lattice, const FlowField& field,
                               std::span<const double> fx = {}, std::span<const double> fy = {});

// sqrt(Σ|a − b|²/Σ|b|²) over both components of a vector field.
double relative_l2_vector(std::span<const double> ax, std::span<const double> ay, std::span<const double> bx,
                          std::span<const double> by);

// Cell-centred node coordinate (model: node (x, y) sits at (x + ½, y + ½)).
inline double node_position(int index) { return index + 0.5; }

}  // namespace erythro::vv
