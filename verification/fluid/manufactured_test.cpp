// Cases verification.manufactured (CI) and verification.manufactured_full (issue 3 item 3).
//
// Requirement: with the manufactured body force of mms/mms_forcing.hpp fed per node
// (Guo forcing), the steady state of the LBM converges to the manufactured steady
// Navier–Stokes solution at second order in the velocity (BGK and TRT).
// Reference: method of manufactured solutions (Roache 2002, J Fluids Eng 124:4;
// Salari & Knupp 2000, SAND2000-1444). Fields (doubly periodic, k = 2π/N, ρ0 = 1):
//   u = U[sin kx cos ky + ½ sin 2ky],  v = U[−cos kx sin ky + ½ cos 2kx],
//   p = U²[¼ cos 2kx + ½ sin kx sin 2ky],
//   F = ρ0 (u·∇)u + ∇p − ρ0 ν ∇²u  (derived by mms/derive_forcing.py with sympy, the
//   nonlinear term included; the header is generated and committed).
// Scaling: diffusive (τ = 0.8, U = 0.05·16/N). The LBM is weakly compressible: its
// steady state satisfies ∇·(ρu) = 0 with ρ = 1 + 3p, not ∇·u = 0, which moves u by
// O(Ma²) = O(h²) — the same order as the truncation error, so order 2 is still expected.
// Steady state: started from the exact fields (fluid/initial_state.hpp), stepped in
// chunks of one e-fold time t_e = 1/(νk²) of the slowest mode until the change over a
// chunk, δ, bounds the remaining transient (≈ δ/(e − 1) for an exponential decay) below
// 0.1% of the error being measured.
// Runs: verification/fluid/manufactured.toml (N × N, τ, collision; diagnostics every
// chunk, at most 40 chunks); the force field and the exact start are set on the fluid
// before the run; the case's probe (manufactured_probe.hpp) writes the velocity error and
// the transient ratio at every chunk and the scene's [[stop_when]] ends the run on it;
// the pressure error is taken from the final fields (lattice units, a FieldsRecorder).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/case_support.hpp"
#include "common/convergence.hpp"
#include "common/scene_case.hpp"
#include "fluid/initial_state.hpp"
#include "fluid_scenes.hpp"
#include "lattice/d2q9.hpp"
#include "manufactured_probe.hpp"
#include "mms/mms_forcing.hpp"
#include "simulation/fields_recorder.hpp"

using namespace erythro;

