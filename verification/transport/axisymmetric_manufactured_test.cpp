// Case verification.transport_axisymmetric_manufactured (issue 20 items 1 and 3).
//
// Requirement: the axisymmetric transport lattice (docs/model.md §7b: φ = r C with the drift
// D/r; D2Q5, the only stencil it takes) with a per-node diffusivity, an axial velocity varying
// across the radius, a source, the axis and a fixed-concentration wall converges at second
// order (observed order 2 ± 0.15) to a manufactured steady solution, in the whole cylinder AND
// on the row next to the axis (r = h/2), with the TRT (Λ = ¼) and the BGK collision; the
// r-weighted mass balance closes to round-off in every step.
// Reference: manufactured solution and source derived symbolically by
// mms/derive_axisymmetric_source.py (generated mms/axisymmetric_mms.hpp); Roache, "Code
// Verification by the Method of Manufactured Solutions" (2002).
// Scaling: diffusive — D0 = 0.25 fixed in lattice units (τ 0.875..1.625), Péclet U R / D0 = 10
// fixed, so U_lattice ∝ 1/N and Δt ∝ h²; the drift D/r at the axis row is 2D (lattice units)
// at every level.
// Measured when the scope was set (2026-12-03, N = 16/32/64): D2Q9 converges at order 2.0 in
// the cylinder but 1.6 on the axis row (BGK and TRT), hence D2Q5 only; with the radial velocity
// of a stream function the central φ flux of r C u_r (∝ r² near the axis) is inconsistent at the
// axis face and the order there falls to 1.65 (the cylindrical finite-volume scheme with the
// same central flux, solved directly, does the same), hence the axial velocity only.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/case_support.hpp"
#include "common/convergence.hpp"
#include "mms/axisymmetric_mms.hpp"
#include "simulation/simulation.hpp"
#include "transport_run.hpp"

using namespace erythro;
using namespace erythro::transport;

