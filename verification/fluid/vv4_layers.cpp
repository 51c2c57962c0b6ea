#include "vv4_layers.hpp"

#include <algorithm>
#include <cmath>

#include "channel_flows.hpp"
#include "common/case_support.hpp"

namespace erythro::vv {

std::string to_string(LayerFlow flow) { return flow == LayerFlow::couette ? "couette" : "poiseuille"; }

std::string to_string(InterfacePlacement p) {
  switch (p) {
    case InterfacePlacement::midpoint: return "midpoint";
    case InterfacePlacement::node_harmonic: return "node_harmonic";
    case InterfacePlacement::node_arithmetic: return "node_arithmetic";
    case InterfacePlacement::node_lower: return "node_lower";
  }
  return "?";
}

bool TwoLayerProblem::near_interface(int row) const {
  return std::abs((row + 0.5) - interface_y()) <= 2.0;
}

bool TwoLayerProblem::far_from_interface(int row) const {
  return std::abs((row + 0.5) - interface_y()) > 0.25 * N;
}

double TwoLayerProblem::row_viscosity(int row) const {
  const double y = row + 0.5, a = interface_y();
  if (std::abs(y - a) > 0.25) return y < a ? nu_lower : nu_upper;
  // A node row on the interface (node_* placements only: N odd).
  switch (placement) {
    case InterfacePlacement::node_harmonic: return 2.0 / (1.0 / nu_lower + 1.0 / nu_upper);
    case InterfacePlacement::node_arithmetic: return 0.5 * (nu_lower + nu_upper);
    default: return nu_lower;
  }
}

// Continuum solution (layered_viscosity_test.cpp): shear stress σ = ν du/dy (ρ = 1)
// continuous at y = a, σ(y) = σ0 − F y, u(0) = 0, u(H) = U.
//  Couette (F = 0):  σ0 = U / (a/ν1 + (H − a)/ν2);
//  Poiseuille (U = 0): σ0 = F [a²/ν1 + (H² − a²)/ν2] / (2 [a/ν1 + (H − a)/ν2]);
//  u = (σ0 y − F y²/2)/ν1 for y ≤ a,  u(a) + (σ0 (y − a) − F (y² − a²)/2)/ν2 above.
double two_layer_exact(const TwoLayerProblem& p, double y) {
  const double H = p.N, a = p.interface_y(), n1 = p.nu_lower, n2 = p.nu_upper;
  const double resistance = a / n1 + (H - a) / n2;
  double F = 0.0, s0 = 0.0;
  if (p.flow == LayerFlow::couette) {
    s0 = p.drive / resistance;
  } else {
    F = p.drive;
    s0 = F * (a * a / n1 + (H * H - a * a) / n2) / (2.0 * resistance);
  }
  if (y <= a) return (s0 * y - 0.5 * F * y * y) / n1;
  const double ua = (s0 * a - 0.5 * F * a * a) / n1;
  return ua + (s0 * (y - a) - 0.5 * F * (y * y - a * a)) / n2;
}

TwoLayerRun run_two_layer(const TwoLayerProblem& p, fluid::CollisionModel model, double trt_magic,
                          double residual) {
  fluid::BoundaryConfig walls;
  walls.bottom.type = fluid::SideType::wall;
  walls.top.type = p.flow == LayerFlow::couette ? fluid::SideType::moving_wall : fluid::SideType::wall;
  if (p.flow == LayerFlow::couette) walls.top.ux = p.drive;
  const Grid g{1, p.N};  // x-invariant flow: one periodic column suffices
  fluid::FluidLattice lattice(g, {model, 0.5 + 3.0 * p.nu_upper, trt_magic}, walls);
  lattice.enable_tau_field();
  double nu_min = p.nu_upper;
  for (int y = 0; y < g.ny; ++y) {
    const double nu = p.row_viscosity(y);
    nu_min = std::min(nu_min, nu);
    for (int x = 0; x < g.nx; ++x) lattice.tau_field()[g.index(x, y)] = 0.5 + 3.0 * nu;  // ν = (τ − ½)/3
  }
  if (p.flow == LayerFlow::poiseuille) lattice.set_uniform_force(p.drive, 0.0);

  // From rest, the slowest mode decays at least as fast as exp(−ν_min (π/N)² t)
  // (Rayleigh quotient ∫ν u'² / ∫u² ≥ ν_min π²/N²), so the single-viscosity estimate
  // of channel_flows.hpp with ν = ν_min is an upper bound.
  const ChannelResult channel = run_channel(lattice, steps_to_steady_state(p.N, nu_min, residual));

  TwoLayerRun run;
  run.steps = channel.steps;
  run.wall_time_s = channel.wall_time_s;
  run.ux = channel.ux;
  double far_e2 = 0, far_u2 = 0, near_max = 0, u_max = 0;
  for (int y = 0; y < g.ny; ++y) {
    const double u = run.ux[static_cast<std::size_t>(y)], ex = two_layer_exact(p, y + 0.5), e = u - ex;
    run.exact.push_back(ex);
    u_max = std::max(u_max, std::abs(ex));
    if (p.near_interface(y)) near_max = std::max(near_max, std::abs(e));
    if (p.far_from_interface(y)) {
      far_e2 += e * e;
      far_u2 += ex * ex;
    }
  }
  // Derived link relations (i), (ii); τ− = τ+ (BGK), ½ + Λ/(τ+ − ½) (TRT), 1 (regularized).
  const double F = p.flow == LayerFlow::poiseuille ? p.drive : 0.0;
  const auto f = lattice.populations();
  std::vector<double> sigma, tau_minus, nu;
  double sigma_max = 0.0;
  for (int y = 0; y < g.ny; ++y) {
    const std::size_t n = g.index(0, y), N = g.size();
    const double pxy = f[5 * N + n] - f[6 * N + n] + f[7 * N + n] - f[8 * N + n];
    const double tau = lattice.tau_field()[n], om = 1.0 / tau;
    sigma.push_back(-(1.0 - 0.5 * om) / (1.0 - om) * pxy);
    sigma_max = std::max(sigma_max, std::abs(sigma.back()));
    nu.push_back((tau - 0.5) / 3.0);
    tau_minus.push_back(model == fluid::CollisionModel::bgk   ? tau
                        : model == fluid::CollisionModel::trt ? fluid::trt_tau_minus(tau, trt_magic)
                                                              : 1.0);
  }
  for (int j = 0; j + 1 < g.ny; ++j) {
    const std::size_t a = static_cast<std::size_t>(j), b = a + 1;
    const double r1 = (sigma[b] - sigma[a] + F) / sigma_max;
    const double r2 = (run.ux[b] - run.ux[a] - 0.5 * (sigma[a] / nu[a] + sigma[b] / nu[b]) -
                       2.0 * F * (tau_minus[b] - tau_minus[a])) / u_max;
    run.link_residual = std::max({run.link_residual, std::abs(r1), std::abs(r2)});
  }
  run.error_l2 = relative_l2(run.ux, run.exact);
  run.error_near_linf = near_max / u_max;
  run.error_far_l2 = std::sqrt(far_e2 / far_u2);
  return run;
}

}  // namespace erythro::vv
