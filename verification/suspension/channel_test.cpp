// Case verification.channel_diagnostics (issue 19 item 3): the channel probe's numbers
// and the profiles across the channel against closed forms (docs/model.md §12).
//
// Requirement: (1) plasma alone in a channel at steady state (channel_plasma.toml, TRT
// with Λ = 3/16, which puts the halfway bounce-back walls exactly at y = 0 and H, so the
// steady profile is the parabola at the nodes): the relative apparent viscosity U0/Ū is
// the closed form of the node sum: the flow rate is the midpoint sum of u over the n rows,
// which for the parabola exceeds F H³/(12 μ) by the factor 1 + 1/(2n²), so
// U0/Ū = 1/(1 + 1/(2n²)). (2) one circular cell of radius R at height y_c, at rest
// (channel_one_cell.toml): the cell-free layers are the circle's, y_c − πR/4 at the bottom
// (the mean over the columns the circle crosses of the distance to its lower arc) and
// H − y_c − πR/4 at the top; the tube haematocrit is the 96-gon's area (n/2)R² sin(2π/n)
// over the channel's. Profiles (eq 12.6, run.h5 /profiles): (1) the velocity profile is the
// parabola F y (H − y)/(2μ) at the row centres, its row mean the series' Ū, and the
// haematocrit and the cells' flux are 0 in every row; (2) each row's haematocrit × n_x is
// the polygon's chord at the row's centre in nodes, and its row mean is the tube
// haematocrit; (3) the cell carried by the flow (the same scene, F = 1.5e5 N/m³, centre at
// y = 8 µm, 2000 steps): the discharge haematocrit of the nodes Σq/Σū (eq 12.7) is the
// probe's H_d (eq 12.3).
// Reference: the closed forms above. Tolerances: (1) 1e-9, the steady state's own
// convergence (the run stops when u changes by < 1e-12 per 100 steps), and no transverse
// velocity (mean |u_y| ≤ 1e-12 u_max, round-off); the profile: 1e-9 of u_max likewise
// (Λ = 3/16 puts the walls exactly at y = 0 and H: no wall-position error), its row mean
// 1e-12 (the same sum in another order); no cells: exactly 0; (2) the column mean
// samples the arc at lattice columns (with partial columns at the circle's two sides) and
// takes the lowest of markers 0.79 h apart: a quarter of h; the area: round-off, 1e-9.
// A row counts the node centres on its chord: below one node per row, |n_j − c_j/h| < 1
// (each of the chord's two ends within half a node). Summed over the rows the outline
// crosses, the nodes inside differ from A/h² by less than one node per row crossed (the
// chords at the row centres stand for the h-high strips: a midpoint rule in y, of smaller
// order), so |mean φ − H_t| ≤ rows crossed/(n_x n_y). (3) The nodes' flux has the same
// discretisation, each node carrying at most u_max: relative (u_max/U_c)·rows/N_inside;
// and the probe carries the cell at its mean marker velocity U_c, the mean of u over the
// outline, where the flux has the mean over the area: for the parabola, u = u_max − 4 u_max
// (y − H/2)²/H², these differ by u_max R²/H² (the mean of (y − y_c)² is R²/2 on a circle,
// R²/4 on the disk): relative (u_max/U_c)(R/H)². The tolerance is their sum.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "analysis/profiles.hpp"
#include "common/case_support.hpp"
#include "common/scene_case.hpp"

using namespace erythro;

namespace {
// The length of the chord of the closed polygon (x, y) at height y0 (even–odd: the
// crossings of its edges, sorted, paired).
double chord(const std::vector<double>& x, const std::vector<double>& y, std::size_t from, std::size_t to, double y0) {
  std::vector<double> xs;
  for (std::size_t i = from; i < to; ++i) {
    const std::size_t k = i + 1 < to ? i + 1 : from;
    if ((y[i] > y0) != (y[k] > y0)) xs.push_back(x[i] + (y0 - y[i]) * (x[k] - x[i]) / (y[k] - y[i]));
  }
  std::sort(xs.begin(), xs.end());
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < xs.size(); i += 2) length += xs[i + 1] - xs[i];
  return length;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}
}  // namespace

