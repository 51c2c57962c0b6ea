// The fluid's scene features used by the fluid verification cases: initial.non_equilibrium,
// initial.type = "double_shear_layer", [[fluid.layers]], the oscillating body force's time
// convention, the fluid probe's momentum and FieldsRecorder::at.
// Scene: water in a 10 µm box, h = 1 µm, τ = 0.8 (Δt = 1e-7 s, u_lat = u[µm/s]·1e-7).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fluid/initial_state.hpp"
#include "input_error_matchers.hpp"
#include "lattice/d2q9.hpp"
#include "scene/scene_parser.hpp"
#include "scene_fixtures.hpp"
#include "simulation/fields_recorder.hpp"
#include "simulation/series_recorder.hpp"
#include "simulation/simulation.hpp"

namespace erythro::scene {
namespace {

using testing::channel_scene;
using testing::derive;
using testing::error_of;

const std::string channel = channel_scene("10, 10", "1.0", "0.8", "20");
const std::string periodic = channel_scene("10, 10", "1.0", "0.8", "20", /*walls=*/false);
const Grid g10{10, 10};
const std::string layered = channel + "[[fluid.layers]]\ny_um = [0, 5]\nviscosity_cP = 3.0\n";

Scene parse(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return parse_scene(text, "test.toml", overrides);
}

struct Outcome {
  sim::RunSummary summary;
  sim::FieldsRecorder fields;
  sim::SeriesRecorder series;
};

// Runs the scene with a FieldsRecorder and a SeriesRecorder.
void run(const Scene& scene, Outcome& out) {
  sim::Simulation simulation(scene, derive_lattice(scene));
  sim::ObserverList list;
  list.add(out.fields);
  list.add(out.series);
  out.summary = simulation.run(list);
}

TEST(FluidInitial, NonEquilibriumKeyIsABoolean) {
  EXPECT_TRUE(parse(periodic, {"initial.non_equilibrium=true"}).initial.non_equilibrium);
  EXPECT_FALSE(parse(periodic).initial.non_equilibrium);
  const std::string e = error_of([&] { parse(periodic, {"initial.non_equilibrium=1"}); });
  EXPECT_CONTAINS(e, "initial.non_equilibrium");
  EXPECT_CONTAINS(e, "true or false");
}

TEST(FluidInitial, DoubleShearLayerNeedsPeriodicSidesAndVelocityAlongX) {
  const std::vector<std::string> layer = {"initial.type=double_shear_layer", "initial.velocity_um_s=[1e5, 0]"};
  EXPECT_NEAR(derive(periodic, layer).initial_velocity[0], 0.01, 1e-15);
  EXPECT_CONTAINS(error_of([&] { derive(channel, layer); }), "needs all four sides periodic");
  EXPECT_CONTAINS(error_of([&] { parse(periodic, {"initial.type=double_shear_layer", "initial.velocity_um_s=[1, 1]"}); }),
                  "must be [U, 0]");
  // The speed check sees its amplitude: U = 0.1 lattice is Ma 0.17 > limits.max_mach.
  EXPECT_CONTAINS(error_of([&] { derive(periodic, {"initial.type=double_shear_layer", "initial.velocity_um_s=[1e6, 0]"}); }),
                  "initial.velocity_um_s");
}

TEST(FluidInitial, NonEquilibriumStartHasTheFlowsMomentsAndItsStress) {
  // The non-equilibrium part carries no mass or momentum: the moments at t = 0 are the flow's.
  Outcome eq, neq;
  const std::vector<std::string> tg = {"initial.type=taylor_green", "initial.velocity_um_s=[2e5, 0]", "run.steps=1"};
  run(parse(periodic, tg), eq);
  std::vector<std::string> tg_neq = tg;
  tg_neq.push_back("initial.non_equilibrium=true");
  run(parse(periodic, tg_neq), neq);
  const fluid::Moments& a = eq.fields.at(0);
  const fluid::Moments& b = neq.fields.at(0);
  const fluid::FlowField exact = fluid::taylor_green_flow(Grid{10, 10}, 0.02, false);
  for (std::size_t n = 0; n < a.rho.size(); ++n) {
    EXPECT_NEAR(b.rho[n], exact.rho[n], 1e-15);
    EXPECT_NEAR(b.ux[n], exact.ux[n], 1e-16);
    EXPECT_NEAR(b.uy[n], a.uy[n], 1e-16);
  }
  // ... but the stress differs: the next step's velocities differ at O(ν k² U) per step.
  double diff = 0.0;
  for (std::size_t n = 0; n < a.rho.size(); ++n)
    diff = std::max(diff, std::abs(eq.fields.at(1).ux[n] - neq.fields.at(1).ux[n]));
  EXPECT_GT(diff, 1e-6);
}

TEST(FluidInitial, NonEquilibriumShearStartHasTheSteadyCouetteStress) {
  // Couette flow u_x = γy: its steady state has Π*_xy = Σ c_x c_y f* = −ργ(τ − 1)/3 at every
  // node (relation (i) of verification/fluid/layered_viscosity_test.cpp with σ = ρνγ), the
  // xy moment of −(τ − 1) 3 w ρ Q:∇u. The non-equilibrium start has it from t = 0; the
  // equilibrium start (Π*_xy = 0) builds it up. The velocity is exact in both (Π_eq,xy = 0).
  const std::vector<std::string> couette = {"boundaries.top.type=moving_wall", "boundaries.top.velocity_um_s=[1e5, 0]",
                                            "initial.type=shear", "run.steps=50"};
  const double gamma = 0.01 / 10.0, expected = -gamma * (0.8 - 1.0) / 3.0;
  for (const bool non_equilibrium : {true, false}) {
    std::vector<std::string> o = couette;
    o.push_back(std::string("initial.non_equilibrium=") + (non_equilibrium ? "true" : "false"));
    const Scene scene = parse(channel, o);
    sim::Simulation simulation(scene, derive_lattice(scene));
    auto pxy = [&] {  // at node (3, 5)
      const auto f = simulation.fluid()->populations();
      double sum = 0.0;
      for (int i = 0; i < d2q9::Q; ++i) sum += d2q9::cx[i] * d2q9::cy[i] * f[i * 100 + g10.index(3, 5)];
      return sum;
    };
    const double at_start = pxy();
    sim::RunObserver none;
    simulation.run(none);
    if (non_equilibrium) {
      EXPECT_NEAR(at_start, expected, 1e-12 * std::abs(expected));
      EXPECT_NEAR(pxy(), expected, 1e-4 * std::abs(expected));  // O(u²) terms of f_eq aside
    } else {
      EXPECT_LT(std::abs(at_start), 1e-15 * std::abs(expected));
    }
  }
}

TEST(FluidInitial, PostCollisionStartCarriesHalfTheForce) {
  // Σ c f* = ρu + F/2 at every node, so the first step's collision sees u + F/2 → u + F.
  fluid::FluidLattice lattice(Grid{4, 4}, {}, fluid::BoundaryConfig{});
  fluid::FlowField field = fluid::uniform_flow(Grid{4, 4}, {0.01, 0.0}, true);
  const std::vector<double> fx(16, 1e-4), fy(16, 0.0);
  fluid::initialize_post_collision(lattice, field, fx, fy);
  lattice.set_uniform_force(1e-4, 0.0);
  lattice.step();
  EXPECT_NEAR(lattice.moments().ux[5], 0.01 + 1e-4, 1e-17);
}

TEST(FluidLayers, ParsedConvertedAndWrittenPerNode) {
  const LatticeSetup s = derive(layered);
  ASSERT_EQ(s.viscosity_layers.size(), 1u);
  // τ = ½ + (τ0 − ½) μ_l/μ = 0.5 + 0.3 · 3.
  EXPECT_DOUBLE_EQ(s.viscosity_layers[0].tau, 1.4);
  EXPECT_DOUBLE_EQ(s.viscosity_layers[0].y_hi, 5.0);
  // A layer of the fluid's own viscosity gets exactly the fluid's τ.
  EXPECT_EQ(derive(layered, {"fluid.layers[0].viscosity_cP=1.0"}).viscosity_layers[0].tau, s.collision.tau);
  sim::Simulation simulation(parse(layered), s);
  const std::span<const double> tau = std::as_const(*simulation.fluid()).tau_field();
  ASSERT_EQ(tau.size(), 100u);
  EXPECT_DOUBLE_EQ(tau[g10.index(3, 4)], 1.4);  // centre y = 4.5 < 5
  EXPECT_DOUBLE_EQ(tau[g10.index(3, 5)], 0.8);  // centre y = 5.5
  // Later layers win; x_um limits a layer to a rectangle.
  const LatticeSetup two = derive(layered + "[[fluid.layers]]\ny_um = [0, 10]\nx_um = [0, 2]\nviscosity_cP = 2.0\n");
  sim::Simulation second(parse(layered), two);
  const std::span<const double> t2 = std::as_const(*second.fluid()).tau_field();
  EXPECT_DOUBLE_EQ(t2[g10.index(1, 2)], 1.1);
  EXPECT_DOUBLE_EQ(t2[g10.index(2, 2)], 1.4);
}

TEST(FluidLayers, BadLayersAreRejected) {
  EXPECT_CONTAINS(error_of([&] { parse(layered, {"fluid.layers[0].viscosity_cP=-1"}); }), "must be in [1e-30, 1e+30] (cP)");
  EXPECT_CONTAINS(error_of([&] { parse(channel + "[[fluid.layers]]\nviscosity_cP = 3.0\n"); }),
                  "missing key 'fluid.layers[0].y_um'");
  EXPECT_CONTAINS(error_of([&] { parse(layered + "[[fluid.layers]]\ny_um = [0, 1]\nviscosty_cP = 2\n"); }),
                  "did you mean");
  EXPECT_CONTAINS(error_of([&] { parse(layered, {"fluid.layers[1].viscosity_cP=2"}); }), "1 [[layers]] entries");
  EXPECT_CONTAINS(error_of([&] { derive(layered, {"fluid.layers[0].y_um=[5, 0]"}); }), "must be increasing");
  EXPECT_CONTAINS(error_of([&] { derive(layered, {"fluid.layers[0].y_um=[4.6, 5.4]"}); }), "contains no node centre");
  EXPECT_CONTAINS(error_of([&] { derive(layered, {"fluid.layers[0].viscosity_cP=0.001"}); }),
                  "(0.5 + limits.min_tau_margin)");
}

TEST(FluidForce, OscillatingForceActsAtTheEndOfEachStep) {
  // The collision of step n ends at t = n + 1 and uses F(t = n + 1); the velocity after
  // it carries half of that force: u(s) = Σ_{t=1..s} F(t) − F(s)/2 from rest.
  Outcome r;
  run(parse(periodic, {"body_force.density_N_m3=[1e6, 0]", "body_force.frequency_Hz=1e5",
                       "output.fields_interval_steps=1"}),
      r);
  const double F0 = 1e6 * 1e-14 / 1e-3, w = 2.0 * std::numbers::pi * 1e5 * 1e-7;
  double sum = 0.0;
  for (long s = 1; s <= 20; ++s) {
    sum += F0 * std::cos(w * double(s));
    EXPECT_NEAR(r.fields.at(s).ux[0], sum - 0.5 * F0 * std::cos(w * double(s)), 1e-18) << "step " << s;
  }
}

TEST(FluidProbe, MomentumSeriesIsTheSumOfRhoU) {
  Outcome r;
  run(parse(periodic, {"initial.type=uniform", "initial.velocity_um_s=[1e5, -5e4]", "output.diagnostics_interval_steps=10"}),
      r);
  ASSERT_TRUE(r.series.has("momentum_x_N_s_per_m"));
  // 100 nodes of ρ = 1 at u = (0.01, −0.005): Σρu h² ρ0 · h/Δt = 1 · 1e-12 · 1000 · 10 m/s per unit.
  const double scale = 1000.0 * 1e-12 * 10.0;
  EXPECT_NEAR(r.series.series("momentum_x_N_s_per_m").back(), 100 * 0.01 * scale, 1e-12 * scale);
  EXPECT_NEAR(r.series.series("momentum_y_N_s_per_m").back(), -100 * 0.005 * scale, 1e-12 * scale);
  EXPECT_NEAR(r.series.series("total_mass_kg_per_m")[0], 100 * 1000.0 * 1e-12, 1e-22);
}

TEST(ShearProbe, CouetteWallStressIsMuGammaDotAndTheRelativeViscosityOne) {
  // Walls at ∓U (γ̇ = 2U/H), the steady Couette profile from the start: both wall stresses are
  // μγ̇ (eq 12.5 is exact for a linear profile) and the relative viscosity is 1; walls at rest
  // are not a simple shear and get no series.
  Outcome r;
  run(parse(channel, {"boundaries.top.type=moving_wall", "boundaries.top.velocity_um_s=[1e5, 0]",
                      "boundaries.bottom.type=moving_wall", "boundaries.bottom.velocity_um_s=[-1e5, 0]",
                      "initial.type=shear", "initial.non_equilibrium=true", "output.diagnostics_interval_steps=10"}),
      r);
  ASSERT_TRUE(r.series.has("shear_relative_viscosity"));
  const double mu_gamma = 1e-3 * 2.0 * 0.1 / 10e-6;  // water: 1 cP × 2 (0.1 m/s) / 10 µm = 20 Pa
  EXPECT_NEAR(r.series.series("wall_shear_stress_bottom_Pa").back(), mu_gamma, 1e-9 * mu_gamma);
  EXPECT_NEAR(r.series.series("wall_shear_stress_top_Pa").back(), mu_gamma, 1e-9 * mu_gamma);
  EXPECT_NEAR(r.series.series("shear_relative_viscosity").back(), 1.0, 1e-9);
  Outcome channel_flow;
  run(parse(channel, {"output.diagnostics_interval_steps=10"}), channel_flow);
  EXPECT_FALSE(channel_flow.series.has("shear_relative_viscosity"));
}

TEST(FieldsRecorder, AtFindsTheOutputOfAStep) {
  Outcome r;
  run(parse(periodic, {"output.fields_interval_steps=5"}), r);
  ASSERT_EQ(r.fields.snapshots().size(), 5u);  // 0, 5, 10, 15, 20
  EXPECT_EQ(&r.fields.at(15), &r.fields.snapshots()[3].moments);
  EXPECT_THROW(r.fields.at(7), std::logic_error);
}

}  // namespace
}  // namespace erythro::scene