namespace {
constexpr double kTau = 0.8;
constexpr double kNu = (kTau - 0.5) / 3.0;
constexpr double kMagic = 3.0 / 16.0;
constexpr double kTransientFraction = 1e-3;  // remaining transient / error
constexpr int kMaxChunks = 40;

struct MmsRun {
  double error_u = 0, error_p = 0, transient_ratio = 0, wall_time_s = 0, max_mach = 0;
  long steps = 0;
  std::string scene_text;
};

MmsRun run_manufactured(fluid::CollisionModel model, int N, const std::string& case_name) {
  static const vv::SceneFile file("verification/fluid/manufactured.toml");
  const double k = 2.0 * std::numbers::pi / N;
  const double U = 0.05 * 16.0 / N;
  const Grid g{N, N};
  fluid::FlowField exact;
  exact.resize(g.size(), true);
  std::vector<double> p_exact(g.size()), fx(g.size()), fy(g.size());
  for (int j = 0; j < N; ++j) {
    for (int i = 0; i < N; ++i) {
      const auto n = g.index(i, j);
      const vv::mms::Fields f = vv::mms::evaluate(i + 0.5, j + 0.5, k, U, kNu);
      exact.rho[n] = 1.0 + d2q9::inv_cs2 * f.p;
      exact.ux[n] = f.ux;
      exact.uy[n] = f.uy;
      exact.dux_dx[n] = f.dux_dx;
      exact.dux_dy[n] = f.dux_dy;
      exact.duy_dx[n] = f.duy_dx;
      exact.duy_dy[n] = f.duy_dy;
      p_exact[n] = f.p;
      fx[n] = f.fx;
      fy[n] = f.fy;
    }
  }
  const long chunk = std::lround(1.0 / (kNu * k * k));
  std::vector<std::string> o = {vv::set_grid(N, N), vv::set_collision(model),
                                vv::set("run.steps", chunk * kMaxChunks),
                                vv::set("output.diagnostics_interval_steps", chunk),
                                vv::set("stop_when[0].below", kTransientFraction)};
  o.push_back(vv::set_tau(file, o, kTau));
  vv::CaseRunOptions options;
  options.configure = [&](sim::Simulation& simulation) {
    fluid::FluidLattice& lattice = *simulation.fluid();
    lattice.enable_force_field();  // steady: written once
    std::copy(fx.begin(), fx.end(), lattice.force_x().begin());
    std::copy(fy.begin(), fy.end(), lattice.force_y().begin());
    fluid::initialize_post_collision(lattice, exact, fx, fy);
    simulation.add_probe(std::make_unique<vv::ManufacturedSteadyProbe>(exact.ux, exact.uy));
  };
  sim::FieldsRecorder fields;
  options.observers.push_back(&fields);
  const std::string label = std::string(fluid::to_string(model)) + "_N" + std::to_string(N);
  const vv::CaseRun r = vv::run_case_scene(file.scene(o), case_name, label, options);
  if (!r.ok()) throw std::runtime_error(label + ": " + r.summary.diagnosis);
  MmsRun run;
  run.steps = r.summary.steps;
  run.error_u = r.file.series("mms_error_u").back();
  run.transient_ratio = r.file.series("mms_transient_over_error").back();
  run.wall_time_s = r.summary.wall_time_s;
  run.scene_text = r.file.scene_text();
  const fluid::Moments& m = fields.last().moments;
  std::vector<double> p_num(g.size());
  for (std::size_t n = 0; n < g.size(); ++n) {
    p_num[n] = d2q9::cs2 * (m.rho[n] - 1.0);
    run.max_mach = std::max(run.max_mach, std::hypot(m.ux[n], m.uy[n]) * std::sqrt(d2q9::inv_cs2));
  }
  run.error_p = vv::relative_l2(p_num, p_exact);
  return run;
}

void run_study(const std::string& case_name, const std::vector<int>& resolutions) {
  vv::Stopwatch total;
  io::ResultRecord record(case_name, "fluid");
  record.set_requirement(
      "Steady manufactured Navier-Stokes solution (two Fourier modes per velocity component, nonlinear forcing) in "
      "a doubly periodic box, per-node Guo forcing: the steady-state velocity converges at second order (observed "
      "order 2 +- 0.15, asymptotic range reached) for BGK and TRT (Lambda = 3/16); the pressure likewise.");
  record.set_reference(
      "Method of manufactured solutions (Roache 2002, J Fluids Eng 124:4): u = U[sin kx cos ky + sin 2ky / 2], "
      "v = U[-cos kx sin ky + cos 2kx / 2], p = U^2[cos 2kx / 4 + sin kx sin 2ky / 2], F = rho (u.grad)u + grad p - "
      "mu lap u, derived by verification/fluid/mms/derive_forcing.py (sympy).");
  record.set_parameter("tau", kTau);
  record.set_parameter("trt_magic", kMagic);
  std::string levels;
  for (int N : resolutions) levels += (levels.empty() ? "" : ", ") + std::to_string(N);
  record.set_parameter("resolutions", "N = " + levels + " (N x N, periodic)");
  record.set_parameter("scaling", std::string("diffusive: tau fixed, U = 0.05*16/N (lattice), k = 2 pi / N"));
  record.set_parameter("steady_state_rule",
                       std::string("chunks of t_e = 1/(nu k^2) steps until change/(e-1) <= 0.001 x velocity error"));

  // The generated header against a direct evaluation of (u.grad)u from its own
  // velocity and gradients (a check of the sympy output independent of its algebra).
  double worst_header = 0.0;
  for (double x : {0.3, 1.7, 4.1}) {
    for (double y : {0.2, 2.9, 5.3}) {
      const vv::mms::Fields f = vv::mms::evaluate(x, y, 0.7, 0.03, 0.1);
      worst_header = std::max({worst_header, std::abs(f.convection_x - (f.ux * f.dux_dx + f.uy * f.dux_dy)),
                               std::abs(f.convection_y - (f.ux * f.duy_dx + f.uy * f.duy_dy))});
    }
  }
  EXPECT_TRUE(record.add_metric({"forcing header consistency",
                                 "max |convection - (u du/dx + v du/dy)| of mms_forcing.hpp at 9 points (k = 0.7, "
                                 "U = 0.03)", "", worst_header, 1e-16, 0.0, io::Comparison::at_most,
                                 "the terms are O(U^2 k) = 6e-4: equal up to a few ulps"}))
      << worst_header;

  double worst_transient = 0.0;
  for (auto model : {fluid::CollisionModel::bgk, fluid::CollisionModel::trt}) {
    const std::string label = model == fluid::CollisionModel::bgk ? "BGK" : "TRT";
    io::ConvergenceSeries u_series{label + " velocity", "relative L2 velocity error (steady state)", {}, {}, {},
                                   2.0, 0.0, 0.15, false, ""};
    io::ConvergenceSeries p_series{label + " pressure", "relative L2 pressure error (steady state)", {}, {}, {},
                                   2.0, 0.0, 0.15, false, ""};
    io::SpeedErrorSeries speed{label, {}, {}, {}};
    for (int N : resolutions) {
      const MmsRun run = run_manufactured(model, N, case_name);
      record.add_run({{"model", std::string(fluid::to_string(model))}, {"N", double(N)}, {"steps", double(run.steps)},
                      {"max_mach", run.max_mach}, {"error_u", run.error_u}, {"error_p", run.error_p},
                      {"transient_over_error", run.transient_ratio}, {"wall_time_s", run.wall_time_s}},
                     run.scene_text);
      u_series.h.push_back(1.0 / N);
      u_series.error.push_back(run.error_u);
      p_series.h.push_back(1.0 / N);
      p_series.error.push_back(run.error_p);
      speed.wall_time_s.push_back(run.wall_time_s);
      speed.error.push_back(run.error_u);
      speed.label.push_back("N=" + std::to_string(N));
      worst_transient = std::max(worst_transient, run.transient_ratio);
    }
    vv::fit_order(u_series);
    vv::fit_order(p_series);
    record.add_convergence(u_series);
    record.add_convergence(p_series);
    record.add_speed_error(speed);
    EXPECT_TRUE(record.add_metric(vv::order_metric(
        u_series, "truncation error and the O(Ma^2) weak-compressibility shift of the steady state are both O(h^2) "
                  "in diffusive scaling; 0.15 covers the O(h^4) remainder at the coarsest levels")))
        << u_series.name << " order " << u_series.observed_order;
    EXPECT_TRUE(record.add_metric(vv::asymptotic_metric(u_series))) << u_series.name;
    EXPECT_TRUE(record.add_metric(vv::order_metric(
        p_series, "steady state: no initial-layer sound wave survives (it decays like the transient), so the "
                  "pressure carries only O(h^2) truncation and compressibility errors; 0.15 as for the velocity")))
        << p_series.name << " order " << p_series.observed_order;
    EXPECT_TRUE(record.add_metric(vv::asymptotic_metric(p_series))) << p_series.name;
  }
  EXPECT_TRUE(record.add_metric({"steady-state residual", "max over runs of (remaining transient) / (velocity error)",
                                 "", worst_transient, kTransientFraction, 0.0, io::Comparison::at_most,
                                 "the iteration error must be negligible (0.1%) against the discretisation error"}))
      << worst_transient;
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
}  // namespace

TEST(Manufactured, SecondOrderSteadyState) { run_study("verification.manufactured", {16, 24, 32, 48, 64}); }

// Full tier only (about 1 min): the same study extended to N = 96 and 128.
TEST(ManufacturedFull, SecondOrderSteadyStateExtended) {
  run_study("verification.manufactured_full", {16, 24, 32, 48, 64, 96, 128});
}
