#pragma once
// Initial states of the fluid (lattice units): a flow field on the nodes, the analytic
// flows a scene's [initial] table names (docs/scenes.md), and the populations that
// start a run consistently from a flow field, with the Chapman–Enskog non-equilibrium
// part of its velocity gradient (docs/model.md §1; Krüger et al. 2017, The Lattice
// Boltzmann Method, §5.5; Mei et al. 2006, Comput Fluids 35:855).
#include <array>
#include <span>
#include <vector>

#include "fluid/boundary.hpp"
#include "fluid/fluid_lattice.hpp"
#include "lattice/grid.hpp"

namespace erythro::fluid {

// ρ and u on the nodes (n = y·nx + x), and the velocity gradient when the
// non-equilibrium part is wanted (empty: equilibrium only).
struct FlowField {
  std::vector<double> rho, ux, uy;
  std::vector<double> dux_dx, dux_dy, duy_dx, duy_dy;
  explicit FlowField(std::size_t n = 0);
  // ρ = 1, u = 0 on n nodes; zero gradients if `with_gradients`, none otherwise.
  void resize(std::size_t n, bool with_gradients);
  bool has_gradients() const { return !dux_dx.empty(); }
  void drop_gradients();  // equilibrium-only initialisation
};

// Overwrites the stored populations of `lattice` with a state consistent with `field`
// at t = 0. The stored populations are POST-collision ones (the pull step streams them,
// then collides), so, with the Chapman–Enskog non-equilibrium part
// f_neq = −τ w_i ρ Q_i:∇u / c_s² of the pre-collision populations, the stored value is
//   f*_i = f_eq_i(ρ, u) + (1 − 1/τ) f_neq_i = f_eq_i − (τ − 1) 3 w_i ρ Q_i:∇u,
//   Q_i = c_i c_i − c_s² I,
// plus w_i 3 c_i·F/2 when a force F is given, so that Σ c_i f*_i = ρu + F/2 as after a
// Guo collision. τ is the viscous (symmetric) relaxation time, τ+ for TRT, per node
// when the lattice has a τ field. Without gradients only the equilibrium (and force)
// part is set.
void initialize_post_collision(FluidLattice& lattice, const FlowField& field, std::span<const double> fx = {},
                               std::span<const double> fy = {});

// The analytic flows of [initial] (node centres at (i + ½, j + ½)); `gradients` also
// fills the exact velocity gradient.
//  uniform:            u = u0.
//  shear:              u_x = u_b + (u_t − u_b) y/n_y between the bottom and top walls.
//  taylor_green:       u = −U cos(k_x x) sin(k_y y), v = U (k_x/k_y) sin(k_x x) cos(k_y y),
//                      ρ = 1 + p/c_s², p = −U²/4 [cos 2k_x x + (k_x/k_y)² cos 2k_y y], k = 2π/n.
//  double_shear_layer: u = U tanh((y − n_y/4)/δ) for y ≤ n_y/2, U tanh((3n_y/4 − y)/δ) above,
//                      v = εU sin(2π(x/n_x + ¼)), δ = n_y/30, ε = 0.05 (Minion & Brown 1997,
//                      J Comput Phys 138:734, the thick layer).
FlowField uniform_flow(const Grid& grid, std::array<double, 2> u0, bool gradients);
FlowField shear_flow(const Grid& grid, const BoundaryConfig& walls, bool gradients);
FlowField taylor_green_flow(const Grid& grid, double U, bool gradients);
FlowField double_shear_layer_flow(const Grid& grid, double U, bool gradients);

}  // namespace erythro::fluid
