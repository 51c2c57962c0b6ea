// Case verification.transport_krogh_cylinder (issue 20 item 5).
//
// Requirement: the Krogh–Erlang tissue cylinder — O2 diffusing from a capillary wall held at
// PO2 = 70 Torr (r_c = 3 µm) into tissue consuming it at the zero-order rate M = 50 µM/s out to a
// zero-flux edge (R_t = 60 µm) — on the axisymmetric lattice with an inner radius (an annulus,
// docs/model.md §7b) converges at second order (2 ± 0.15) to the exact profile; the steady O2
// entering through the capillary wall equals the consumption M π (R_t² − r_c²) per unit length to
// the steady tolerance; the r-weighted mass balance closes to round-off in every step.
// Reference: Krogh (1919), the exact solution of D (1/r)(r C')' = M with C(r_c) = C_c and
// C'(R_t) = 0:
//   C(r) = C_c + M (r² − r_c²)/(4D) − M R_t² ln(r/r_c)/(2D),
// exact while C > 0 everywhere (its minimum, at R_t, is 10.7 µM here). Parameters:
// docs/parameters.md §4 (D_O2, α, tissue Q_max as the P ≫ K_m limit, the 70 Torr lumen PO2).
// Scaling: h = 1 µm / m, m = 1, 2, 4; τ = 5 for D_O2 (the steady TRT(¼) state and Ĉ are the
// finite-volume scheme whatever τ, eq 7.9); started from the exact profile.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/case_support.hpp"
#include "common/convergence.hpp"
#include "simulation/simulation.hpp"
#include "transport/transport_units.hpp"
#include "transport_run.hpp"

using namespace erythro;

namespace {
constexpr double kD = 2800.0, kM = 50.0, kCc = 1.3 * 70.0, kRc = 3.0, kRt = 60.0, kTau = 5.0;

double krogh(double r) {
  return kCc + kM * (r * r - kRc * kRc) / (4.0 * kD) - kM * kRt * kRt * std::log(r / kRc) / (2.0 * kD);
}

struct KroghRun {
  double error_l2 = 0.0, error_linf = 0.0, wall_flux_error = 0.0;
  vv::TransportRun run;
};

KroghRun run_krogh(int m) {
  const double h = 1.0 / m;
  const int rows = static_cast<int>(std::lround((kRt - kRc) / h));
  const transport::TransportUnits units{h, transport::dt_for_tau(h, kD, kTau)};
  std::vector<double> ref(static_cast<std::size_t>(rows));
  for (int y = 0; y < rows; ++y) ref[std::size_t(y)] = krogh(kRc + (y + 0.5) * h);
  const long interval = std::max(1L, std::lround(0.1 / units.dt_s));  // 0.1 s; slowest mode ~0.5 s
  auto set_up = vv::steady_overrides("O2", interval, 1e-10 * kCc, 400 * interval);
  set_up.push_back(vv::set("domain.spacing_um", h));
  set_up.push_back(vv::set("domain.size_um", h, rows * h));
  set_up.push_back(vv::set("transport.time_step_s", units.dt_s));
  const auto configure = [&](sim::Simulation& s) { s.transport()->initialize(0, ref); };
  auto run = vv::run_transport(vv::case_scene("verification/transport/krogh_cylinder.toml", set_up),
                               "verification.transport_krogh_cylinder", "m" + std::to_string(m), "O2", configure);
  KroghRun out;
  double num = 0.0, den = 0.0, cmax = 0.0;
  for (int y = 0; y < rows; ++y) {
    const double r = kRc + (y + 0.5) * h, e = run.C[std::size_t(y)] - ref[std::size_t(y)];
    num += r * e * e;
    den += r * ref[std::size_t(y)] * ref[std::size_t(y)];
    out.error_linf = std::max(out.error_linf, std::fabs(e));
    cmax = std::max(cmax, ref[std::size_t(y)]);
  }
  out.error_l2 = std::sqrt(num / den);
  out.error_linf /= cmax;
  // Steady balance: what entered through the wall over what the tissue consumed (probe series,
  // |inflow + net source| / |net source| of the last step).
  out.wall_flux_error = run.series.series("O2_steady_balance").back();
  out.run = std::move(run);
  return out;
}
}  // namespace

