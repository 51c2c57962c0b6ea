// validation.deoxygenation (full) and validation.deoxygenation_ci (CI): a still 2D
// biconcave RBC releasing O2 into a box held at 20 µM (thesis ch. V calibration case).
// The rate modifier M > 0 of the cell-averaged Hb kinetics (rate k_off/M) is fitted
// (calibration.hpp, Brent on ln M, RMS misfit) to the cell-averaged S(t) of the resolved
// PLANAR section (reference_rbc.py --planar, local kinetics); the 3D axisymmetric cell
// (reference_rbc.py) is fitted too, to measure the geometric gap.
// docs/validation-deoxygenation.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "common/calibration.hpp"
#include "common/case_support.hpp"
#include "deoxy_run.hpp"
#include "io/result_record.hpp"

using namespace erythro;

namespace {

// Validation tolerance of the issue: the calibrated cell-averaged saturation follows the
// reference within 0.01 in S over the whole transient (S falls by ≈ 0.79). The reference's
// own numerical error (Richardson, PROVENANCE.md) is < 2e-4, well inside it.
constexpr double kCurveTolerance = 0.01;
// Resolution independence of the fitted modifier between h = 0.2 and 0.1 µm (issue).
constexpr double kMChangeTolerance = 0.02;
// CI subset at h = 0.4 um (6.5 nodes across the rim): the misfit there is lattice error
// (release too slow even with instantaneous kinetics: 0.026 at M = 0.05); 0.05 guards the
// coupling/transport against regressions without claiming validation.
constexpr double kCiCurveTolerance = 0.05;
// The 3D cell is not reachable by any M (the gap is geometric: planar vs revolved diffusion).
// The best free-M fit to the 3D curve must stay far outside the validation tolerance
// (measured 0.07–0.09); 0.05 = five times the tolerance, while the planar fit meets 0.01.
constexpr double kGeometricGapFloor = 0.05;
// O2 balance: released = Δ(O2 in the lattice) − boundary inflow, summed over ~10⁵
// steps of round-off-level per-step balances (transport_lattice.hpp eq T5).
constexpr double kBalanceTolerance = 1e-9;
// Free bracket of the modifier, fitted as x = ln M (rate k_off/M from k_off/4 to 20 k_off;
// M → 0 is instantaneous local equilibrium, M = 0.05 already within 1e-3 of that limit).
const double kLnMLower = std::log(0.05), kLnMUpper = std::log(4.0);
// Central-difference step in ln M for the sensitivity (±2 % in M).
constexpr double kFdLnM = 0.02;

std::string fmt(const char* f, double v) {
  char b[96];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// Planar reference (the calibration target): the same Evans–Fung section as a 2D planar
// cell, resolved local kinetics (reference_rbc.py --planar). 3D reference: the real,
// axisymmetric cell (reference_rbc.py) — the model-form comparison.
vv::Curve planar_reference() {
  return deoxy::read_reference(std::string(ERYTHRO_DEOXY_REFERENCE_DIR) + "/reference_S_planar.csv", 1);
}
vv::Curve cell_reference() {
  return deoxy::read_reference(std::string(ERYTHRO_DEOXY_REFERENCE_DIR) + "/reference_S.csv", 1);
}

// Runs of one lattice level, each M once (fits against both references share them).
struct Runner {
  deoxy::Setup base;
  std::map<double, deoxy::Result> memo;
  int runs = 0;
  const deoxy::Result& at(double M) {
    auto it = memo.find(M);
    if (it == memo.end()) {
      deoxy::Setup s = base;
      s.hb.M = M;
      it = memo.emplace(M, deoxy::run(s)).first;
      ++runs;
    }
    return it->second;
  }
};

struct Fit {
  vv::CalibrationResult r;  // parameter x = ln M
  double M = 0.0;
  int runs = 0;             // new lattice runs of this fit (memo hits excluded)
  double wall_s = 0.0;
  double rms_minus = 0.0, rms_plus = 0.0;  // linearised RMS misfit at ln M ∓ kFdLnM
};

// Brent on x = ln M ∈ [lo, hi] to |Δ ln M| ≤ tol_lnM (≈ relative tolerance in M).
Fit fit_lnM(Runner& run, const vv::Curve& ref, double lo, double hi, double tol_lnM) {
  vv::Stopwatch clock;
  const int runs0 = run.runs;
  const vv::CurveModel model = [&](const std::vector<double>& p) { return run.at(std::exp(p[0])).S; };
  vv::CalibrationOptions opt;
  opt.norm = vv::MisfitNorm::rms;
  opt.x_tolerance = tol_lnM / (hi - lo);
  opt.fd_relative_step = kFdLnM / (hi - lo);
  Fit f;
  f.r = vv::calibrate_1d(model, ref, {"lnM", lo, hi, 0.5 * (lo + hi)}, opt);
  f.M = std::exp(f.r.params[0]);
  // Is the fit a minimum? RMS at ln M ∓ δ from r + J δ (δ = kFdLnM).
  const auto r0 = vv::residuals(run.at(f.M).S, ref);
  double sm = 0.0, sp = 0.0;
  for (std::size_t k = 0; k < r0.size(); ++k) {
    sm += std::pow(r0[k] - f.r.jacobian[k][0] * kFdLnM, 2);
    sp += std::pow(r0[k] + f.r.jacobian[k][0] * kFdLnM, 2);
  }
  f.rms_minus = std::sqrt(sm / static_cast<double>(r0.size()));
  f.rms_plus = std::sqrt(sp / static_cast<double>(r0.size()));
  f.runs = run.runs - runs0;
  f.wall_s = clock.seconds();
  return f;
}

struct Level {
  double h = 0.0, dt = 0.0;
  Fit planar;            // fit against the planar reference (the validation target)
  Fit cell;              // free-M fit against the 3D cell (documented difference); r.params empty: not done
  deoxy::Result calibrated;  // at the planar fit
  vv::Misfit plain_misfit;   // M = 1 against the planar reference (if run)
  vv::Misfit cell_at_planar_fit;
  bool has_plain = false;
  double wall_s = 0.0;
  int runs = 0;
};

Runner make_runner(double h, double t_end) {
  Runner r;
  r.base.h_um = h;
  r.base.dt_s = deoxy::diffusive_dt(h);
  r.base.t_end_s = t_end;
  return r;
}

// One level: planar fit on [lo, hi] (ln M), optionally the 3D fit on the full bracket and M = 1.
Level calibrate_level(double h, const vv::Curve& ref, const vv::Curve& cell, double lo, double hi, double tol_lnM,
                      bool fit_cell, bool run_plain) {
  vv::Stopwatch clock;
  Level L;
  L.h = h;
  L.dt = deoxy::diffusive_dt(h);
  Runner run = make_runner(h, ref.t.back());
  L.planar = fit_lnM(run, ref, lo, hi, tol_lnM);
  L.calibrated = run.at(L.planar.M);
  L.cell_at_planar_fit = vv::curve_misfit(L.calibrated.S, cell);
  std::printf("h = %.2f um planar: M = %.4f (bound %d, %d evals + %d), max %.5f rms %.5f, 3D at it %.4f; %.0f s\n", h,
              L.planar.M, static_cast<int>(L.planar.r.at_bound[0]), L.planar.r.evaluations,
              L.planar.r.sensitivity_evaluations, L.planar.r.misfit.max_abs, L.planar.r.misfit.rms,
              L.cell_at_planar_fit.max_abs, L.planar.wall_s);
  std::fflush(stdout);
  if (fit_cell) {
    L.cell = fit_lnM(run, cell, kLnMLower, kLnMUpper, 0.01);
    std::printf("h = %.2f um 3D cell: M = %.4f (bound %d), max %.5f rms %.5f; %.0f s\n", h, L.cell.M,
                static_cast<int>(L.cell.r.at_bound[0]), L.cell.r.misfit.max_abs, L.cell.r.misfit.rms, L.cell.wall_s);
  }
  if (run_plain) {
    L.plain_misfit = vv::curve_misfit(run.at(1.0).S, ref);
    L.has_plain = true;
  }
  L.runs = run.runs;
  L.wall_s = clock.seconds();
  std::fflush(stdout);
  return L;
}

void describe(io::ResultRecord& rec, double t_end) {
  rec.set_requirement(
      "With one calibrated rate modifier M > 0 (rate k_off/M), the 2D lattice model of a still biconcave RBC (ONE "
      "cell-averaged Hb-O2 saturation, D2Q5 O2 transport) reproduces the cell-averaged saturation S(t) of the same "
      "section resolved with local Hb-O2 kinetics within 0.01 over the whole transient, and M is "
      "resolution-independent (< 2 % between h = 0.2 and 0.1 um); the gap to the 3D (axisymmetric) real cell is "
      "measured by a free-M fit and reported.");
  rec.set_reference(
      "reference_data/deoxygenation/reference_rbc.py (PROVENANCE.md): finite volumes + BDF2 + Newton, local "
      "Hb-O2 kinetics (k_off = 44 1/s, Hill P50 = 26.8 Torr, n = 2.7, heme 20.3 mM), D_O2 950 (in) / 2800 (out) "
      "um^2/s; --planar: the Evans-Fung section as a planar cell (calibration target, reference_S_planar.csv); "
      "default: the 3D cell of revolution (reference_S.csv); each converged to < 2e-4 in S (3 grids, "
      "Richardson). Thesis ch. V: single RBC in a 20 uM medium, lattice 0.2 um, dt = 10 us.");
  rec.set_parameter("geometry", "square box of half-width 6 um, C = 20 uM held on all sides (3D reference: "
                                "cylinder r <= 6 um, |z| <= 6 um held at 20 uM; planar reference: the same square)");
  rec.set_parameter("initial_state", "cell in equilibrium at P0 = 100 Torr (S0 = Hill(100) = 0.9722), medium 20 uM");
  rec.set_parameter("kinetics", "dS/dt = -(k_off/M)[S - (1-S)(P/P50)^n], P = mean over interior nodes "
                                "(hb_kinetics.hpp), cell-implicit coupling (deoxy_run.hpp)");
  rec.set_parameter("D_in_um2_s", 950.0);
  rec.set_parameter("D_out_um2_s", 2800.0);
  rec.set_parameter("dt_scaling", "diffusive: dt = 10 us (h/0.2 um)^2, tau_out = 2.6, tau_in = 1.2125 at every level");
  rec.set_parameter("mask", "interior::ray_cast_inside of membrane::biconcave(800 markers, a = 3.91 um)");
  rec.set_parameter("calibration", "Brent on x = ln M (calibration.hpp), free bracket M in [0.05, 4], RMS misfit at "
                                   "the reference times (linear interpolation of the simulated curve), central-"
                                   "difference sensitivity at ln M +- 0.02");
  rec.set_parameter("t_end_s", t_end);
}

void add_level(io::ResultRecord& rec, const Level& L) {
  const auto& f = L.planar.r;
  std::map<std::string, io::Value> row{
      {"h_um", L.h},
      {"dt_us", L.dt * 1e6},
      {"nodes_per_side", static_cast<double>(L.calibrated.nodes)},
      {"interior_nodes", static_cast<double>(L.calibrated.interior_nodes)},
      {"interior_area_um2", L.calibrated.interior_area_um2},
      {"M_fitted", L.planar.M},
      {"M_at_bound", f.at_bound[0] ? 1.0 : 0.0},
      {"max_misfit", f.misfit.max_abs},
      {"rms_misfit", f.misfit.rms},
      {"sensitivity_rms_dS_dlnM", f.sensitivity_rms[0]},
      {"sensitivity_max_dS_dlnM", f.sensitivity_max[0]},
      {"sensitivity_rms_dS_dM", f.sensitivity_rms[0] / L.planar.M},
      {"relative_width_M_for_0.001", f.width(0, 1e-3)},
      {"gn_relative_standard_error_M", f.gn_standard_error[0]},
      {"brent_evaluations", static_cast<double>(f.evaluations)},
      {"model_runs", static_cast<double>(L.runs)},
      {"max_misfit_3d_cell_at_planar_fit", L.cell_at_planar_fit.max_abs},
      {"balance_residual", L.calibrated.balance_residual},
      {"max_step_balance_residual", L.calibrated.max_step_residual},
      {"run_wall_time_s", L.calibrated.wall_s},
      {"wall_time_s", L.wall_s},
      {"error", f.misfit.max_abs}};
  if (L.has_plain) {
    row["max_misfit_M1"] = L.plain_misfit.max_abs;
    row["rms_misfit_M1"] = L.plain_misfit.rms;
  }
  if (!L.cell.r.params.empty()) {
    row["M_fitted_3d_cell"] = L.cell.M;
    row["M_3d_at_bound"] = L.cell.r.at_bound[0] ? 1.0 : 0.0;
    row["max_misfit_3d_cell_fit"] = L.cell.r.misfit.max_abs;
    row["rms_misfit_3d_cell_fit"] = L.cell.r.misfit.rms;
  }
  rec.add_run(row);
}

void add_level_metrics(io::ResultRecord& rec, const Level& L, double curve_tolerance, const std::string& reason) {
  const std::string tag = fmt("h%.2f", L.h);
  const auto& f = L.planar;
  if (curve_tolerance > 0.0)
    rec.add_metric({"max_misfit_" + tag, "max |S_2D - S_ref,planar| over the transient at the fitted M, h = " +
                        fmt("%.2f um", L.h), "", f.r.misfit.max_abs, curve_tolerance, 0.0, io::Comparison::at_most,
                    reason});
  rec.add_metric({"fit_is_minimum_" + tag,
                  "min(RMS(lnM - 0.02), RMS(lnM + 0.02)) - RMS(lnM) (linearised; >= 0 at a minimum, one side at a "
                  "bound)", "", std::min(f.r.at_bound[0] ? 1.0 : f.rms_minus, f.rms_plus) - f.r.misfit.rms, -1e-6,
                  0.0, io::Comparison::at_least, "Brent must end at a (constrained) minimum of the RMS misfit"});
  rec.add_metric({"o2_balance_" + tag, "|released - (change in lattice O2 - boundary inflow)| / released", "",
                  std::abs(L.calibrated.balance_residual), kBalanceTolerance, 0.0, io::Comparison::at_most,
                  "exact discrete balance (eq T5) summed over all steps: round-off only"});
}

io::Series curve_series(const std::string& name, const std::string& title, const vv::Curve& ref,
                        const vv::Curve& sim) {
  io::Series s;
  s.name = name;
  s.title = title;
  s.xlabel = "t (s)";
  s.ylabel = "S";
  s.x = ref.t;
  s.y_reference = ref.y;
  for (double t : ref.t) s.y.push_back(vv::interpolate(sim, t));
  return s;
}

void add_curves(io::ResultRecord& rec, const vv::Curve& ref, const vv::Curve& cell, const Level& L) {
  const std::string h = fmt("h = %.2f um", L.h);
  rec.add_series(curve_series("S(t) calibrated, " + h, "2D calibrated (M = " + fmt("%.3f", L.planar.M) +
                                                             ") vs planar resolved reference", ref, L.calibrated.S));
  rec.add_series(curve_series("S(t) vs 3D cell, " + h, "2D at the planar fit vs the 3D (axisymmetric) cell: "
                                                       "model-form gap", cell, L.calibrated.S));
}

}  // namespace

TEST(Deoxygenation, CiSubset) {
  vv::Stopwatch clock;
  const auto ref = planar_reference(), cell = cell_reference();
  const Level L = calibrate_level(0.4, ref, cell, kLnMLower, kLnMUpper, 0.01, false, false);
  io::ResultRecord rec("validation.deoxygenation_ci", "deoxygenation");
  describe(rec, ref.t.back());
  rec.set_parameter("levels", "h = 0.4 um only (CI subset of validation.deoxygenation), tolerance 0.01 in ln M");
  add_level(rec, L);
  add_level_metrics(rec, L, kCiCurveTolerance,
                    "CI regression guard at the coarse lattice (lattice error dominates there; the 0.01 validation "
                    "tolerance is asserted by validation.deoxygenation at h = 0.1 um)");
  add_curves(rec, ref, cell, L);
  rec.set_wall_time(clock.seconds());
  std::printf("written: %s\n", rec.write_to_results_dir().c_str());
  for (const auto& m : rec.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}

// Finest level (a run costs ~16 runs at 0.2 um): Brent on a narrow bracket around the 0.2 um
// fit (warm start), ln M(0.2) ± 0.15 (M within −14 %/+16 %), tolerance 1e-3 in ln M. A fit
// ending on that bracket's edge means |ΔM| > 14 %, far outside the 2 % requirement: the check
// below then fails, as it must.
constexpr double kFineHalfBracket = 0.15;

TEST(Deoxygenation, FullStudy) {
  vv::Stopwatch clock;
  const auto ref = planar_reference(), cell = cell_reference();
  std::vector<Level> levels;
  levels.push_back(calibrate_level(0.4, ref, cell, kLnMLower, kLnMUpper, 0.01, true, true));
  levels.push_back(calibrate_level(0.2, ref, cell, kLnMLower, kLnMUpper, 1e-3, true, true));
  const double x2 = std::log(levels[1].planar.M);
  levels.push_back(
      calibrate_level(0.1, ref, cell, x2 - kFineHalfBracket, x2 + kFineHalfBracket, 1e-3, false, false));
  const Level &L2 = levels[1], &L1 = levels[2];

  io::ResultRecord rec("validation.deoxygenation", "deoxygenation");
  describe(rec, ref.t.back());
  rec.set_parameter("levels", "h = 0.4, 0.2 um: Brent on ln M over [ln 0.05, ln 4] (tolerance 0.01, 1e-3); h = 0.1 "
                              "um: Brent on ln M(0.2 um) +- 0.15 (tolerance 1e-3); dt = 40, 10, 2.5 us; 3D-cell fits "
                              "at 0.4 and 0.2 um (tolerance 0.01)");
  io::Series mh;
  mh.name = "fitted M vs h";
  mh.title = "calibrated rate modifier M against lattice spacing (planar reference)";
  mh.xlabel = "h (um)";
  mh.ylabel = "M";
  for (const auto& L : levels) {
    add_level(rec, L);
    add_level_metrics(rec, L, 0.0, "");  // balance and fit quality; misfits in /runs and below
    add_curves(rec, ref, cell, L);
    mh.x.push_back(L.h);
    mh.y.push_back(L.planar.M);
  }
  rec.add_series(mh);
  rec.add_metric({"max_misfit_h0.10", "max |S_2D - S_ref,planar| over the transient at the fitted M, h = 0.1 um", "",
                  L1.planar.r.misfit.max_abs, kCurveTolerance, 0.0, io::Comparison::at_most,
                  "issue 7 validation tolerance 0.01 in S: 1.3 % of the drop S0 - S_f = 0.79, fifty times the "
                  "reference's numerical error (Richardson < 2e-4); asserted at the finest lattice (coarser: /runs)"});
  const double dM = std::abs(L1.planar.M - L2.planar.M) / L1.planar.M;
  rec.add_metric({"M_change_h0.2_h0.1", "|M(0.1 um) - M(0.2 um)| / M(0.1 um), both Brent fits", "", dM,
                  kMChangeTolerance, 0.0, io::Comparison::at_most,
                  "issue 7: the fitted M is resolution-independent, < 2 % between 0.2 and 0.1 um (fit tolerance "
                  "1e-3 in ln M, i.e. 0.1 % in M)"});
  rec.add_metric({"misfit_decreases_with_h", "1 if the calibrated max misfit falls with every refinement 0.4 > 0.2 > "
                  "0.1 um", "", (L2.planar.r.misfit.max_abs < levels[0].planar.r.misfit.max_abs &&
                                 L1.planar.r.misfit.max_abs < L2.planar.r.misfit.max_abs) ? 1.0 : 0.0, 1.0, 0.0,
                  io::Comparison::at_least,
                  "the coarse-level misfit is lattice error (interior mask, D2Q5 at tau = 2.6): it must shrink with h"});
  rec.add_metric({"best_3d_misfit_h0.20", "max |S_2D - S_ref,3D| at the free-M fit to the 3D cell, h = 0.2 um", "",
                  L2.cell.r.misfit.max_abs, kGeometricGapFloor, 0.0, io::Comparison::at_least,
                  "the 2D-vs-3D gap is geometric (planar vs revolved O2 diffusion), not kinetic: no M closes it, "
                  "while the planar fit meets 0.01 (max_misfit_h0.10); measured direction, recorded difference"});
  rec.set_wall_time(clock.seconds());
  std::printf("M: %.4f %.4f %.4f, |dM|/M(0.1) = %.4f\n", levels[0].planar.M, L2.planar.M, L1.planar.M, dM);
  std::printf("written: %s\n", rec.write_to_results_dir().c_str());
  for (const auto& m : rec.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}

