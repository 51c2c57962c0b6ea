// Case verification.transport_zero_order_slab (issue 7 item 7).
//
// Requirement: O2 consumed at a uniform zero-order rate Q in a tissue slab fed from
// one side (fixed concentration, anti-bounce-back) and closed on the other
// (zero flux, bounce-back) converges at second order (2 ± 0.1) to the exact quadratic
// profile; the mass balance closes to round-off in every step, and at steady state
// the boundary inflow equals the consumption.
// Reference: D C'' = Q, C(0) = C_b, C'(H) = 0 ⇒ C(y) = C_b − (Q/D)(H y − y²/2),
// valid while C(H) = C_b − Q H²/(2D) > 0 (Krogh-type slab; docs/parameters.md: D_O2 =
// 2800 µm²/s, tissue Q_max = 50 µM/s in its zero-order limit P ≫ K_m, α = 1.3 µM/Torr).
// Variant "flux-fed" (D2Q5): bottom fixed_flux J = Q H/2, top C = C_b; exact
// C = C_b + (Q/(2D))(y² − H²) − (J/D)(y − H) (checks the fixed-flux side on a curved profile).
// Set-up: C_b = 70 Torr × α = 91 µM, H = 90 µm so that C(H) = 0.2 C_b; physical
// units converted by TransportUnits with τ = 1 at every resolution (Δt ∝ h²).
#include <gtest/gtest.h>

#include <cmath>

#include "common/case_support.hpp"
#include "common/convergence.hpp"
#include "transport/transport_units.hpp"
#include "simulation/simulation.hpp"
#include "transport_run.hpp"

using namespace erythro;
using namespace erythro::transport;

namespace {
constexpr int kResolutions[] = {16, 32, 64, 128};
constexpr double kD = 2800.0;       // µm²/s
constexpr double kQ = 50.0;         // µM/s
constexpr double kCb = 70.0 * 1.3;  // µM
constexpr double kTau = 1.0;
// H such that C(H) = 0.2 C_b: Q H²/(2D) = 0.8 C_b.
const double kH = std::sqrt(1.6 * kCb * kD / kQ);

double exact(double y) { return kCb - (kQ / kD) * (kH * y - 0.5 * y * y); }

// Flux-fed variant: half the consumption enters through the bottom as a fixed inward
// flux J = Q H/2, C = C_b on the top: D C'' = Q, −D C'(0) = J, C(H) = C_b ⇒
// C = C_b + (Q/(2D))(y² − H²) − (J/D)(y − H); minimum 0.8 C_b at y = H/2.
constexpr double kFluxFraction = 0.5;
double exact_flux_fed(double y) {
  const double J = kFluxFraction * kQ * kH;
  return kCb + (kQ / (2.0 * kD)) * (y * y - kH * kH) - (J / kD) * (y - kH);
}

struct SlabRun {
  double error_l2, error_linf, inflow_vs_consumption;
  vv::TransportRun run;
  double dt;
};

SlabRun run_slab(Stencil stencil, int N, bool flux_fed = false) {
  const double h = kH / N;
  const TransportUnits units{h, dt_for_tau(h, kD, kTau)};
  auto profile = [&](double y) { return flux_fed ? exact_flux_fed(y) : exact(y); };
  // Slowest mode (quarter wave): e-fold N² (2/π)²/D_lat steps; check every N² steps.
  auto set_up = vv::steady_overrides("O2", long(N) * N, 1e-11 * kCb, 2000L * N * N);
  for (const std::string& o : {vv::set("domain.spacing_um", h), vv::set("domain.size_um", h, N * h),
                               vv::set("transport.time_step_s", units.dt_s),
                               vv::set("transport.stencil", std::string(stencil == Stencil::d2q5 ? "\"d2q5\"" : "\"d2q9\""))})
    set_up.push_back(o);
  if (flux_fed) {  // half the consumption enters through the bottom, C_b held on the top
    set_up.push_back(vv::set("species[0].bottom", std::string("\"fixed_flux\"")));
    set_up.push_back(vv::set("species[0].bottom_value", kFluxFraction * kQ * kH));  // µM µm/s
    set_up.push_back(vv::set("species[0].top", std::string("\"fixed_concentration\"")));
    set_up.push_back(vv::set("species[0].top_value", kCb));
  }
  // Start at the exact profile: the steady state is unique, so only the discrete error (O(h²))
  // has to settle, which halves the steps.
  std::vector<double> start(static_cast<std::size_t>(N));
  for (int y = 0; y < N; ++y) start[std::size_t(y)] = profile((y + 0.5) * h);
  const auto configure = [&](sim::Simulation& s) { s.transport()->initialize(0, start); };
  const std::string label = std::string(stencil == Stencil::d2q5 ? "d2q5" : "d2q9") + "_N" + std::to_string(N) +
                            (flux_fed ? "_flux" : "");
  auto run = vv::run_transport(vv::case_scene("verification/transport/zero_order_slab.toml", set_up),
                               "verification.transport_zero_order_slab", label, "O2", configure);
  std::vector<double> ref(static_cast<std::size_t>(N));
  for (int y = 0; y < N; ++y) ref[std::size_t(y)] = profile((y + 0.5) * h);
  // |inflow − consumption| / consumption of the last step (the probe's O2_steady_balance)
  const double balance = run.series.series("O2_steady_balance").back();
  const std::vector<double> C = run.C;
  return {vv::relative_l2(C, ref), vv::relative_linf(C, ref), balance, std::move(run), units.dt_s};
}
}  // namespace

