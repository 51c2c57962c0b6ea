// Cases verification.transport_arteriole_no_o2 (CI) and _full (issue 20 items 2 and 6).
//
// Requirement: the continuum RBC-core arteriole ([no_o2], docs/model.md §7c) — the core scavenging
// NO at the R4 rate and holding O2 near 70 Torr, the cell-free layer, the endothelium producing NO
// by R1(P) and using O2 1 : 1, the smooth muscle and the tissue consuming NO (R2) and O2 by the
// NO-inhibited Michaelis–Menten law (R5) — reaches a coupled nonlinear steady state whose NO and
// PO2 at the endothelium's and the smooth muscle's midpoints and 10 µm into the tissue agree with
// an independent reference within 0.5 %, as a planar section and as a body of revolution, for
// cell-free layers of 2, 3 and 5 µm (CI: 3 µm); the error falls with h (full, 3 µm); the mass balance
// closes to round-off in every step.
// Reference: reference_data/arteriole_no_o2/reference_arteriole.py (PROVENANCE.md there): 1D
// finite volumes, Newton on the steady nonlinear system, four grids, Richardson-extrapolated;
// its own error estimate ≤ 4e-5 relative.
// Set-up: arteriole_no_o2.toml, h = 0.5 µm (CI and full) and 0.25 µm (full, 3 µm), τ = 5 for NO,
// D2Q5 TRT (Λ = ¼), Ĉ readout; from NO = 0 and PO2 = 70 Torr to the steady state (O2 changing
// by < 1e-9 of its scale over 0.25 s).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/case_support.hpp"
#include "simulation/simulation.hpp"
#include "transport/transport_units.hpp"
#include "transport_run.hpp"

using namespace erythro;

namespace {
constexpr double kAlpha = 1.3, kLumen = 25.0;

// reference_arteriole.csv: value by (geometry, cfl, point, quantity).
std::map<std::string, double> read_reference() {
  const char* dir = std::getenv("ERYTHRO_SOURCE_DIR");
  std::ifstream in(std::string(dir ? dir : ".") + "/reference_data/arteriole_no_o2/reference_arteriole.csv");
  std::map<std::string, double> out;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::vector<std::string> f;
    for (std::string cell; std::getline(row, cell, ',');) f.push_back(cell);
    if (f.size() >= 6) out[f[0] + "|" + f[1] + "|" + f[2] + "|" + f[4]] = std::stod(f[5]);
  }
  return out;
}

std::string key(const std::string& geometry, double cfl, const std::string& point, const std::string& quantity) {
  char b[16];
  std::snprintf(b, sizeof b, "%g", cfl);
  return geometry + "|" + b + "|" + point + "|" + quantity;
}

const std::vector<std::pair<std::string, double>> kPoints = {
    {"EC", kLumen + 1.25}, {"SM", kLumen + 2.5 + 5.0}, {"tissue", kLumen + 12.5 + 10.0}};

struct CoupledRun {
  std::map<std::string, double> value;  // "<point>_<quantity>" → lattice value
  double worst_error = 0.0;             // max relative deviation from the reference
  std::map<std::string, double> point_error;  // "<point>_error": max relative deviation of NO, PO2 there
  double no_change = 0.0;               // NO's last change over 0.25 s, relative to its largest value
  vv::TransportRun run;
};

double interpolate(const std::vector<double>& f, double y, double h) {
  const double s = y / h - 0.5;
  const auto i = static_cast<std::size_t>(std::floor(s));
  const double t = s - std::floor(s);
  return (1.0 - t) * f[i] + t * f[i + 1];
}