namespace {
constexpr double kC0 = 1.0, kA = 0.5, kD0 = 0.25, kPeclet = 10.0;

struct AxisymmetricRun {
  double error_l2 = 0.0;    // r-weighted relative L2 of C − C0 over the cylinder
  double error_linf = 0.0;  // relative max over the cylinder
  double axis_linf = 0.0;   // relative max over the row next to the axis (r = h/2)
  vv::TransportRun run;
};

// Steady run at N×N (axisymmetric_manufactured.toml): z = x + ½, r = y + ½ (lattice units), the
// manufactured data set through configure (u_r = 0), the start C0 (equilibrium with the source).
// The collision of a run: TRT (Λ = ¼) or BGK, on D2Q5.
std::string collision_name(bool trt) { return trt ? "D2Q5 TRT" : "D2Q5 BGK"; }

AxisymmetricRun run_case(const std::string& case_name, bool trt, int N) {
  const double L = N, R = N, U = kPeclet * kD0 / R;
  const Grid g{N, N};
  std::vector<double> uz(g.size()), ur(g.size(), 0.0), D(g.size()), q(g.size()), exact(g.size());
  for (int y = 0; y < N; ++y)
    for (int x = 0; x < N; ++x) {
      const std::size_t n = g.index(x, y);
      const auto f = vv::axisymmetric_mms::evaluate(x + 0.5, y + 0.5, L, R, kC0, kA, kD0, U);
      uz[n] = f.uz;
      D[n] = f.D;
      q[n] = f.q;
      exact[n] = f.C - kC0;
    }
  const auto configure = [&](sim::Simulation& s) {
    sim::TransportPhysics& t = *s.transport();
    t.lattice(0).set_velocity(uz, ur);
    std::copy(D.begin(), D.end(), t.lattice(0).diffusivity().begin());
    std::copy(q.begin(), q.end(), t.base_source(0).begin());
    t.initialize(0, std::vector<double>(g.size(), kC0));
  };
  const long interval = long(N) * N / 2;
  auto set_up = vv::steady_overrides("C", interval, 1e-12, 400L * N * N);
  set_up.push_back(vv::set("domain.size_um", L, R));
  set_up.push_back(vv::set("transport.collision", std::string(trt ? "\"trt\"" : "\"bgk\"")));
  const std::string label = std::string(trt ? "trt" : "bgk") + "_N" + std::to_string(N);
  auto run = vv::run_transport(vv::case_scene("verification/transport/axisymmetric_manufactured.toml", set_up),
                               case_name, label, "C", configure);
  // Norms weighted by the volume of each node's ring (∝ r); the axis row's own maximum.
  double num = 0.0, den = 0.0, worst = 0.0, scale = 0.0, axis = 0.0;
  for (int y = 0; y < N; ++y)
    for (int x = 0; x < N; ++x) {
      const std::size_t n = g.index(x, y);
      const double r = y + 0.5, e = run.C[n] - kC0 - exact[n];
      num += r * e * e;
      den += r * exact[n] * exact[n];
      worst = std::max(worst, std::fabs(e));
      scale = std::max(scale, std::fabs(exact[n]));
      if (y == 0) axis = std::max(axis, std::fabs(e));
    }
  return {std::sqrt(num / den), worst / scale, axis / scale, std::move(run)};
}

void axisymmetric_case(const std::string& case_name, const std::vector<int>& resolutions) {
  vv::Stopwatch total;
  io::ResultRecord record(case_name, "transport");
  record.set_requirement(
      "Steady axisymmetric advection-diffusion (phi = r C lattice with the drift D/r, docs/model.md eq 7.7) with "
      "per-node D(z,r) (0.5..1.5 D0), an axial velocity u_z(r), a manufactured source, the axis (zero flux) and a "
      "fixed-concentration wall converges at second order (observed order 2 +- 0.15, D2Q5 with TRT and with BGK), in "
      "the r-weighted L2 norm over the cylinder and in the max norm on the row next to the axis; the r-weighted mass "
      "balance closes to <= 1e-13 relative in every step.");
  record.set_reference(
      "Manufactured solution C = C0 + A cos(pi r^2/(2R^2))[1 + sin(2 pi z/L)/2], D = D0[1 + (r^2/R^2) cos(2 pi z/L)/2], "
      "u_z = U[1/2 + (1 - r^2/R^2)] (plug plus Poiseuille), u_r = 0; q = div(Cu) - "
      "div(D grad C) in cylindrical coordinates derived by sympy (verification/transport/mms/"
      "derive_axisymmetric_source.py); method: Roache 2002.");
  std::string levels;
  for (int N : resolutions) levels += (levels.empty() ? "" : ", ") + std::to_string(N);
  record.set_parameter("resolutions", "N = " + levels + " (N x N: L = R = N; periodic in z, axis at y = 0, wall at y = N)");
  record.set_parameter("scaling", std::string("diffusive: D0 = 0.25 (lattice), Peclet U R/D0 = 10, U = 2.5/N"));
  record.set_parameter("C0", kC0);
  record.set_parameter("A", kA);
  record.set_parameter("steady_tolerance", std::string("max |dC| over N^2/2 steps <= 1e-12"));

  double worst_balance = 0.0;
  for (const bool trt : {true, false}) {
    const std::string name = collision_name(trt);
    io::ConvergenceSeries series{}, axis_series{};
    series.name = name;
    series.norm = "r-weighted relative L2 error of C - C0";
    axis_series.name = name + " axis row";
    axis_series.norm = "relative max error on the row next to the axis";
    for (io::ConvergenceSeries* s : {&series, &axis_series}) {
      s->formal_order = 2.0;
      s->order_tolerance = 0.15;
    }
    io::SpeedErrorSeries speed{name, {}, {}, {}}, axis_speed{name + " axis row", {}, {}, {}};
    for (int N : resolutions) {
      const AxisymmetricRun r = run_case(case_name, trt, N);
      EXPECT_TRUE(r.run.converged) << name << " N=" << N;
      worst_balance = std::max(worst_balance, r.run.worst_mass_residual);
      record.add_run({{"lattice", name}, {"N", double(N)}, {"steps", double(r.run.steps)},
                      {"error_l2", r.error_l2}, {"error_linf", r.error_linf}, {"axis_row_error_linf", r.axis_linf},
                      {"mass_residual", r.run.worst_mass_residual}, {"wall_time_s", r.run.wall_time_s}},
                     r.run.scene_text);
      vv::add_convergence_point(series, speed, 1.0 / N, r.error_l2, r.run.wall_time_s, "N=" + std::to_string(N));
      vv::add_convergence_point(axis_series, axis_speed, 1.0 / N, r.axis_linf, r.run.wall_time_s,
                                "N=" + std::to_string(N));
    }
    for (io::ConvergenceSeries* s : {&series, &axis_series}) {
      vv::fit_order(*s);
      record.add_convergence(*s);
      EXPECT_TRUE(record.add_metric(vv::order_metric(
          *s, "the steady phi = r C lattice is the conservative cylindrical finite-volume scheme up to O(h^2) terms "
              "(docs/model.md eq 7.9; at the axis row the face r = 0 carries nothing and r = h/2, no 1/r "
              "singularity), so second order in the cylinder and at the axis; 0.15 covers the pre-asymptotic drift "
              "of the coarsest level (N = 16)")))
          << s->name << " order " << s->observed_order;
      EXPECT_TRUE(record.add_metric(vv::asymptotic_metric(*s))) << s->name;
    }
    record.add_speed_error(speed);
  }
  EXPECT_TRUE(record.add_metric(vv::mass_balance_metric(worst_balance))) << worst_balance;
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
}  // namespace

// CI tier: N = 16, 32, 64.
TEST(TransportAxisymmetricManufactured, SecondOrderInTheCylinderAndAtTheAxis) {
  axisymmetric_case("verification.transport_axisymmetric_manufactured", {16, 32, 64});
}
