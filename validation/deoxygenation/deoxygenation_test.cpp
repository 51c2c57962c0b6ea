// validation.deoxygenation (full) and validation.deoxygenation_ci (CI): a still 2D
// biconcave RBC releasing O2 into a box held at 20 µM (thesis ch. V calibration case).
// The rate modifier M of the cell-averaged Hb kinetics is fitted (calibration.hpp, Brent,
// RMS misfit) to the cell-averaged S(t) of the 3D axisymmetric reference solver
// reference_data/deoxygenation/reference_rbc.py (local kinetics, M = 1).
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
// own numerical error (Richardson, PROVENANCE.md) is ≈ 1e-3, well inside it.
constexpr double kCurveTolerance = 0.01;
// Resolution independence of the fitted modifier between h = 0.2 and 0.1 µm (issue).
constexpr double kMChangeTolerance = 0.02;
// CI subset at h = 0.4 um (6.5 nodes across the rim): the misfit there is dominated by the
// lattice error (full study: 0.032 at 0.4, 0.011 at 0.2 um at M = 1, falling with h);
// 0.05 guards the coupling/transport against regressions without claiming validation.
constexpr double kCiCurveTolerance = 0.05;
// O2 balance: released = Δ(O2 in the lattice) − boundary inflow, summed over ~10⁵
// steps of round-off-level per-step balances (transport_lattice.hpp eq T5).
constexpr double kBalanceTolerance = 1e-9;
constexpr double kMLower = 1.0, kMUpper = 30.0;

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

struct Level {
  double h = 0.0, dt = 0.0;
  vv::CalibrationResult fit;
  deoxy::Result calibrated, plain;  // at the fitted M and at M = 1
  vv::Misfit plain_misfit;          // M = 1 against the planar reference
  vv::Misfit cell_misfit, cell_plain_misfit;  // fitted M and M = 1 against the 3D cell
  double rms_minus = 0.0, rms_plus = 0.0;  // linearised RMS misfit at M ∓ δ (δ = fd step)
  double wall_s = 0.0;
  int runs = 0;
};

Level calibrate_level(double h, const vv::Curve& ref, const vv::Curve& cell, double lower, double upper) {
  vv::Stopwatch clock;
  Level L;
  L.h = h;
  L.dt = deoxy::diffusive_dt(h);
  deoxy::Setup base;
  base.h_um = h;
  base.dt_s = L.dt;
  base.t_end_s = ref.t.back();
  std::map<double, deoxy::Result> memo;  // each M runs once (the fit's final point is reused)
  const auto run_at = [&](double M) -> const deoxy::Result& {
    auto it = memo.find(M);
    if (it == memo.end()) {
      deoxy::Setup s = base;
      s.hb.M = M;
      it = memo.emplace(M, deoxy::run(s)).first;
      ++L.runs;
    }
    return it->second;
  };
  const vv::CurveModel model = [&](const std::vector<double>& p) { return run_at(p[0]).S; };
  vv::CalibrationOptions opt;
  opt.norm = vv::MisfitNorm::rms;
  opt.x_tolerance = 0.005 / (upper - lower);      // 0.005 in M
  opt.fd_relative_step = 0.02 / (upper - lower);  // ±0.02 in M for the sensitivity
  L.fit = vv::calibrate_1d(model, ref, {"M", lower, upper, 0.5 * (lower + upper)}, opt);
  L.calibrated = run_at(L.fit.params[0]);
  L.plain = run_at(1.0);
  L.plain_misfit = vv::curve_misfit(L.plain.S, ref);
  L.cell_misfit = vv::curve_misfit(L.calibrated.S, cell);
  L.cell_plain_misfit = vv::curve_misfit(L.plain.S, cell);
  // Is the fit a minimum? RMS at M ∓ δ from r + J δ (δ = 0.02, inside the bracket).
  const auto r0 = vv::residuals(L.calibrated.S, ref);
  const double d = 0.02;
  double sm = 0.0, sp = 0.0;
  for (std::size_t k = 0; k < r0.size(); ++k) {
    sm += std::pow(r0[k] - L.fit.jacobian[k][0] * d, 2);
    sp += std::pow(r0[k] + L.fit.jacobian[k][0] * d, 2);
  }
  L.rms_minus = std::sqrt(sm / static_cast<double>(r0.size()));
  L.rms_plus = std::sqrt(sp / static_cast<double>(r0.size()));
  L.wall_s = clock.seconds();
  std::printf("h = %.2f um: M = %.4f (bound %d), planar max %.4f rms %.4f; M = 1: max %.4f; 3D cell: max %.4f "
              "(M = 1: %.4f); %d runs, %.1f s\n",
              h, L.fit.params[0], static_cast<int>(L.fit.at_bound[0]), L.fit.misfit.max_abs, L.fit.misfit.rms,
              L.plain_misfit.max_abs, L.cell_misfit.max_abs, L.cell_plain_misfit.max_abs, L.runs, L.wall_s);
  return L;
}