TEST(TransportKroghCylinder, ZeroOrderConsumptionAroundACapillary) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.transport_krogh_cylinder", "transport");
  record.set_requirement(
      "Krogh-Erlang cylinder (capillary wall r_c = 3 um at 70 Torr, zero-order consumption 50 uM/s, zero flux at "
      "R_t = 60 um) on the axisymmetric lattice with an inner radius converges at second order (2 +- 0.15, r-weighted "
      "L2 and max norm) to the exact profile; the steady wall inflow balances the consumption to <= 1e-6 relative; "
      "r-weighted mass balance <= 1e-13 in every step.");
  record.set_reference(
      "Krogh 1919: C(r) = C_c + M (r^2 - r_c^2)/(4D) - M R_t^2 ln(r/r_c)/(2D), exact while C > 0 (minimum 10.7 uM "
      "at R_t); parameters docs/parameters.md section 4.");
  record.set_parameter("refinements", std::string("h = 1 um / m, m = 1, 2, 4 (57 m rows)"));
  record.set_parameter("tau", kTau);
  record.set_parameter("minimum_exact_uM", krogh(kRt));
  io::ConvergenceSeries l2{"D2Q5 TRT", "r-weighted relative L2 error of C", {}, {}, {}, 2.0, 0.0, 0.15, false, ""};
  io::ConvergenceSeries linf{"D2Q5 TRT max", "relative max error of C", {}, {}, {}, 2.0, 0.0, 0.15, false, ""};
  io::SpeedErrorSeries speed{"D2Q5 TRT", {}, {}, {}};
  double worst_balance = 0.0, worst_steady = 0.0;
  for (int m : {1, 2, 4}) {
    const KroghRun r = run_krogh(m);
    EXPECT_TRUE(r.run.converged) << m;
    worst_balance = std::max(worst_balance, r.run.worst_mass_residual);
    worst_steady = std::max(worst_steady, r.wall_flux_error);
    record.add_run({{"m", double(m)}, {"steps", double(r.run.steps)}, {"error_l2", r.error_l2},
                    {"error_linf", r.error_linf}, {"steady_balance", r.wall_flux_error},
                    {"mass_residual", r.run.worst_mass_residual}, {"wall_time_s", r.run.wall_time_s}},
                   r.run.scene_text);
    vv::add_convergence_point(l2, speed, 1.0 / m, r.error_l2, r.run.wall_time_s, "m=" + std::to_string(m));
    linf.h.push_back(1.0 / m);
    linf.error.push_back(r.error_linf);
  }
  for (auto* s : {&l2, &linf}) {
    vv::fit_order(*s);
    record.add_convergence(*s);
    EXPECT_TRUE(record.add_metric(vv::order_metric(
        *s, "halfway anti-bounce-back at the capillary wall and bounce-back at the edge are the finite-volume faces "
            "(eq 7.10), the steady TRT(1/4) state is the finite-volume scheme (eq 7.9): second order; 0.15 covers "
            "the coarsest level")))
        << s->name << " " << s->observed_order;
    EXPECT_TRUE(record.add_metric(vv::asymptotic_metric(*s))) << s->name;
  }
  record.add_speed_error(speed);
  EXPECT_TRUE(record.add_metric({"steady_wall_balance",
                                 "worst |wall inflow - consumption| / consumption of the last step, any level", "",
                                 worst_steady, 1e-6, 0.0, io::Comparison::at_most,
                                 "at a steady state what enters equals what is consumed; the runs stop at a change "
                                 "<= 1e-10 C_c per 0.1 s, which leaves ~1e-8 of imbalance"}))
      << worst_steady;
  EXPECT_TRUE(record.add_metric(vv::mass_balance_metric(worst_balance))) << worst_balance;
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
