// Case verification.conservation (issue 2 §9c).
//
// Requirement: in a fully periodic box the scheme conserves mass to round-off
// (relative drift ≤ 1e-12 over 10⁴ steps) and the change of total momentum equals
// the impulse of the applied body force, for BGK and TRT, with a uniform force and
// with a non-uniform per-node force field.
// Reference: the collision conserves Σf exactly and adds exactly F per node and step
// (Guo et al. 2002; docs/model.md §1); streaming only moves populations.
// Runs: verification/fluid/periodic_box.toml (32 × 32, τ, collision, 10⁴ steps; the
// uniform force as [body_force]); the non-trivial start and the per-node force field are
// set on the simulation's fluid before the run (CaseRunOptions::configure). Mass and
// momentum are the fluid probe's total_mass_kg_per_m and momentum_{x,y}_N_s_per_m series
// at the first and last samples (run.h5), i.e. Σρ and Σρu of the moments. Those carry
// Guo's half-force correction ρu = Σc f* − F/2 with the force of the last collision; at
// step 0 no collision has run, so a uniform force enters from step 1 only (the start is
// the equilibrium of the given u): Σρu changes by (n − ½)·ΣF over n steps, a per-node
// field that is set before the run (and read as it is) by n·ΣF.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/case_support.hpp"
#include "common/scene_case.hpp"
#include "fluid_scenes.hpp"

using namespace erythro;

namespace {
constexpr long kSteps = 10000;

struct Drift {
  double mass = 0.0, momentum = 0.0;
  std::string scene_text;
};

Drift run_box(fluid::CollisionModel model, bool force_field, double tau) {
  static const vv::SceneFile box("verification/fluid/periodic_box.toml");
  const Grid g{32, 32};
  std::vector<std::string> o = {vv::set_grid(g.nx, g.ny), vv::set_collision(model), vv::set("run.steps", kSteps)};
  o.push_back(vv::set_tau(box, o, tau));
  if (!force_field) o.push_back(vv::set_body_force(box, o, {1e-6, -5e-7}));
  double fx_total = 0.0, fy_total = 0.0;
  vv::CaseRunOptions options;
  options.configure = [&](sim::Simulation& simulation) {
    fluid::FluidLattice& lattice = *simulation.fluid();
    // A non-trivial initial state: shear wave plus density perturbation.
    std::vector<double> rho(g.size()), ux(g.size()), uy(g.size());
    const double k = 2.0 * std::numbers::pi / g.nx;
    for (int y = 0; y < g.ny; ++y) {
      for (int x = 0; x < g.nx; ++x) {
        const auto n = g.index(x, y);
        rho[n] = 1.0 + 0.01 * std::sin(k * x) * std::cos(2 * k * y);
        ux[n] = 0.05 * std::sin(k * y);
        uy[n] = 0.03 * std::cos(k * x);
      }
    }
    lattice.initialize(rho, ux, uy);
    if (!force_field) return;
    lattice.enable_force_field();
    for (int y = 0; y < g.ny; ++y) {
      for (int x = 0; x < g.nx; ++x) {
        const auto n = g.index(x, y);
        lattice.force_x()[n] = 1e-6 * (1.0 + std::sin(k * y));
        lattice.force_y()[n] = -2e-6 * std::cos(k * x) * std::cos(k * x);
        fx_total += lattice.force_x()[n];
        fy_total += lattice.force_y()[n];
      }
    }
  };
  const std::string label = std::string(fluid::to_string(model)) + (force_field ? "_field" : "_uniform") + "_tau" +
                            std::to_string(tau).substr(0, 4);
  const vv::CaseRun run = vv::run_case_scene(box.scene(o), "verification.conservation", label, options);
  // Back to lattice units: mass ρ0h² per node, momentum ρ0h²·h/Δt.
  const auto& sc = run.setup.scales;
  const double mass_scale = sc.density_kg_m3 * sc.length_m * sc.length_m;
  const double momentum_scale = mass_scale * sc.velocity_m_s();
  const auto& mass = run.file.series("total_mass_kg_per_m");
  const auto& px = run.file.series("momentum_x_N_s_per_m");
  const auto& py = run.file.series("momentum_y_N_s_per_m");
  const std::size_t last = mass.size() - 1;
  double shift = 0.0;  // the uniform force's missing half step at t = 0
  if (!force_field) {
    fx_total = run.setup.body_force[0] * double(g.size());
    fy_total = run.setup.body_force[1] * double(g.size());
    shift = 0.5;
  }
  Drift d;
  d.mass = std::abs(mass[last] - mass[0]) / mass[0];
  const double ix = fx_total * kSteps, iy = fy_total * kSteps;
  const double ex = fx_total * (kSteps - shift), ey = fy_total * (kSteps - shift);
  d.momentum = std::hypot((px[last] - px[0]) / momentum_scale - ex, (py[last] - py[0]) / momentum_scale - ey) /
               std::hypot(ix, iy);
  d.scene_text = run.file.scene_text();
  return d;
}
}  // namespace

TEST(Conservation, MassAndMomentumBalance) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.conservation", "fluid");
  record.set_requirement(
      "Periodic box, 10^4 steps: total mass constant to 1e-12 relative; change of total momentum equals the "
      "applied force impulse (relative mismatch <= 1e-10), BGK and TRT, uniform and per-node force.");
  record.set_reference("Exact conservation of the collision invariants and Guo forcing (Guo et al. 2002, PRE 65:046308).");
  record.set_parameter("grid", std::string("32 x 32 periodic"));
  record.set_parameter("steps", 10000.0);
  double worst_mass = 0, worst_momentum = 0;
  for (auto model : {fluid::CollisionModel::bgk, fluid::CollisionModel::trt}) {
    for (bool field : {false, true}) {
      for (double tau : {0.51, 0.8, 1.7}) {
        const vv::Stopwatch clock;
        const Drift d = run_box(model, field, tau);
        worst_mass = std::max(worst_mass, d.mass);
        worst_momentum = std::max(worst_momentum, d.momentum);
        record.add_run({{"model", std::string(fluid::to_string(model))}, {"force", std::string(field ? "field" : "uniform")},
                        {"tau", tau}, {"mass_drift", d.mass}, {"momentum_mismatch", d.momentum},
                        {"wall_time_s", clock.seconds()}},
                       d.scene_text);
      }
    }
  }
  EXPECT_TRUE(record.add_metric({"mass drift", "max relative change of total mass over 10^4 steps", "", worst_mass,
                                 1e-12, 0.0, io::Comparison::at_most,
                                 "issue 2 requirement; round-off of 10^4 sums of 9216 terms is ~1e-13"}))
      << worst_mass;
  EXPECT_TRUE(record.add_metric({"momentum balance",
                                 "max |dP - impulse| / |impulse| (uniform force: impulse of n - 1/2 steps, see source)",
                                 "", worst_momentum, 1e-10, 0.0,
                                 io::Comparison::at_most,
                                 "the force adds exactly F per node and step; the bound allows round-off in summing "
                                 "momentum O(1) per node over 1024 nodes against an impulse of O(10)"}))
      << worst_momentum;
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
