// units: physical → lattice conversion and the set-up checks.
// Hand-computed reference: ν = 1 cP / 1000 kg/m³ = 1e-6 m²/s, h = 1 µm, τ = 0.8
//   → Δt = (τ − ½) h² / (3ν) = 0.3 · 1e-12 / 3e-6 = 1e-7 s, ν_lat = 0.1,
//   u_lat = u Δt / h = u[m/s] · 0.1, F_lat = F Δt² / (ρ h) = F · 1e-14 / 1e-3 = F · 1e-11.
#include "scene/units.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "common/error.hpp"
#include "input_error_matchers.hpp"
#include "scene_fixtures.hpp"
#include "scene/scene_parser.hpp"

namespace erythro::scene {
namespace {

using testing::channel_scene;
using testing::derive;
using testing::error_of;

// A 10 µm × 10 µm channel: periodic in x, walls at bottom and top; and the same box periodic on all sides.
const std::string channel = channel_scene("10, 10", "1.0", "0.8", "1000");
const std::string periodic = channel_scene("10, 10", "1.0", "0.8", "1000", /*walls=*/false);

std::string derive_error(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return error_of([&] { derive(text, overrides); });
}

TEST(Units, TauToTimeStepAndBack) {
  const LatticeSetup a = derive(channel);
  EXPECT_EQ(a.grid.nx, 10);
  EXPECT_EQ(a.grid.ny, 10);
  EXPECT_DOUBLE_EQ(a.scales.length_m, 1e-6);
  EXPECT_DOUBLE_EQ(a.scales.time_s, 1e-7);
  EXPECT_DOUBLE_EQ(a.scales.density_kg_m3, 1000.0);
  EXPECT_DOUBLE_EQ(a.collision.tau, 0.8);
  EXPECT_DOUBLE_EQ(a.viscosity, 0.1);
  // Physical viscosity recovered from the lattice one: ν = ν_lat h²/Δt.
  EXPECT_DOUBLE_EQ(a.viscosity * a.scales.kinematic_viscosity_m2_s(), 1e-6);

  // Giving the step instead yields the same τ: τ = ½ + 3νΔt/h².
  std::string by_step = channel;
  by_step.replace(by_step.find("tau = 0.8"), 9, "step_s = 1e-7");
  const LatticeSetup c = derive(by_step);
  EXPECT_DOUBLE_EQ(c.collision.tau, 0.8);
  EXPECT_DOUBLE_EQ(c.scales.time_s, 1e-7);
}

TEST(Units, VelocityForceAndFrequencyConversion) {
  const LatticeSetup s = derive(channel, {"boundaries.top.type=moving_wall", "boundaries.top.velocity_um_s=[1000, 0]",
                                          "body_force.density_N_m3=[1e4, -2e3]", "body_force.frequency_Hz=1000",
                                          "body_force.phase_rad=0.25"});
  EXPECT_EQ(s.boundaries.top.type, fluid::SideType::moving_wall);
  EXPECT_DOUBLE_EQ(s.boundaries.top.ux, 1e-4);  // 1e-3 m/s × 1e-7 s / 1e-6 m
  EXPECT_DOUBLE_EQ(s.boundaries.top.uy, 0.0);
  EXPECT_DOUBLE_EQ(s.body_force[0], 1e-7);  // 1e4 N/m³ × 1e-14 s² / (1000 kg/m³ × 1e-6 m)
  EXPECT_DOUBLE_EQ(s.body_force[1], -2e-8);
  EXPECT_DOUBLE_EQ(s.force_frequency, 1e-4);  // 1000 Hz × 1e-7 s
  EXPECT_DOUBLE_EQ(s.force_phase, 0.25);
  // Round trip through the scales: F_phys = F_lat ρ h / Δt².
  EXPECT_DOUBLE_EQ(s.body_force[0] * s.scales.force_density_N_m3(), 1e4);
}

TEST(Units, InitialVelocityAndStepsFromDuration) {
  const LatticeSetup s = derive(periodic, {"initial.type=uniform", "initial.velocity_um_s=[-500, 200]"});
  EXPECT_DOUBLE_EQ(s.initial_velocity[0], -5e-5);
  EXPECT_DOUBLE_EQ(s.initial_velocity[1], 2e-5);
  EXPECT_DOUBLE_EQ(s.expected_max_speed, std::hypot(5e-5, 2e-5));

  std::string timed = channel;
  timed.replace(timed.find("steps = 1000"), 12, "duration_s = 1e-5");
  EXPECT_EQ(derive(timed).total_steps, 100);  // 1e-5 / 1e-7, despite round-off
  timed.replace(timed.find("duration_s = 1e-5"), 17, "duration_s = 1.005e-5");
  EXPECT_EQ(derive(timed).total_steps, 101);  // ⌈100.5⌉
}

TEST(Units, TaylorGreenSpeedInANonSquareBox) {
  const std::vector<std::string> tg{"initial.type=taylor_green", "initial.velocity_um_s=[1000, 0]"};
  // v = U (kx/ky) sin cos, kx/ky = ny/nx: the peak speed is U max(1, ny/nx).
  std::vector<std::string> wide = tg, tall = tg;
  wide.push_back("domain.size_um=[20, 10]");
  tall.push_back("domain.size_um=[10, 20]");
  EXPECT_DOUBLE_EQ(derive(periodic, wide).expected_max_speed, 1e-4);
  EXPECT_DOUBLE_EQ(derive(periodic, tall).expected_max_speed, 2e-4);
}

TEST(Units, PoiseuilleSpeedMachAndReynolds) {
  // Centre speed F H²/(8ν) = 1e-7 × 10² / 0.8 = 1.25e-5 (= 125 µm/s physical).
  const LatticeSetup s = derive(channel, {"body_force.density_N_m3=[1e4, 0]"});
  EXPECT_DOUBLE_EQ(s.expected_max_speed, 1.25e-5);
  EXPECT_DOUBLE_EQ(s.mach, 1.25e-5 * std::sqrt(3.0));
  EXPECT_DOUBLE_EQ(s.reynolds, 1.25e-5 * 10 / 0.1);  // L = channel width, 10 nodes
  EXPECT_DOUBLE_EQ(s.reynolds_length_m, 10e-6);
  const std::string report = format_lattice_report(parse_scene(channel, "u.toml", {"body_force.density_N_m3=[1e4, 0]"}), s);
  EXPECT_CONTAINS(report, "125 µm/s");
  EXPECT_CONTAINS(report, "1e-07 s");
  EXPECT_CONTAINS(report, "10 × 10");
  EXPECT_EQ(report.find("estimate"), std::string::npos) << report;
}

TEST(Units, ForceInPeriodicBoxIsAnEstimate) {
  const std::vector<std::string> force{"body_force.density_N_m3=[1e4, 0]"};
  const LatticeSetup s = derive(periodic, force);
  EXPECT_DOUBLE_EQ(s.expected_max_speed, 1.25e-5);  // Poiseuille with H = domain size
  const LatticeSetup short_run = derive(periodic, {"body_force.density_N_m3=[1e4, 0]", "run.steps=10"});
  EXPECT_DOUBLE_EQ(short_run.expected_max_speed, 1e-6);  // F × steps is smaller
  EXPECT_CONTAINS(format_lattice_report(parse_scene(periodic, "u.toml", force), s), "estimate");
}

TEST(Units, TauMarginRejection) {
  const std::string m = derive_error(channel, {"time.tau=0.502"});
  EXPECT_CONTAINS(m, "test.toml: key 'time.tau' = 0.502 is out of range: must be >= 0.505");
  EXPECT_CONTAINS(m, "limits.min_tau_margin");

  std::string by_step = channel;
  by_step.replace(by_step.find("tau = 0.8"), 9, "step_s = 1e-9");  // τ = 0.503
  const std::string s = derive_error(by_step);
  EXPECT_CONTAINS(s, "key 'time.step_s' = 1e-09 s gives τ = 0.503, below 0.505");
  EXPECT_CONTAINS(s, "time.step_s must be >= 1.66667e-09 s");  // (0.005) h² / (3ν)
}

TEST(Units, MachRejectionNamesTheSource) {
  // 1e6 µm/s → u_lat = 0.1, Ma = 0.173 > 0.1.
  const std::string m = derive_error(channel, {"boundaries.top.type=moving_wall", "boundaries.top.velocity_um_s=[1e6, 0]"});
  EXPECT_CONTAINS(m, "expected Mach number 0.173205 exceeds limits.max_mach = 0.1");
  EXPECT_CONTAINS(m, "boundaries.top.velocity_um_s = [1e+06, 0] µm/s");
  EXPECT_CONTAINS(m, "time.tau <= ");
  // No time-step advice when the τ it needs would break the τ margin.
  const std::string t = derive_error(channel, {"time.tau=0.51", "boundaries.top.type=moving_wall",
                                               "boundaries.top.velocity_um_s=[6e7, 0]"});
  EXPECT_CONTAINS(t, "lower it by a factor");
  EXPECT_EQ(t.find("time.tau <="), std::string::npos) << t;
  const std::string f = derive_error(channel, {"body_force.density_N_m3=[1e9, 0]"});
  EXPECT_CONTAINS(f, "is set by body_force.density_N_m3");
  EXPECT_NO_THROW(derive(channel, {"boundaries.top.type=moving_wall", "boundaries.top.velocity_um_s=[1e6, 0]",
                                   "limits.max_mach=0.2"}));
}

TEST(Units, TooCoarseChannel) {
  const std::string m = derive_error(channel, {"domain.size_um=[10, 3]"});
  EXPECT_CONTAINS(m, "resolution too coarse");
  EXPECT_CONTAINS(m, "bottom and top walls has 3 nodes across");
  EXPECT_CONTAINS(m, "limits.min_nodes_across_channel = 4");
  EXPECT_CONTAINS(m, "domain.spacing_um <= 0.75 µm");
  // The periodic direction may be as short as one node.
  EXPECT_NO_THROW(derive(channel, {"domain.size_um=[1, 10]"}));
}

TEST(Units, NonIntegerNodeCount) {
  const std::string m = derive_error(channel, {"domain.size_um=[10, 10.5]"});
  EXPECT_CONTAINS(m, "domain.size_um = [10, 10.5] µm is not a whole number of domain.spacing_um = 1 µm");
  EXPECT_CONTAINS(m, "nearest valid spacing is 0.5 µm");
  // Spacings that are not exact in binary still give whole node counts.
  const LatticeSetup s = derive(channel, {"domain.size_um=[0.3, 0.9]", "domain.spacing_um=0.1"});
  EXPECT_EQ(s.grid.nx, 3);
  EXPECT_EQ(s.grid.ny, 9);
}

TEST(Units, InconsistentBoundariesAndInitialState) {
  EXPECT_CONTAINS(derive_error(channel, {"boundaries.top.type=periodic"}),
                  "boundaries: bottom and top must both be periodic or both be walls");
  EXPECT_CONTAINS(derive_error(channel, {"boundaries.top.type=moving_wall", "boundaries.top.velocity_um_s=[0, 5]"}),
                  "can only move along x");
  EXPECT_CONTAINS(derive_error(channel, {"initial.type=taylor_green"}), "needs all four sides periodic");
  EXPECT_NO_THROW(derive(channel, {"initial.type=shear"}));
}

TEST(Units, TrtReport) {
  const Scene scene = parse_scene(channel, "u.toml", {"fluid.collision=trt"});
  const LatticeSetup s = derive_lattice(scene);
  EXPECT_EQ(s.collision.model, fluid::CollisionModel::trt);
  EXPECT_DOUBLE_EQ(s.collision.trt_magic, 3.0 / 16.0);
  EXPECT_CONTAINS(format_lattice_report(scene, s), "trt, Λ = 0.1875");
}

}  // namespace
}  // namespace erythro::scene
