#include "vv4_layers.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "channel_flows.hpp"
#include "common/case_support.hpp"
#include "fluid_scenes.hpp"
#include "simulation/simulation.hpp"

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

TwoLayerRun run_two_layer(const TwoLayerProblem& p, fluid::CollisionModel model, double residual) {
  static const SceneFile file("verification/fluid/layered_channel.toml");
  const Grid g{1, p.N};  // x-invariant flow: one periodic column suffices
  double nu_min = p.nu_upper;
  for (int y = 0; y < g.ny; ++y) nu_min = std::min(nu_min, p.row_viscosity(y));
  // From rest, the slowest mode decays at least as fast as exp(−ν_min (π/N)² t)
  // (Rayleigh quotient ∫ν u'² / ∫u² ≥ ν_min π²/N²), so the single-viscosity estimate
  // of channel_flows.hpp with ν = ν_min is an upper bound.
  std::vector<std::string> o = {set_grid(1, p.N), set_collision(model),
                                set("run.steps", steps_to_steady_state(p.N, nu_min, residual))};
  const double tau_upper = 0.5 + 3.0 * p.nu_upper;  // the fluid (ν = (τ − ½)/3)
  o.push_back(set_tau(file, o, tau_upper));
  // layers[0]: ν1 below the interface; layers[1]: ν2 above a midpoint interface, or the
  // interface row J = (N − 1)/2 with its own viscosity (vv4_layers.hpp).
  const bool row = p.placement != InterfacePlacement::midpoint;
  const int J = p.N / 2;
  const double lo = row ? J : 0.5 * p.N, hi = row ? J + 1.0 : double(p.N);
  const double tau_row = 0.5 + 3.0 * (row ? p.row_viscosity(J) : p.nu_upper);
  const double mu = file.scene(o).fluid.viscosity_cP;
  for (const auto& [i, y0, y1, tau] : {std::tuple{0, 0.0, lo, 0.5 + 3.0 * p.nu_lower}, std::tuple{1, lo, hi, tau_row}}) {
    const std::string key = "fluid.layers[" + std::to_string(i) + "].";
    o.push_back(set(key + "y_um", y0, y1));
    o.push_back(set_exact(file, o, key + "viscosity_cP", tau, mu * (tau - 0.5) / (tau_upper - 0.5),
                          [i](const scene::LatticeSetup& s) { return s.viscosity_layers[i].tau; }));
  }
  if (p.flow == LayerFlow::couette) {
    o.push_back(set_top_wall_velocity(file, o, p.drive));
  } else {
    o.push_back(set("boundaries.top.type", "\"wall\""));
    o.push_back(set_body_force(file, o, {p.drive, 0.0}));
  }
  // The post-collision populations and τ of the final state, for the link relations.
  std::vector<double> f, tau_field;
  CaseRunOptions options;
  const long steps = file.setup(o).total_steps;
  options.configure = [&](sim::Simulation& simulation) {
    const fluid::FluidLattice& lattice = *simulation.fluid();
    simulation.add_stage(
        sim::Phase::observe, "final_populations",
        [&](long) {
          const auto pop = lattice.populations();
          f.assign(pop.begin(), pop.end());
          tau_field.assign(lattice.tau_field().begin(), lattice.tau_field().end());
        },
        steps, steps - 1);
  };
  const std::string label = to_string(p.flow) + "_" + std::string(fluid::to_string(model)) + "_" +
                            to_string(p.placement) + "_N" + std::to_string(p.N);
  const ChannelResult channel = run_channel(file, o, "verification.layered_viscosity", label, options);

  TwoLayerRun run;
  run.steps = channel.steps;
  run.wall_time_s = channel.wall_time_s;
  run.ux = channel.ux;
  run.scene_text = channel.scene_text;
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
  const double trt_magic = file.setup(o).collision.trt_magic;
  std::vector<double> sigma, tau_minus, nu;
  double sigma_max = 0.0;
  for (int y = 0; y < g.ny; ++y) {
    const std::size_t n = g.index(0, y), N = g.size();
    const double pxy = f[5 * N + n] - f[6 * N + n] + f[7 * N + n] - f[8 * N + n];
    const double tau = tau_field[n], om = 1.0 / tau;
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