CoupledRun run_coupled(const std::string& case_name, bool axisymmetric, double cfl, double h,
                       const std::map<std::string, double>& reference) {
  const int rows = static_cast<int>(std::lround(137.5 / h));
  const double dt = transport::dt_for_tau(h, 3300.0, 5.0);
  const long interval = std::lround(0.25 / dt);
  std::vector<std::string> set_up = {
      vv::set("domain.geometry", std::string(axisymmetric ? "\"axisymmetric\"" : "\"planar\"")),
      vv::set("domain.spacing_um", h), vv::set("domain.size_um", h, rows * h), vv::set("transport.time_step_s", dt),
      vv::set("monitor.interval_steps", interval), vv::set("output.diagnostics_interval_steps", interval),
      vv::set("no_o2.layers[0].y_um", 0.0, kLumen - cfl), vv::set("no_o2.layers[1].y_um", kLumen - cfl, kLumen)};
  char label[64];
  std::snprintf(label, sizeof label, "%s_cfl%g_h%g", axisymmetric ? "axisymmetric" : "planar", cfl, h);
  CoupledRun out;
  out.run = vv::run_transport(vv::case_scene("verification/transport/arteriole_no_o2.toml", set_up), case_name, label,
                              "NO", {});
  const std::vector<double> NO = out.run.C;
  const std::vector<double>& O2 = out.run.series.transport_field("O2");
  const std::string g = axisymmetric ? "axisymmetric" : "planar";
  for (const auto& [point, y] : kPoints) {
    const double no = interpolate(NO, y, h), po2 = interpolate(O2, y, h) / kAlpha;
    out.value[point + "_NO_uM"] = no;
    out.value[point + "_PO2_torr"] = po2;
    for (const auto& [q, v] : {std::pair{std::string("NO_uM"), no}, std::pair{std::string("PO2_torr"), po2}}) {
      const double ref = reference.at(key(g, cfl, point, q)), e = std::fabs(v - ref) / std::fabs(ref);
      out.worst_error = std::max(out.worst_error, e);
      out.point_error[point + "_error"] = std::max(out.point_error[point + "_error"], e);
    }
  }
  out.no_change = out.run.series.series("NO_change_uM").back() / *std::max_element(NO.begin(), NO.end());
  return out;
}