void describe(io::ResultRecord& rec, double t_end) {
  rec.set_requirement(
      "With one calibrated rate modifier M >= 1, the 2D lattice model of a still biconcave RBC (ONE cell-averaged "
      "Hb-O2 saturation, D2Q5 O2 transport) reproduces the cell-averaged saturation S(t) of the same cell resolved "
      "with local Hb-O2 kinetics within 0.01 over the whole transient, and M is resolution-independent (< 2 % "
      "between h = 0.2 and 0.1 um); the gap to the 3D (axisymmetric) real cell is measured and reported.");
  rec.set_reference(
      "reference_data/deoxygenation/reference_rbc.py (PROVENANCE.md): finite volumes + BDF2 + Newton, local "
      "Hb-O2 kinetics (k_off = 44 1/s, Hill P50 = 26.8 Torr, n = 2.7, heme 20.3 mM), D_O2 950 (in) / 2800 (out) "
      "um^2/s; --planar: the Evans-Fung section as a planar cell (calibration target, reference_S_planar.csv); "
      "default: the 3D cell of revolution (reference_S.csv); each converged to < 1e-3 in S (3 grids, "
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
  rec.set_parameter("calibration", "Brent on M (calibration.hpp), RMS misfit at the reference times (linear "
                                   "interpolation of the simulated curve), central-difference sensitivity");
  rec.set_parameter("t_end_s", t_end);
}

void add_level(io::ResultRecord& rec, const Level& L) {
  rec.add_run({{"h_um", L.h},
               {"dt_us", L.dt * 1e6},
               {"nodes_per_side", static_cast<double>(L.calibrated.nodes)},
               {"interior_nodes", static_cast<double>(L.calibrated.interior_nodes)},
               {"interior_area_um2", L.calibrated.interior_area_um2},
               {"M_fitted", L.fit.params[0]},
               {"M_at_bound", L.fit.at_bound[0] ? 1.0 : 0.0},
               {"max_misfit", L.fit.misfit.max_abs},
               {"rms_misfit", L.fit.misfit.rms},
               {"sensitivity_rms_dS_dM", L.fit.sensitivity_rms[0]},
               {"sensitivity_max_dS_dM", L.fit.sensitivity_max[0]},
               {"width_M_for_0.001", L.fit.width(0, 1e-3)},
               {"gn_standard_error_M", L.fit.gn_standard_error[0]},
               {"model_runs", static_cast<double>(L.runs)},
               {"max_misfit_M1", L.plain_misfit.max_abs},
               {"rms_misfit_M1", L.plain_misfit.rms},
               {"max_misfit_3d_cell", L.cell_misfit.max_abs},
               {"max_misfit_3d_cell_M1", L.cell_plain_misfit.max_abs},
               {"balance_residual", L.calibrated.balance_residual},
               {"max_step_balance_residual", L.calibrated.max_step_residual},
               {"run_wall_time_s", L.calibrated.wall_s},
               {"wall_time_s", L.wall_s},
               {"error", L.fit.misfit.max_abs}});
}

void add_level_metrics(io::ResultRecord& rec, const Level& L, double curve_tolerance, const std::string& reason) {
  const std::string tag = fmt("h%.2f", L.h);
  if (curve_tolerance > 0.0)
    rec.add_metric({"max_misfit_" + tag, "max |S_2D - S_ref,planar| over the transient at the fitted M, h = " +
                        fmt("%.2f um", L.h), "", L.fit.misfit.max_abs, curve_tolerance, 0.0, io::Comparison::at_most,
                    reason});
  rec.add_metric({"fit_is_minimum_" + tag,
                  "min(RMS(M - 0.02), RMS(M + 0.02)) - RMS(M) (linearised; >= 0 at a minimum, one side at a bound)",
                  "", std::min(L.fit.at_bound[0] ? 1.0 : L.rms_minus, L.rms_plus) - L.fit.misfit.rms, -1e-6, 0.0,
                  io::Comparison::at_least, "Brent must end at a (constrained) minimum of the RMS misfit"});
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
  rec.add_series(curve_series("S(t) calibrated, " + h, "2D calibrated (M = " + fmt("%.3f", L.fit.params[0]) +
                                                             ") vs planar resolved reference", ref, L.calibrated.S));
  rec.add_series(curve_series("S(t) M = 1, " + h, "2D uncalibrated (M = 1) vs planar resolved reference", ref,
                              L.plain.S));
  rec.add_series(curve_series("S(t) vs 3D cell, " + h, "2D calibrated vs the 3D (axisymmetric) cell: model-form gap",
                              cell, L.calibrated.S));
}

}  // namespace