TEST(ChannelDiagnostics, PlasmaAndOneCell) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.channel_diagnostics", "suspension");
  record.set_requirement(
      "The channel probe against closed forms: plasma alone at steady state gives U0/mean(u) = 1/(1 + 1/(2n^2)) "
      "(the node sum of the exact parabola) within 1e-9; one circular cell at rest gives the cell-free layers "
      "y_c - pi R/4 and H - y_c - pi R/4 within h/4 and the tube haematocrit of its polygon within 1e-9. The "
      "profiles across the channel: plasma alone gives the parabola F y (H - y)/(2 mu) at the row centres within "
      "1e-9 u_max and no haematocrit; one circle at rest gives each row's haematocrit x n_x within one node of its "
      "chord and the row mean within one node per row crossed of the tube haematocrit; a circle carried by the flow "
      "gives the discharge haematocrit of the nodes (cells' flux / flow) within the discretisation and the "
      "outline-versus-area mean velocity of the probe's.");
  record.set_reference(
      "Plane Poiseuille flow, U0 = F H^2/(12 mu) (docs/model.md eq 12.1), midpoint sum over n rows; the mean of "
      "the lower arc of a circle over its width, pi R/4 below the centre (eq 12.2); the area of a regular n-gon "
      "(eq 12.3); the chord of a polygon; the mean of a parabola over a circle and over a disk (eqs 12.6, 12.7).");

  const vv::CaseRun plasma = vv::run_case_scene(vv::case_scene("verification/suspension/channel_plasma.toml"),
                                                record.case_name(), "plasma");
  ASSERT_TRUE(plasma.ok()) << plasma.summary.diagnosis;
  const double rows = plasma.setup.grid.ny;
  const double eta = plasma.file.series("relative_apparent_viscosity").back();
  const double eta_expected = 1.0 / (1.0 + 1.0 / (2.0 * rows * rows));
  record.add_run({{"scene", std::string("plasma")},
                  {"rows", rows},
                  {"steps", static_cast<double>(plasma.summary.steps)},
                  {"relative_apparent_viscosity", eta},
                  {"expected", eta_expected},
                  {"wall_time_s", plasma.wall_time_s}},
                 plasma.scene.source_text);
  const double transverse = plasma.file.series("mean_transverse_plasma_speed_um_s").back();
  const double u_max_um_s = 1.5 * plasma.file.series("channel_mean_velocity_um_s").back();
  record.add_metric({"plasma_transverse_speed", "mean |u_y| of plasma alone at steady state, / u_max", "",
                     transverse / u_max_um_s, 1e-12, 0.0, io::Comparison::at_most,
                     "plane Poiseuille flow has no transverse velocity; round-off only"});
  record.add_metric({"plasma_relative_viscosity", "U0/mean(u) of plasma alone at steady state", "", eta, eta_expected,
                     1e-9, io::Comparison::absolute,
                     "the steady state is reached to 1e-12 per 100 steps; TRT's walls make the parabola exact"});

  // eq 12.6: the profiles of plasma alone
  {
    const auto& s = plasma.setup;
    const std::vector<double>& u = plasma.file.profile("velocity_x_um_s").back();
    const std::vector<double>& y = plasma.file.profile_y_um();
    const double h_um = s.scales.length_m * 1e6, H_um = s.grid.ny * h_um;
    const double F = plasma.scene.body_force->density_N_m3[0], mu = plasma.scene.fluid.viscosity_cP * 1e-3;
    std::vector<double> parabola(y.size()), error(y.size());
    for (std::size_t j = 0; j < y.size(); ++j) {
      EXPECT_NEAR(y[j], (static_cast<double>(j) + 0.5) * h_um, 1e-12 * H_um);
      parabola[j] = F * (y[j] * 1e-6) * ((H_um - y[j]) * 1e-6) / (2.0 * mu) * 1e6;  // um/s
      error[j] = u[j] - parabola[j];
    }
    const double u_max = F * H_um * H_um * 1e-12 / (8.0 * mu) * 1e6;
    double row_mean = 0.0;
    for (double v : u) row_mean += v / static_cast<double>(u.size());
    const double series_mean = plasma.file.series("channel_mean_velocity_um_s").back();
    const double cells_in_plasma = std::max(max_abs(plasma.file.profile("haematocrit").back()),
                                            max_abs(plasma.file.profile("cell_flux_um_s").back()) / u_max);
    record.add_series({"plasma_velocity_profile", "Plasma alone: velocity profile across the channel at steady state",
                       "y (um)", "mean u_x over the row (um/s)", y, u, parabola});
    record.add_metric({"plasma_profile_error", "max over the rows of |u_j - F y_j (H - y_j)/(2 mu)| / u_max", "",
                       max_abs(error) / u_max, 1e-9, 0.0, io::Comparison::at_most,
                       "TRT's walls at y = 0 and H make the parabola exact at the nodes; the steady state is reached "
                       "to 1e-12 per 100 steps"});
    record.add_metric({"plasma_profile_mean", "row mean of the velocity profile against the series' mean velocity",
                       "um/s", row_mean, series_mean, 1e-12, io::Comparison::relative,
                       "the same node sum in another order: round-off"});
    record.add_metric({"plasma_profile_no_cells", "max over the rows of the haematocrit and of the cells' flux / u_max",
                       "", cells_in_plasma, 0.0, 0.0, io::Comparison::at_most, "no cells: no node inside one"});
  }

  const vv::CaseRun one = vv::run_case_scene(vv::case_scene("verification/suspension/channel_one_cell.toml"),
                                             record.case_name(), "one_cell");
  ASSERT_TRUE(one.ok()) << one.summary.diagnosis;
  const scene::CellSpec& cell = one.scene.cells.at(0);
  const double h_um = one.setup.scales.length_m * 1e6, H_um = one.setup.grid.ny * h_um;
  const double L_um = one.setup.grid.nx * h_um, R = cell.radius_um, yc = cell.center_um[1];
  const double n = static_cast<double>(cell.markers);
  const double bottom = one.file.series("cell_free_layer_bottom_um").back();
  const double top = one.file.series("cell_free_layer_top_um").back();
  const double hct = one.file.series("tube_haematocrit").back();
  const double bottom_expected = yc - std::numbers::pi * R / 4.0, top_expected = H_um - yc - std::numbers::pi * R / 4.0;
  const double hct_expected = 0.5 * n * R * R * std::sin(2.0 * std::numbers::pi / n) / (L_um * H_um);
  record.add_run({{"scene", std::string("one cell")},
                  {"cell_free_layer_bottom_um", bottom},
                  {"expected_bottom_um", bottom_expected},
                  {"cell_free_layer_top_um", top},
                  {"expected_top_um", top_expected},
                  {"tube_haematocrit", hct},
                  {"expected_haematocrit", hct_expected},
                  {"wall_time_s", one.wall_time_s}},
                 one.scene.source_text);
  const std::string column_reason =
      "the column mean samples the arc at lattice columns (partial columns at the circle's sides) and takes the "
      "lowest of markers 0.79 h apart: a quarter of h";
  record.add_metric({"cfl_bottom", "cell-free layer at the bottom wall, one circle", "um", bottom, bottom_expected,
                     0.25 * h_um, io::Comparison::absolute, column_reason});
  record.add_metric({"cfl_top", "cell-free layer at the top wall, one circle", "um", top, top_expected, 0.25 * h_um,
                     io::Comparison::absolute, column_reason});
  record.add_metric({"tube_haematocrit", "the cell's share of the channel's area", "", hct, hct_expected, 1e-9,
                     io::Comparison::relative, "the polygon's area, exact to round-off (the cell has not moved)"});
  // eq 12.6: the haematocrit profile of the circle at rest, row by row against its chord
  {
    const auto& phi = one.file.profile("haematocrit").back();
    const io::RunFile::CellsFrame& frame = one.file.cells().back();
    const double nx = one.setup.grid.nx, ny = one.setup.grid.ny;
    const std::vector<double>& y = one.file.profile_y_um();
    std::vector<double> chord_nodes(y.size()), counted(y.size());
    double worst_row = 0.0, rows_crossed = 0.0, row_mean = 0.0;
    for (std::size_t j = 0; j < y.size(); ++j) {
      chord_nodes[j] = chord(frame.x_um, frame.y_um, frame.offsets[0], frame.offsets[1], y[j]) / h_um;
      counted[j] = phi[j] * nx;
      worst_row = std::max(worst_row, std::abs(counted[j] - chord_nodes[j]));
      if (chord_nodes[j] > 0.0) rows_crossed += 1.0;
      row_mean += phi[j] / ny;
    }
    record.add_series({"one_cell_haematocrit_profile", "One circle at rest: nodes inside per row against its chord",
                       "y (um)", "nodes inside the cell per row", y, counted, chord_nodes});
    record.add_metric({"one_cell_profile_rows", "max over the rows of |nodes inside - chord/h|", "nodes", worst_row,
                       1.0, 0.0, io::Comparison::at_most,
                       "a row counts the node centres on its chord: each of the chord's two ends within half a node"});
    record.add_metric({"one_cell_profile_tube_haematocrit", "row mean of the haematocrit profile against H_t", "",
                       row_mean, hct, rows_crossed / (nx * ny), io::Comparison::absolute,
                       "one node per row the outline crosses (" + std::to_string(static_cast<int>(rows_crossed)) +
                           " rows): the chord's two ends, and the midpoint rule in y of smaller order"});
  }

  // eqs 12.6, 12.7: the circle carried by the flow; the discharge haematocrit of the nodes
  // against the probe's, and the time-averaged profiles for the report
  const vv::CaseRun flow = vv::run_case_scene(
      vv::case_scene("verification/suspension/channel_one_cell.toml",
                     {"body_force.density_N_m3=[1.5e5, 0.0]", "run.steps=2000", "output.diagnostics_interval_steps=200",
                      "cells[0].center_um=[10.0, 8.0]"}),
      record.case_name(), "flowing_cell");
  ASSERT_TRUE(flow.ok()) << flow.summary.diagnosis;
  {
    const auto& u = flow.file.profile("velocity_x_um_s").back();
    const auto& phi = flow.file.profile("haematocrit").back();
    const auto& q = flow.file.profile("cell_flux_um_s").back();
    const analysis::ChannelHaematocrits nodes = analysis::channel_haematocrits(phi, q, u);
    const double hd = flow.file.series("discharge_haematocrit").back();
    const double ht = flow.file.series("tube_haematocrit").back();
    const double mean_u = flow.file.series("channel_mean_velocity_um_s").back();
    const double u_cell = hd * mean_u / ht;  // eq 12.3 with one cell: H_d/H_t = U_c/Ū
    const double u_max = *std::max_element(u.begin(), u.end());
    const double h = flow.setup.scales.length_m * 1e6, H = flow.setup.grid.ny * h;
    const double r = flow.scene.cells.at(0).radius_um;
    double rows_crossed = 0.0, inside = 0.0;
    for (double p : phi) {
      rows_crossed += p > 0.0 ? 1.0 : 0.0;
      inside += p * flow.setup.grid.nx;
    }
    const double tolerance = u_max / u_cell * (rows_crossed / inside + (r / H) * (r / H));
    record.add_run({{"scene", std::string("flowing cell")},
                    {"discharge_haematocrit", hd},
                    {"discharge_haematocrit_nodes", nodes.discharge},
                    {"tube_haematocrit", ht},
                    {"tube_haematocrit_nodes", nodes.tube},
                    {"cell_velocity_um_s", u_cell},
                    {"max_velocity_um_s", u_max},
                    {"wall_time_s", flow.wall_time_s}},
                   flow.scene.source_text);
    record.add_metric({"flowing_cell_discharge_haematocrit",
                       "discharge haematocrit of the nodes (sum q / sum u, eq 12.7) against the probe's H_d (eq 12.3)",
                       "", nodes.discharge, hd, tolerance, io::Comparison::relative,
                       "the nodes' discretisation of the flux, (u_max/U_c) rows crossed / nodes inside, plus the "
                       "outline-versus-area mean of the parabola, (u_max/U_c)(R/H)^2"});
    // The time-averaged profiles over the run's second half (eq 12.7), for the report.
    const std::vector<double>& time = flow.file.series("time_s");
    const double after = 0.5 * time.back();
    const std::vector<double>& y = flow.file.profile_y_um();
    record.add_series({"flowing_cell_velocity_profile", "Circle carried by the flow: time-averaged velocity profile",
                       "y (um)", "mean u_x over the row (um/s)", y,
                       analysis::time_average(time, flow.file.profile("velocity_x_um_s"), after), {}});
    record.add_series({"flowing_cell_haematocrit_profile", "Circle carried by the flow: time-averaged haematocrit",
                       "y (um)", "haematocrit of the row", y,
                       analysis::time_average(time, flow.file.profile("haematocrit"), after), {}});
  }
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  for (const auto& m : record.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}
