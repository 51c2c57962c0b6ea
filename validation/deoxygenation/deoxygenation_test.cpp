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
#include <future>
#include <map>
#include <utility>
#include <string>
#include <vector>

#include "common/calibration.hpp"
#include "common/case_support.hpp"
#include "deoxy_case.hpp"
#include "io/result_record.hpp"

using namespace erythro;

namespace {

// Validation tolerance of the issue: the calibrated cell-averaged saturation follows the
// reference within 0.01 in S over the whole transient (S falls by ≈ 0.79). The reference's
// own numerical error (Richardson, PROVENANCE.md) is < 2e-4, well inside it.
constexpr double kCurveTolerance = 0.01;
// CI subset at h = 0.4 um (the full study's coarsest level, same Δt rule and representation):
// measured max misfit at the fit 0.0080 (docs); 0.015 guards the coupling/transport/mask
// against regressions (the old ray-cast, τ = 2.6 set-up gave 0.026) without claiming validation.
constexpr double kCiCurveTolerance = 0.015;
// Asserted by the CI subset and, at its coarsest level, by the full study too (which is why
// the CI subset does not run in `full`).
constexpr const char* kCiGuardReason =
    "CI regression guard at the coarse lattice (0.008 measured; the 0.01 validation tolerance and the 2 % "
    "resolution check are asserted by validation.deoxygenation at the finest levels)";
// The 3D cell is not reachable by any M (the gap is geometric: planar vs revolved diffusion).
// The best free-M fit to the 3D curve must stay far outside the validation tolerance
// (measured 0.066 at h = 0.4, 0.3 um); 0.05 = five times the tolerance, while the planar fit meets 0.01.
constexpr double kGeometricGapFloor = 0.05;

using deoxy::cell_reference;
using deoxy::planar_reference;

using deoxy::curve_series;
using deoxy::Fit;
using deoxy::fmt;
using deoxy::Runner;

const deoxy::PointOf kPointM = [](double x) { return std::make_pair(std::exp(x), 1.0); };

// Brent on x = ln M ∈ [lo, hi] (β = 1) to |Δ ln M| ≤ tol_lnM (≈ relative tolerance in M), RMS.
Fit fit_lnM(Runner& run, const vv::Curve& ref, double lo, double hi, double tol_lnM, int priority = -1) {
  return deoxy::fit_log(run, ref, "lnM", kPointM, lo, hi, tol_lnM, vv::MisfitNorm::rms, deoxy::kFdLnM, priority);
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

// The rest of a level once its planar fit is known: the calibrated run and its 3D misfit.
void complete_level(Level& L, Runner& run, const vv::Curve& cell) {
  L.calibrated = run.at(L.planar.value);
  L.cell_at_planar_fit = vv::curve_misfit(L.calibrated.S, cell);
  L.runs = run.runs();
}

void describe(io::ResultRecord& rec, double t_end) {
  rec.set_requirement(
      "With one calibrated rate modifier M > 0 (rate k_off/M), the 2D lattice model of a still biconcave RBC (ONE "
      "cell-averaged Hb-O2 saturation, D2Q5 O2 transport) reproduces the cell-averaged saturation S(t) of the same "
      "section resolved with local Hb-O2 kinetics within 0.01 over the whole transient, and M is "
      "resolution-independent (change < 2 % between the two finest lattice levels); the gap to the 3D (axisymmetric) real cell is "
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
  rec.set_parameter("kinetics", "dS/dt = -(k_off/M)[S - (1-S)(P/P50)^n], P = heme-weighted mean over the cell's nodes "
                                "(hb_kinetics.hpp)");
  rec.set_parameter("D_in_um2_s", 950.0);
  rec.set_parameter("D_out_um2_s", 2800.0);
  rec.set_parameter("dt_scaling", "diffusive: dt = 2.5 us (h/0.2 um)^2, tau_out = 1.025, tau_in = 0.678 at every level");
  rec.set_parameter("collision", "TRT, magic parameter Lambda = 1/4 at every node (tau+ = 1/2 + Lambda/(tau- - 1/2), "
                                 "tau- = 1/2 + 3 D), mean P from C + q/(12 D) (transport eq T7: exact steady "
                                 "finite-volume equivalence, harmonic face D)");
  rec.set_parameter("coupling", "cell-implicit with the outflow of the previous step: P_end = P^k - o^(k-1) + (1 + "
                                "kappa) r^k (deoxy_run.hpp); the fitted M no longer depends on dt");
  rec.set_parameter("mask", "area fraction phi of each node's square inside geometry::biconcave(800 markers, a = 3.91 "
                            "um) (exact clipping): heme weight phi, P mean weighted by phi, node 1/D = phi/D_in + "
                            "(1-phi)/D_out, C0 = phi*130 + (1-phi)*20 uM (the reference's volume-fraction mask)");
  rec.set_parameter("interface", "face subpixel tensor (transport eqs T10-T11): on each face's dual cell D_f = "
                                 "<1/D>^-1 n n^T + <D> (I - n n^T) (phi and normal of the dual cell), target face "
                                 "flux K (C_a - C_b) - D_xy (transverse mean difference), imposed on the node-series "
                                 "lattice by a mass-conserving source pair per face (lagged one step)");
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
      {"polygon_area_um2", L.calibrated.polygon_area_um2},
      {"M_fitted", L.planar.value},
      {"M_at_bound", f.at_bound[0] ? 1.0 : 0.0},
      {"max_misfit", f.misfit.max_abs},
      {"rms_misfit", f.misfit.rms},
      {"sensitivity_rms_dS_dlnM", f.sensitivity_rms[0]},
      {"sensitivity_max_dS_dlnM", f.sensitivity_max[0]},
      {"sensitivity_rms_dS_dM", f.sensitivity_rms[0] / L.planar.value},
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
    row["M_fitted_3d_cell"] = L.cell.value;
    row["M_3d_at_bound"] = L.cell.r.at_bound[0] ? 1.0 : 0.0;
    row["max_misfit_3d_cell_fit"] = L.cell.r.misfit.max_abs;
    row["rms_misfit_3d_cell_fit"] = L.cell.r.misfit.rms;
  }
  rec.add_run(row, L.calibrated.scene_text);
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
                  "bound)", "", std::min(f.r.at_bound[0] ? 1.0 : f.norm_minus, f.norm_plus) - f.r.misfit.rms, -1e-6,
                  0.0, io::Comparison::at_least, "Brent must end at a (constrained) minimum of the RMS misfit"});
  rec.add_metric({"o2_balance_" + tag, "|released - (change in lattice O2 - boundary inflow)| / released", "",
                  std::abs(L.calibrated.balance_residual), deoxy::kBalanceTolerance, 0.0, io::Comparison::at_most,
                  "exact discrete balance (eq T5) summed over all steps: round-off only"});
}