TEST(TransportZeroOrderSlab, QuadraticProfileAndMassBalance) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.transport_zero_order_slab", "transport");
  record.set_requirement(
      "Zero-order O2 consumption (50 uM/s) in a 90 um tissue slab fed at 91 uM on one side and closed on the other "
      "converges at second order (2 +- 0.1, D2Q5 and D2Q9) to the exact quadratic profile, and so does the "
      "variant fed by a fixed inward flux (half the consumption) against a fixed concentration; the mass balance "
      "closes to <= 1e-13 relative in every step and at steady state inflow = consumption to 1e-9.");
  record.set_reference(
      "C(y) = C_b - (Q/D)(H y - y^2/2) (exact solution of D C'' = Q, C(0) = C_b, C'(H) = 0, valid while C > 0); "
      "docs/parameters.md: D_O2 2800 um^2/s, tissue Q_max 50 uM/s, alpha 1.3 uM/Torr, 70 Torr.");
  record.set_parameter("resolutions", std::string("N = 16, 32, 64, 128 nodes across H"));
  record.set_parameter("H_um", kH);
  record.set_parameter("C_b_uM", kCb);
  record.set_parameter("tau", kTau);
  record.set_parameter("C_min_over_C_b", exact(kH) / kCb);
  double worst_balance = 0.0, worst_inflow = 0.0;
  struct Variant {
    Stencil stencil;
    bool flux_fed;
    std::string name;
  };
  for (const Variant& v : {Variant{Stencil::d2q5, false, "D2Q5"}, Variant{Stencil::d2q9, false, "D2Q9"},
                           Variant{Stencil::d2q5, true, "D2Q5 flux-fed"}}) {
    const Stencil stencil = v.stencil;
    const std::string& name = v.name;
    io::ConvergenceSeries series{name, "relative L2 error of C", {}, {}, {}, 2.0, 0.0, 0.1, false, ""};
    io::SpeedErrorSeries speed{name, {}, {}, {}};
    for (int N : kResolutions) {
      const SlabRun r = run_slab(stencil, N, v.flux_fed);
      EXPECT_TRUE(r.run.converged) << name << " N=" << N;
      worst_balance = std::max(worst_balance, r.run.worst_mass_residual);
      worst_inflow = std::max(worst_inflow, r.inflow_vs_consumption);
      record.add_run({{"stencil", name}, {"N", double(N)}, {"dt_s", r.dt}, {"steps", double(r.run.steps)},
                      {"error_l2", r.error_l2}, {"error_linf", r.error_linf},
                      {"inflow_minus_consumption", r.inflow_vs_consumption},
                      {"mass_residual", r.run.worst_mass_residual}, {"wall_time_s", r.run.wall_time_s}},
                     r.run.scene_text);
      vv::add_convergence_point(series, speed, 1.0 / N, r.error_l2, r.run.wall_time_s, "N=" + std::to_string(N));
    }
    vv::fit_order(series);
    record.add_convergence(series);
    record.add_speed_error(speed);
    EXPECT_TRUE(record.add_metric(vv::order_metric(
        series, "the halfway anti-bounce-back and bounce-back walls have a tau-dependent O(h^2) position error "
                "for a curved profile (as BGK bounce-back for Poiseuille flow); the bulk is exact for a quadratic; "
                "0.1 covers round-off and the steady-state residual")))
        << name << " order " << series.observed_order;
    EXPECT_TRUE(record.add_metric(vv::asymptotic_metric(series))) << name;
  }
  EXPECT_TRUE(record.add_metric({"steady_inflow_balance",
                                 "largest |boundary inflow - consumption| / consumption in the last step (steady)", "",
                                 worst_inflow, 1e-9, 0.0, io::Comparison::at_most,
                                 "at steady state storage is constant; the steady-state tolerance 1e-11 C_b per N^2 "
                                 "steps bounds the remaining storage change far below 1e-9"}))
      << worst_inflow;
  EXPECT_TRUE(record.add_metric(vv::mass_balance_metric(worst_balance))) << worst_balance;
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