// Every width at h = 0.5 µm; the `refined` width also at 0.25 µm (the error must fall; with the wall
// times: speed against error, issue 20 item 8). 0.5 µm is the coarsest spacing that divides every band
// edge (22 and 2.5 µm), which [no_o2] requires; the next finer, 1/6 µm, costs ≈ 1 min per run.
void coupled_case(const std::string& case_name, const std::vector<double>& widths, std::optional<double> refined) {
  vv::Stopwatch total;
  io::ResultRecord record(case_name, "transport");
  record.set_requirement(
      "The continuum RBC-core arteriole ([no_o2]: core R4 sink and O2 held near 70 Torr, cell-free layer, EC with "
      "R1(P) and 1:1 O2 use, SM and tissue with R2 and the NO-inhibited R5) reaches a coupled steady state whose NO "
      "and PO2 at the EC and SM midpoints and 10 um into the tissue agree with the independent reference within 0.5 % "
      "(planar and axisymmetric; every run), the error falling from h = 0.5 to 0.25 um where both run; NO steady to 1e-7 of "
      "its scale over 0.25 s; mass balance <= 1e-13 in every step.");
  record.set_reference(
      "reference_data/arteriole_no_o2/reference_arteriole.py: 1D finite volumes, damped Newton on the steady "
      "nonlinear system, h = 0.5 .. 0.0625 um, Richardson-extrapolated (own error estimate <= 4e-5 relative; "
      "PROVENANCE.md); parameters docs/parameters.md section 4.");
  std::string ws;
  for (double w : widths) ws += (ws.empty() ? "" : ", ") + std::to_string(w).substr(0, 3);
  record.set_parameter("cell_free_layers_um", ws);
  record.set_parameter("spacings_um", std::string(refined ? "0.5 (every width), 0.25 (the " +
                                                                std::to_string(*refined).substr(0, 3) + " um layer)"
                                                          : "0.5"));
  record.set_parameter("collision", std::string("D2Q5 TRT, magic parameter 1/4, tau 5 (NO); readout source_corrected"));
  const auto reference = read_reference();
  ASSERT_EQ(reference.size(), 36u) << "reference_arteriole.csv not found or incomplete";
  double worst_balance = 0.0, worst_error = 0.0, worst_no_change = 0.0;
  bool falls = true;
  for (const bool axisymmetric : {false, true}) {
    const std::string g = axisymmetric ? "axisymmetric" : "planar";
    for (double cfl : widths) {
      double previous = 0.0;
      const std::vector<double> spacings =
          refined && *refined == cfl ? std::vector<double>{0.5, 0.25} : std::vector<double>{0.5};
      // speed against error (issue 20 item 8): the worst deviation at the three points vs wall time
      char series_name[64];
      std::snprintf(series_name, sizeof series_name, "%s, CFL %g um", g.c_str(), cfl);
      io::SpeedErrorSeries speed{series_name, {}, {}, {}};
      for (double h : spacings) {
        const CoupledRun r = run_coupled(case_name, axisymmetric, cfl, h, reference);
        EXPECT_TRUE(r.run.converged) << g << " " << cfl << " " << h;
        worst_balance = std::max(worst_balance, r.run.worst_mass_residual);
        worst_error = std::max(worst_error, r.worst_error);
        worst_no_change = std::max(worst_no_change, r.no_change);
        if (previous > 0.0 && !(r.worst_error < previous)) falls = false;
        previous = r.worst_error;
        std::map<std::string, io::Value> row = {{"geometry", g}, {"cfl_um", cfl}, {"h_um", h},
                                                              {"steps", double(r.run.steps)},
                                                              {"worst_relative_error", r.worst_error},
                                                              {"wall_time_s", r.run.wall_time_s}};
        for (const auto& [k, v] : r.value) row[k] = v;
        for (const auto& [k, v] : r.point_error) row[k] = v;
        record.add_run(row, r.run.scene_text);
        speed.wall_time_s.push_back(r.run.wall_time_s);
        speed.error.push_back(r.worst_error);
        speed.label.push_back("h=" + std::to_string(h).substr(0, 4));
      }
      if (spacings.size() > 1) record.add_speed_error(speed);
    }
  }
  EXPECT_TRUE(record.add_metric({"reference_agreement",
                                 "largest relative deviation of NO or PO2 from the reference at the EC, SM and tissue "
                                 "points, any run",
                                 "", worst_error, 5e-3, 0.0, io::Comparison::at_most,
                                 "the issue's 0.5 %: at h = 0.5 um the lattice's O(h^2) error is about 0.3 % at the EC "
                                 "(a thin source layer of 5 rows) and below 0.1 % elsewhere; the reference's own error "
                                 "is 100x smaller"}))
      << worst_error;
  if (refined) {
    EXPECT_TRUE(record.add_metric({"error_falls_with_h", "the deviation falls from each spacing to the next, every "
                                   "geometry and width", "", falls ? 1.0 : 0.0, 1.0, 0.0, io::Comparison::at_least,
                                   "a converging scheme; the reference is exact to 4e-5"}));
  }
  EXPECT_TRUE(record.add_metric({"no_steady", "NO's last change over 0.25 s / its largest value, any run", "",
                                 worst_no_change, 1e-7, 0.0, io::Comparison::at_most,
                                 "the run stops on O2; NO's slowest mode (tissue, ~0.7 s) then leaves at most ~3x "
                                 "this change to come, so 1e-7 bounds the remaining drift far below the 3e-3 "
                                 "discretisation error at h = 0.5 um (measured 7.6e-9)"}))
      << worst_no_change;
  EXPECT_TRUE(record.add_metric(vv::mass_balance_metric(worst_balance))) << worst_balance;
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
}  // namespace

// CI tier: the 3 µm layer at h = 0.5 µm, planar and axisymmetric.
TEST(TransportArterioleNoO2, CoupledSteadyStateAgainstTheReference) {
  coupled_case("verification.transport_arteriole_no_o2", {3.0}, std::nullopt);
}

// Full tier: the 2, 3 and 5 µm layers at h = 0.5 µm, the 3 µm layer also at 0.25 µm (measured:
// 0.25 µm on every width gives 0.02-0.04 % everywhere, at 6x the cost).
TEST(TransportArterioleNoO2Full, CoupledSteadyStateAgainstTheReference) {
  coupled_case("verification.transport_arteriole_no_o2_full", {2.0, 3.0, 5.0}, 3.0);
}
