// Case verification.channel_diagnostics (issue 19 item 3): the channel probe's numbers
// against closed forms (docs/model.md §12).
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
// over the channel's.
// Reference: the closed forms above. Tolerances: (1) 1e-9, the steady state's own
// convergence (the run stops when u changes by < 1e-12 per 100 steps), and no transverse
// velocity (mean |u_y| ≤ 1e-12 u_max, round-off); (2) the column mean
// samples the arc at lattice columns (with partial columns at the circle's two sides) and
// takes the lowest of markers 0.79 h apart: a quarter of h; the area: round-off, 1e-9.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "common/case_support.hpp"
#include "common/scene_case.hpp"

using namespace erythro;

TEST(ChannelDiagnostics, PlasmaAndOneCell) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.channel_diagnostics", "suspension");
  record.set_requirement(
      "The channel probe against closed forms: plasma alone at steady state gives U0/mean(u) = 1/(1 + 1/(2n^2)) "
      "(the node sum of the exact parabola) within 1e-9; one circular cell at rest gives the cell-free layers "
      "y_c - pi R/4 and H - y_c - pi R/4 within h/4 and the tube haematocrit of its polygon within 1e-9.");
  record.set_reference(
      "Plane Poiseuille flow, U0 = F H^2/(12 mu) (docs/model.md eq 12.1), midpoint sum over n rows; the mean of "
      "the lower arc of a circle over its width, pi R/4 below the centre (eq 12.2); the area of a regular n-gon "
      "(eq 12.3).");

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
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  for (const auto& m : record.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}