void add_curves(io::ResultRecord& rec, const vv::Curve& ref, const vv::Curve& cell, const Level& L) {
  const std::string h = fmt("h = %.2f um", L.h);
  rec.add_series(curve_series("S(t) calibrated, " + h, "2D calibrated (M = " + fmt("%.3f", L.planar.value) +
                                                             ") vs planar resolved reference", ref, L.calibrated.S));
  rec.add_series(curve_series("S(t) vs 3D cell, " + h, "2D at the planar fit vs the 3D (axisymmetric) cell: "
                                                       "model-form gap", cell, L.calibrated.S));
}

}  // namespace

TEST(Deoxygenation, CiSubset) {
  vv::Stopwatch clock;
  const auto ref = planar_reference(), cell = cell_reference();
  Runner run(deoxy::case_setup(0.4, ref.t.back()), "validation.deoxygenation_ci");
  Level L;
  L.h = 0.4;
  L.dt = deoxy::diffusive_dt(L.h, deoxy::kDtAt0p2);
  L.planar = fit_lnM(run, ref, deoxy::kLnMLower, deoxy::kLnMUpper, 0.02);
  complete_level(L, run, cell);
  L.wall_s = clock.seconds();
  io::ResultRecord rec("validation.deoxygenation_ci", "deoxygenation");
  describe(rec, ref.t.back());
  rec.set_parameter("levels", "h = 0.4 um only (CI subset of validation.deoxygenation), dt = 10 us, tolerance 0.02 in ln M");
  add_level(rec, L);
  add_level_metrics(rec, L, kCiCurveTolerance, kCiGuardReason);
  add_curves(rec, ref, cell, L);
  rec.set_wall_time(clock.seconds());
  std::printf("written: %s\n", rec.write_to_results_dir().c_str());
  for (const auto& m : rec.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}

// The calibrated RMS misfit is the model-form floor (one lumped S against local kinetics)
// once lattice error is below it; measured with this set-up at every level (0.4–0.15 µm).
// Lattice error under control = the calibrated RMS misfit at each level within 5 % of that
// at the finest level (docs/validation-deoxygenation.md,
// "The misfit is the model-form floor at every level").
constexpr double kFloorSpread = 0.05;

TEST(Deoxygenation, FullStudy) {
  vv::Stopwatch clock;
  const auto ref = planar_reference(), cell = cell_reference();
  // Stage 1 (deoxy_case.hpp: Brent at 0.4 and 0.3 um, continuation at 0.2 and 0.15 um) and, on
  // the same runners and concurrently, the free-M fits to the 3D cell and the M = 1 runs of the
  // two coarse levels (priority below the stage-1 chain, which is the critical path).
  auto runners = deoxy::stage1_runners(ref, "validation.deoxygenation");
  std::vector<Level> levels(deoxy::kLevels.size());
  std::vector<std::future<void>> extras;
  for (std::size_t i = 0; i < 2; ++i) {
    runners[i]->prefetch({{1.0, 1.0}}, 10);
    extras.push_back(std::async(std::launch::async, [&, i] {
      levels[i].cell = fit_lnM(*runners[i], cell, deoxy::kLnMLower, deoxy::kLnMUpper, 0.01, 10);
      std::printf("h = %.2f um 3D cell: M = %.4f (bound %d), max %.5f rms %.5f; %.0f s\n", deoxy::kLevels[i],
                  levels[i].cell.value, static_cast<int>(levels[i].cell.r.at_bound[0]), levels[i].cell.r.misfit.max_abs,
                  levels[i].cell.r.misfit.rms, levels[i].cell.wall_s);
    }));
  }
  // The fixed-M run on the second-finest level (below) is at the finest fit's M: started as soon
  // as the finest level's iterate is known (almost always the fit itself), beside its run.
  Runner& second = *runners[levels.size() - 2];
  const auto stage = deoxy::stage1_fits(runners, ref, [&second](double M) {
    second.prefetch({{M, 1.0}}, deoxy::level_priority(deoxy::kLevels.size() - 1) - 5);
  });
  for (auto& e : extras) e.get();
  const double stage1_wall = clock.seconds();
  for (std::size_t i = 0; i < levels.size(); ++i) {
    Level& L = levels[i];
    L.h = stage[i].h;
    L.dt = stage[i].dt;
    L.planar = stage[i].planar;
    L.wall_s = stage[i].wall_s;
    if (i < 2) {
      L.plain_misfit = vv::curve_misfit(runners[i]->at(1.0).S, ref);
      L.has_plain = true;
    }
  }
  const Level &L2 = levels[levels.size() - 2], &L1 = levels.back();

  // Curve change between the two finest levels at FIXED M = M(finest): what moves the fit.
  // Linearised shift of ln M it implies: −J·Δr / J·J (J of the finest fit).
  for (std::size_t i = 0; i < levels.size(); ++i) complete_level(levels[i], *runners[i], cell);
  const auto r_fine = vv::residuals(L1.calibrated.S, ref), r_second = vv::residuals(second.at(L1.planar.value).S, ref);
  double dd = 0.0, jd = 0.0, jj = 0.0;
  for (std::size_t k = 0; k < r_fine.size(); ++k) {
    const double d = r_second[k] - r_fine[k], j = L1.planar.r.jacobian[k][0];
    dd += d * d;
    jd += j * d;
    jj += j * j;
  }
  const double curve_change_rms = std::sqrt(dd / static_cast<double>(r_fine.size()));
  const double predicted_dlnM = -jd / jj;
  std::printf("fixed-M curve change %.2f -> %.2f um: RMS %.2e, linearised ln M shift %.4f\n", L2.h, L1.h,
              curve_change_rms, predicted_dlnM);

  // Stage 1 for validation.deoxygenation_3d (its fixture: ctest runs this case first).
  deoxy::write_stage1(stage, stage1_wall);

  io::ResultRecord rec("validation.deoxygenation", "deoxygenation");
  describe(rec, ref.t.back());
  rec.set_parameter("levels", "h = 0.4, 0.3, 0.2, 0.15 um (dt = 10, 5.625, 2.5, 1.406 us); 0.4, 0.3 um: Brent on ln M "
                              "over [ln 0.05, ln 4] (tolerance 0.01, 1e-3), 3D-cell fits (tolerance 0.01); 0.2, "
                              "0.15 um: continuation from the previous level's fit, Gauss-Newton with the central-"
                              "difference Jacobian at it (vv::refine_1d) within ln M(previous level) +- 0.25 "
                              "(tolerance 1e-3)");
  rec.set_parameter("workers", static_cast<double>(deoxy::Slots::instance().workers()));
  rec.set_parameter("curve_change_fixed_M_rms", curve_change_rms);
  rec.set_parameter("curve_change_fixed_M_predicted_dlnM", predicted_dlnM);
  io::Series mh;
  mh.name = "fitted M vs h";
  mh.title = "calibrated rate modifier M against lattice spacing (planar reference)";
  mh.xlabel = "h (um)";
  mh.ylabel = "M";
  for (const auto& L : levels) {
    add_level(rec, L);
    // Balance and fit quality; the curve misfit as the CI guard at the coarsest level (h = 0.4 um),
    // the others in /runs and below.
    const bool coarsest = &L == &levels.front();
    add_level_metrics(rec, L, coarsest ? kCiCurveTolerance : 0.0, coarsest ? kCiGuardReason : "");
    add_curves(rec, ref, cell, L);
    mh.x.push_back(L.h);
    mh.y.push_back(L.planar.value);
  }
  rec.add_series(mh);
  // For the report: O2 around the cell 0.1 s into the release (S = 0.74 in the planar reference), at h = 0.2 um and
  // that level's fitted M; the membrane drawn on top.
  deoxy::Setup picture = deoxy::case_setup(0.2, ref.t.back());
  picture.hb.M = levels[2].planar.value;
  for (const io::FieldPicture& p : deoxy::transient_pictures(picture, 0.1, "validation.deoxygenation", "t = 0.1 s"))
    rec.add_field(p);
  const std::string t1 = fmt("h%.2f", L1.h), t2 = fmt("h%.2f", L2.h);
  rec.add_metric({"max_misfit_" + t1, "max |S_2D - S_ref,planar| over the transient at the fitted M, finest level", "",
                  L1.planar.r.misfit.max_abs, kCurveTolerance, 0.0, io::Comparison::at_most,
                  "issue 7 validation tolerance 0.01 in S: 1.3 % of the drop S0 - S_f = 0.79, fifty times the "
                  "reference's numerical error (Richardson < 2e-4); asserted at the finest lattice (coarser: /runs)"});
  const double dM = std::abs(L1.planar.value - L2.planar.value) / L1.planar.value;
  rec.add_metric({"M_change_" + t2 + "_" + t1, "|M(finest) - M(second finest)| / M(finest), both fitted to 1e-3 in ln M", "", dM,
                  deoxy::kChangeTolerance, 0.0, io::Comparison::at_most,
                  "issue 7: the fitted M is resolution-independent, change < 2 % between the two finest levels (fit "
                  "tolerance 1e-3 in ln M, i.e. 0.1 % in M)"});
  double spread = 0.0;
  for (const auto& L : levels)
    spread = std::max(spread, std::abs(L.planar.r.misfit.rms - L1.planar.r.misfit.rms) / L1.planar.r.misfit.rms);
  rec.add_metric({"misfit_floor_spread", "max over levels |RMS_fit(h) - RMS_fit(finest)| / RMS_fit(finest)", "",
                  spread, kFloorSpread, 0.0, io::Comparison::at_most,
                  "replaces 'misfit decreases with h': with the area-fraction cell and tau_out = 1.025 the calibrated "
                  "misfit is the model-form floor (one lumped S vs local kinetics) at EVERY level, 0.4 um included, "
                  "so it cannot decrease; lattice error under control = the floor reached within 5 % at every level"});
  rec.add_metric({"best_3d_misfit_h0.30", "max |S_2D - S_ref,3D| at the free-M fit to the 3D cell, h = 0.3 um", "",
                  levels[1].cell.r.misfit.max_abs, kGeometricGapFloor, 0.0, io::Comparison::at_least,
                  "the 2D-vs-3D gap is geometric (planar vs revolved O2 diffusion), not kinetic: no M closes it, "
                  "while the planar fit meets 0.01; measured direction, recorded difference"});
  rec.set_wall_time(clock.seconds());
  std::printf("M:");
  for (const auto& L : levels) std::printf(" %.4f", L.planar.value);
  std::printf(", |dM|/M(finest) = %.4f, wall %.0f s\n", dM, clock.seconds());
  std::printf("written: %s\n", rec.write_to_results_dir().c_str());
  for (const auto& m : rec.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}