TEST(Deoxygenation, CiSubset) {
  vv::Stopwatch clock;
  const auto ref = planar_reference(), cell = cell_reference();
  const Level L = calibrate_level(0.4, ref, cell, kMLower, kMUpper);
  io::ResultRecord rec("validation.deoxygenation_ci", "deoxygenation");
  describe(rec, ref.t.back());
  rec.set_parameter("levels", "h = 0.4 um only (CI subset of validation.deoxygenation)");
  add_level(rec, L);
  add_level_metrics(rec, L, kCiCurveTolerance,
                    "CI regression guard at the coarse lattice (lattice error dominates there; the 0.01 validation "
                    "tolerance is asserted by validation.deoxygenation at h = 0.1 um)");
  add_curves(rec, ref, cell, L);
  rec.set_wall_time(clock.seconds());
  std::printf("written: %s\n", rec.write_to_results_dir().c_str());
  for (const auto& m : rec.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}

// Finest level (each run costs ~16 runs at 0.2 um, ~2.5 CPU-min): instead of a full Brent fit, a
// three-point bracket test of the h = 0.2 um fit M2: RMS misfit at M2 and at M2·(1 ± 2 %) (only
// M2 and M2·1.02 when M2·0.98 < 1, the lower bound). If RMS(M2) is the smallest, the minimiser
// at h = 0.1 um lies within ±2 % of M2 (the RMS misfit is unimodal in M: S(t) is monotone in M),
// i.e. the resolution requirement holds; the parabola through the points (or the bound) estimates M.
struct BracketTest {
  std::vector<double> M, rms, max_abs;
  double M_estimate = 0.0;
  bool minimum_inside = false;
  deoxy::Result at_M2, at_1;
  bool have_1 = false;
  double wall_s = 0.0;
};

BracketTest bracket_test(double h, const vv::Curve& ref, double M2) {
  vv::Stopwatch clock;
  BracketTest b;
  deoxy::Setup base;
  base.h_um = h;
  base.dt_s = deoxy::diffusive_dt(h);
  base.t_end_s = ref.t.back();
  std::vector<double> Ms;
  if (0.98 * M2 >= kMLower) Ms.push_back(0.98 * M2);
  Ms.push_back(M2);
  Ms.push_back(1.02 * M2);
  for (double M : Ms) {
    deoxy::Setup s = base;
    s.hb.M = M;
    const auto r = deoxy::run(s);
    const auto m = vv::curve_misfit(r.S, ref);
    b.M.push_back(M);
    b.rms.push_back(m.rms);
    b.max_abs.push_back(m.max_abs);
    if (M == M2) b.at_M2 = r;
    if (M == 1.0) {
      b.at_1 = r;
      b.have_1 = true;
    }
    std::printf("h = %.2f um: M = %.4f rms %.5f max %.5f (%.0f s)\n", h, M, m.rms, m.max_abs, r.wall_s);
    std::fflush(stdout);
  }
  const std::size_t i2 = Ms.size() == 3 ? 1 : 0;  // index of M2
  b.minimum_inside = true;
  for (std::size_t k = 0; k < Ms.size(); ++k)
    if (b.rms[k] < b.rms[i2]) b.minimum_inside = false;
  if (Ms.size() == 3) {  // vertex of the parabola through the three points (equal spacing d)
    const double d = 0.02 * M2, den = b.rms[0] - 2.0 * b.rms[1] + b.rms[2];
    b.M_estimate = den > 0.0 ? M2 + 0.5 * d * (b.rms[0] - b.rms[2]) / den : M2;
  } else {
    b.M_estimate = M2;  // minimiser on the bound M = 1 (one-sided slope > 0)
  }
  b.wall_s = clock.seconds();
  return b;
}

TEST(Deoxygenation, FullStudy) {
  vv::Stopwatch clock;
  const auto ref = planar_reference(), cell = cell_reference();
  std::vector<Level> levels;
  levels.push_back(calibrate_level(0.4, ref, cell, kMLower, kMUpper));
  levels.push_back(calibrate_level(0.2, ref, cell, kMLower, kMUpper));
  std::fflush(stdout);
  const double M2 = levels[1].fit.params[0];
  const BracketTest fine = bracket_test(0.1, ref, M2);

  io::ResultRecord rec("validation.deoxygenation", "deoxygenation");
  describe(rec, ref.t.back());
  rec.set_parameter("levels", "h = 0.4, 0.2 um: Brent fit; h = 0.1 um: three-point bracket test of the 0.2 um fit "
                              "(dt = 40, 10, 2.5 us)");
  io::Series mh;
  mh.name = "fitted M vs h";
  mh.title = "calibrated rate modifier M against lattice spacing (0.1 um: bracket-test estimate)";
  mh.xlabel = "h (um)";
  mh.ylabel = "M";
  for (const auto& L : levels) {
    add_level(rec, L);
    add_level_metrics(rec, L, 0.0, "");  // balance and fit quality; misfits in /runs
    add_curves(rec, ref, cell, L);
    mh.x.push_back(L.h);
    mh.y.push_back(L.fit.params[0]);
  }
  mh.x.push_back(0.1);
  mh.y.push_back(fine.M_estimate);
  rec.add_series(mh);
  for (std::size_t k = 0; k < fine.M.size(); ++k)
    rec.set_parameter(fmt("bracket_h0.10_M%.4f", fine.M[k]),
                      fmt("rms %.6f, ", fine.rms[k]) + fmt("max %.6f", fine.max_abs[k]));
  rec.set_parameter("bracket_h0.10_wall_time_s", fine.wall_s);
  rec.add_series(curve_series("S(t) at M(0.2 um), h = 0.10 um", "2D at the 0.2 um fit vs planar resolved reference",
                              ref, fine.at_M2.S));
  rec.add_series(curve_series("S(t) vs 3D cell, h = 0.10 um", "2D at the 0.2 um fit vs the 3D cell", cell,
                              fine.at_M2.S));
  const std::size_t i2 = fine.M.size() == 3 ? 1 : 0;
  rec.add_metric({"max_misfit_h0.10", "max |S_2D - S_ref,planar| at h = 0.1 um, M = M(0.2 um)", "",
                  fine.max_abs[i2], kCurveTolerance, 0.0, io::Comparison::at_most,
                  "issue 7 validation tolerance 0.01 in S: 1.3 % of the drop S0 - S_f = 0.79, fifty times the "
                  "reference's numerical error (Richardson < 2e-4); asserted at the finest lattice (coarser: /runs)"});
  rec.add_metric({"misfit_decreases_with_h", "1 if the max misfit falls with every refinement 0.4 > 0.2 > 0.1 um",
                  "", (levels[1].fit.misfit.max_abs < levels[0].fit.misfit.max_abs &&
                       fine.max_abs[i2] < levels[1].fit.misfit.max_abs) ? 1.0 : 0.0, 1.0, 0.0,
                  io::Comparison::at_least,
                  "the coarse-level misfit is lattice error (interior mask, D2Q5 at tau = 2.6): it must shrink with h"});
  rec.add_metric({"M_within_2pct_h0.2_h0.1",
                  "1 if RMS misfit at h = 0.1 um is smallest at M(0.2 um) among M(0.2 um)(1 +- 2 %) (bound: 1)", "",
                  fine.minimum_inside ? 1.0 : 0.0, 1.0, 0.0, io::Comparison::at_least,
                  "issue 7: the fitted M changes by < 2 % between 0.2 and 0.1 um (unimodal misfit: bracket test)"});
  rec.add_metric({"o2_balance_h0.10", "|released - (change in lattice O2 - boundary inflow)| / released", "",
                  std::abs(fine.at_M2.balance_residual), kBalanceTolerance, 0.0, io::Comparison::at_most,
                  "exact discrete balance (eq T5) summed over all steps: round-off only"});
  rec.set_wall_time(clock.seconds());
  std::printf("M(0.1 um) estimate %.4f, minimum inside %d\n", fine.M_estimate, static_cast<int>(fine.minimum_inside));
  std::printf("written: %s\n", rec.write_to_results_dir().c_str());
  for (const auto& m : rec.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}
