// validation.deoxygenation_3d (full) and validation.deoxygenation_3d_ci (CI): the 2D section
// model of a still biconcave RBC against the REAL cell, the 3D axisymmetric Evans–Fung cell
// resolved with local Hb–O2 kinetics (reference_rbc.py, reference_S.csv; issue 7 item 9).
// docs/validation-deoxygenation.md, "Calibration against the 3D cell".
//
// The rate modifier M alone leaves a max misfit of 0.066 to the 3D cell at any M
// (validation.deoxygenation): the gap is geometric. The 2D model is a planar prism whose O2
// escapes by 2D diffusion; the real cell is a body of revolution whose medium diffusion is 3D
// (steady escape resistance ln(R/a)/(2πD) per unit length against (1/a − 1/R)/(4πD)). So the
// calibration has two stages, each with one well-determined parameter:
//   1. M against the planar section (what M is for: one lumped S instead of local kinetics;
//      the fit of validation.deoxygenation, repeated here at each level);
//   2. at that M, a geometric closure β = D_out,eff / D_out: an effective medium O2
//      diffusivity standing for the missing third dimension of the escape, fitted against
//      the 3D cell on the norm (max |ΔS| over the transient).
// A joint fit of (M, β) is ill-posed: along the valley M trades against β (parameter
// correlation 0.996 in RMS; M from 0.45 to 1.0 changes the RMS by 1e-5), so M would not be
// resolution-independent. The joint fit is run once, at the coarsest level, to show that
// freeing M does not lower the closure's floor: the remaining gap is geometric, not kinetic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <future>
#include <memory>
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

// Issue 7 item 9: the calibrated curve matches the 3D cell within 0.01 in S over the whole
// transient (S falls by 0.79); the reference's own error (Richardson, PROVENANCE.md) is 1.5e-4.
// Not reached by the 2D planar model (measured floor ≈ 0.011 at every level, docs): asserted
// below as a documented difference, so a model that does reach it makes the case fail and the
// documentation be revisited.
constexpr double kCurveTolerance = 0.01;
// Freeing M on top of β lowers the closure's max misfit by less than this fraction: the gap
// is not kinetic (measured 0.4 % at h = 0.4 um: 0.01067 against 0.01072; the joint simplex
// stops at 0.2 % in x).
constexpr double kJointGainLimit = 0.05;
// Stage 1 (planar, RMS): the bracket, sensitivity step and warm bracket of validation.deoxygenation
// (deoxy_case.hpp), warm from the second level on (that case: from the third).
using deoxy::kBalanceTolerance;
using deoxy::kChangeTolerance;
using deoxy::kFdLnM;
using deoxy::kLnMLower;
using deoxy::kLnMUpper;
using deoxy::kWarmHalfBracket;
// Stage 2 (3D cell, max norm): β ∈ [1, 3] on the coarsest level (β = 1: the plain medium,
// 0.066 short; a probe grid put the best β near 1.5), β(previous level)·e^{±0.25} after it (kWarmHalfBracket).
const double kLnBetaLower = 0.0, kLnBetaUpper = std::log(3.0);
constexpr double kFdLnBeta = 0.01;
// Tolerances in ln p (≈ relative in p): 0.1 % where the change is asserted, coarser below.
constexpr double kFineTolerance = 1e-3;


struct Level {
  double h = 0.0, dt = 0.0, wall_s = 0.0;
  deoxy::Fit planar;          // stage 1: x = ln M against the planar section (RMS)
  deoxy::Fit closure;         // stage 2: x = ln β against the 3D cell at M = planar.value (max)
  deoxy::Result calibrated;   // the run at (M, β)
  vv::Misfit cell_misfit;     // of that run against the 3D cell
  int runs = 0;
};

bool at_minimum(const deoxy::Fit& f) {
  // Off the bracket's edges, and the linearised norm at x ± δ not below the fit's.
  return !f.r.at_bound[0] && std::min(f.norm_minus, f.norm_plus) >= f.r.objective - 1e-6;
}

const deoxy::PointOf kPointM = [](double x) { return std::make_pair(std::exp(x), 1.0); };

// Stage 2 at the stage-1 M of the level, and the calibrated run; `closure` fits x = ln β.
Level closure_level(const deoxy::StageOneLevel& stage, deoxy::Runner& cell_run, const vv::Curve& cell,
                    const std::function<deoxy::Fit(const deoxy::PointOf&)>& closure) {
  vv::Stopwatch clock;
  Level L;
  L.h = stage.h;
  L.dt = stage.dt;
  L.planar = stage.planar;
  const double M = L.planar.value;
  L.closure = closure([M](double x) { return std::make_pair(M, std::exp(x)); });
  L.calibrated = cell_run.at(M, L.closure.value);
  L.cell_misfit = vv::curve_misfit(L.calibrated.S, cell);
  L.runs = cell_run.runs();
  L.wall_s = clock.seconds();
  std::printf("h = %.2f um: M = %.4f (planar rms %.5f), beta = %.4f (D_eff %.0f um^2/s, bound %d): 3D max %.5f rms "
              "%.5f; %d runs, %.0f s\n",
              L.h, M, L.planar.r.misfit.rms, L.closure.value, L.closure.value * cell_run.base().D_out,
              static_cast<int>(L.closure.r.at_bound[0]), L.cell_misfit.max_abs, L.cell_misfit.rms, L.runs, L.wall_s);
  std::fflush(stdout);
  return L;
}


// The joint fit of (ln M, ln β) on the max norm (Nelder–Mead from the two-stage point, steps of
// 10 % of the box): how far does freeing M lower the closure's floor?
struct JointFit {
  vv::CalibrationResult r;
  double correlation = 0.0;  // of the two parameters' Gauss–Newton estimates
  int runs = 0;
  double wall_s = 0.0;
};

// Covariance of the Gauss–Newton estimates ∝ (JᵀJ)⁻¹ = [a11, −a01; −a01, a00] / det, so the
// correlation is −a01 / √(a00 a11), a_ij = Σ_k J_ki J_kj. |r| → 1: the curve fixes one
// combination of ln M and ln β and hardly the other.
double parameter_correlation(const vv::CalibrationResult& f) {
  double a00 = 0.0, a01 = 0.0, a11 = 0.0;
  for (const auto& row : f.jacobian) {
    a00 += row[0] * row[0];
    a01 += row[0] * row[1];
    a11 += row[1] * row[1];
  }
  return -a01 / std::sqrt(a00 * a11);
}

JointFit joint_fit(deoxy::Runner& run, const vv::Curve& cell, const Level& start) {
  vv::Stopwatch clock;
  const int runs0 = run.runs();
  const vv::CurveModel model = [&](const std::vector<double>& p) {
    return run.at(std::exp(p[0]), std::exp(p[1]), 0).S;
  };
  const std::vector<vv::ParameterBound> box{{"lnM", kLnMLower, kLnMUpper, start.planar.r.params[0]},
                                            {"lnBeta", kLnBetaLower, kLnBetaUpper, start.closure.r.params[0]}};
  vv::CalibrationOptions opt;
  opt.norm = vv::MisfitNorm::max_abs;
  opt.x_tolerance = 2e-3;
  // relative to each range: ± 0.01 in ln β and ± 0.04 in ln M (only the correlation uses it)
  opt.fd_relative_step = kFdLnBeta / (kLnBetaUpper - kLnBetaLower);
  opt.max_evaluations = 150;
  opt.prefetch = [&run](const std::vector<std::vector<double>>& ps) {
    std::vector<std::pair<double, double>> points;
    for (const auto& p : ps) points.emplace_back(std::exp(p[0]), std::exp(p[1]));
    run.prefetch(points, 0);
  };
  JointFit j;
  j.r = vv::calibrate(model, cell, box, opt);
  j.correlation = parameter_correlation(j.r);
  j.runs = run.runs() - runs0;
  j.wall_s = clock.seconds();
  std::printf("h = %.2f um joint (M, beta): M = %.4f beta = %.4f, max %.5f rms %.5f, correlation %.3f, %d runs, %.0f s\n",
              start.h, std::exp(j.r.params[0]), std::exp(j.r.params[1]), j.r.misfit.max_abs, j.r.misfit.rms,
              j.correlation, j.runs, j.wall_s);
  return j;
}

void describe(io::ResultRecord& rec, double t_end) {
  rec.set_requirement(
      "The 2D lattice model of a still biconcave RBC (ONE cell-averaged Hb-O2 saturation, D2Q5 O2 transport), with "
      "its rate modifier M calibrated against the planar section and a geometric closure beta (effective medium "
      "diffusivity beta*D_out for the third dimension of the escape) calibrated against the real 3D (axisymmetric) "
      "cell, reproduces the 3D cell's saturation S(t) within 0.01 over the whole transient (issue 7 item 9), with "
      "both parameters resolution-independent (change < 2 % between the two finest levels). Measured: the "
      "parameters converge, the 0.01 match is NOT reached (floor ~0.011, geometric): a documented difference.");
  rec.set_reference(
      "reference_data/deoxygenation/reference_rbc.py (PROVENANCE.md): the Evans-Fung cell of revolution in a "
      "cylinder r <= 6, |z| <= 6 um held at 20 uM, finite volumes + BDF2 + Newton, local Hb-O2 kinetics (k_off = 44 "
      "1/s, P50 = 26.8 Torr, n = 2.7, heme 20.3 mM), D_O2 950 (in) / 2800 (out) um^2/s; reference_S.csv (3D), "
      "reference_S_planar.csv (--planar, stage 1), each converged to < 2e-4 in S. Thesis ch. V, Figs V-2, V-3.");
  rec.set_parameter("geometry", "2D: square box of half-width 6 um held at 20 uM; the Evans-Fung section (a = 3.91 "
                                "um) as an area-fraction mask");
  rec.set_parameter("stage_1", "the fits of validation.deoxygenation (shared, deoxy_case.hpp): ln M against the planar "
                               "section, RMS; Brent on M in [0.05, 4] at 0.4 um (tolerance 0.01 in ln M; CI 0.02) and 0.3 "
                               "um (1e-3), continuation from the previous level (Gauss-Newton, vv::refine_1d) within "
                               "M(previous) * e^(+-0.25) at 0.2 and 0.15 um (1e-3)");
  rec.set_parameter("stage_2", "at that M, ln beta against the 3D cell, max |dS| (the issue's norm): Brent on beta in "
                               "[1, 3] at the coarsest level (tolerance 2e-3; CI 5e-3), continuation from the previous "
                               "level within beta(previous) * e^(+-0.25) after it (the exact minimum of the linearised "
                               "max norm; tolerance 2e-3 at 0.3 um, 1e-3 where the change is asserted); D_out,eff = "
                               "beta * 2800 um^2/s in the medium and in the membrane's face tensor");
  rec.set_parameter("lattice", "TRT Lambda = 1/4, outflow coupling, mean P by eq T7, face subpixel tensor at the "
                               "membrane, dt = 2.5 us (h/0.2 um)^2 (the set-up of validation.deoxygenation)");
  rec.set_parameter("t_end_s", t_end);
}

void add_level(io::ResultRecord& rec, const Level& L) {
  rec.add_run({{"h_um", L.h},
               {"dt_us", L.dt * 1e6},
               {"nodes_per_side", static_cast<double>(L.calibrated.nodes)},
               {"M_fitted_planar", L.planar.value},
               {"rms_misfit_planar", L.planar.r.misfit.rms},
               {"beta_fitted", L.closure.value},
               {"D_out_eff_um2_s", L.closure.value * 2800.0},
               {"beta_at_bound", L.closure.r.at_bound[0] ? 1.0 : 0.0},
               {"max_misfit_3d", L.cell_misfit.max_abs},
               {"rms_misfit_3d", L.cell_misfit.rms},
               {"sensitivity_max_dS_dlnBeta", L.closure.r.sensitivity_max[0]},
               {"sensitivity_rms_dS_dlnBeta", L.closure.r.sensitivity_rms[0]},
               {"relative_width_beta_for_0.001", L.closure.r.width(0, 1e-3)},
               {"brent_evaluations_planar", static_cast<double>(L.planar.r.evaluations)},
               {"brent_evaluations_closure", static_cast<double>(L.closure.r.evaluations)},
               {"model_runs", static_cast<double>(L.runs)},
               {"balance_residual", L.calibrated.balance_residual},
               {"run_wall_time_s", L.calibrated.wall_s},
               {"wall_time_s", L.wall_s},
               {"error", L.cell_misfit.max_abs}},
              L.calibrated.scene_text);
}

void add_level_metrics(io::ResultRecord& rec, const Level& L) {
  const std::string tag = fmt("h%.2f", L.h);
  rec.add_metric({"fits_are_minima_" + tag, "1 if both fits end off their brackets' edges at a minimum", "",
                  at_minimum(L.planar) && at_minimum(L.closure) ? 1.0 : 0.0, 1.0, 0.0, io::Comparison::at_least,
                  "an edge is not a minimum of the misfit (on a warm level it means a change > 22 %)"});
  rec.add_metric({"o2_balance_" + tag, "|released - (change in lattice O2 - boundary inflow)| / released", "",
                  std::abs(L.calibrated.balance_residual), kBalanceTolerance, 0.0, io::Comparison::at_most,
                  "exact discrete balance (eq T5) summed over all steps: round-off only"});
}

io::Series closure_series(const vv::Curve& cell, const Level& L) {
  return deoxy::curve_series("S(t) vs 3D cell, closure, " + fmt("h = %.2f um", L.h),
                             "2D, M = " + fmt("%.3f", L.planar.value) + " (planar fit), beta = " +
                                 fmt("%.3f", L.closure.value) + " (closure) vs the 3D axisymmetric cell",
                             cell, L.calibrated.S);
}

// The regression guard of the closure at the coarse lattice (h = 0.4 um): the CI subset's
// verdict, asserted by the full study on its coarsest level too (which is why the CI subset
// does not run in `full`).
void add_coarse_guard(io::ResultRecord& rec, const Level& L) {
  rec.add_metric({fmt("max_misfit_3d_h%.2f", L.h),
                  "max |S_2D - S_ref,3D| over the transient at (M, beta), h = " + fmt("%.2f um", L.h), "",
                  L.cell_misfit.max_abs, 0.013, 0.0, io::Comparison::at_most,
                  "CI regression guard of the closure at the coarse lattice (measured 0.0107; the M-only "
                  "fit gives 0.066); the full study asserts the resolution checks and records the 0.01 gap"});
}

}  // namespace

// CI subset: the coarsest level, both stages (h = 0.4 um, ≈ 25 runs of ≈ 2 s).
TEST(Deoxygenation3d, CiSubset) {
  vv::Stopwatch clock;
  const auto planar = deoxy::planar_reference(), cell = deoxy::cell_reference();
  // the planar reference runs longer (2.4 s against 1.8 s)
  deoxy::Runner planar_run(deoxy::case_setup(0.4, planar.t.back()), "validation.deoxygenation_3d_ci"),
      cell_run(deoxy::case_setup(0.4, cell.t.back()), "validation.deoxygenation_3d_ci");
  deoxy::StageOneLevel stage;
  stage.h = 0.4;
  stage.dt = deoxy::diffusive_dt(0.4, deoxy::kDtAt0p2);
  stage.planar = deoxy::fit_log(planar_run, planar, "lnM", kPointM, kLnMLower, kLnMUpper, 0.02, vv::MisfitNorm::rms,
                                kFdLnM);
  const Level L = closure_level(stage, cell_run, cell, [&](const deoxy::PointOf& point) {
    return deoxy::fit_log(cell_run, cell, "lnBeta", point, kLnBetaLower, kLnBetaUpper, 5e-3, vv::MisfitNorm::max_abs,
                          kFdLnBeta);
  });
  io::ResultRecord rec("validation.deoxygenation_3d_ci", "deoxygenation");
  describe(rec, cell.t.back());
  rec.set_parameter("levels", "h = 0.4 um only (CI subset of validation.deoxygenation_3d), tolerances 0.02 (ln M), "
                              "0.005 (ln beta)");
  add_level(rec, L);
  add_level_metrics(rec, L);
  add_coarse_guard(rec, L);
  rec.add_series(closure_series(cell, L));
  rec.set_wall_time(clock.seconds());
  std::printf("written: %s\n", rec.write_to_results_dir().c_str());
  for (const auto& m : rec.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}

TEST(Deoxygenation3d, FullStudy) {
  vv::Stopwatch clock;
  const auto planar = deoxy::planar_reference(), cell = deoxy::cell_reference();
  // Stage 1 is validation.deoxygenation's (its fixture, deoxy_case.hpp: the same fits, shared
  // through <results>/deoxygenation_stage1.tsv); computed here only when that file is absent.
  double stage1_wall = 0.0;
  auto stage = deoxy::read_stage1(&stage1_wall);
  const bool shared = !stage.empty();
  if (!shared) {
    auto runners = deoxy::stage1_runners(planar, "validation.deoxygenation_3d");
    stage = deoxy::stage1_fits(runners, planar);
    stage1_wall = clock.seconds();
  }
  ASSERT_EQ(stage.size(), deoxy::kLevels.size()) << deoxy::stage1_path();
  // Stage 2 on the two coarse levels (0.4 and 0.3 um), each warm from the previous level's β; the
  // joint fit at the coarsest level runs beside (lowest priority). The closure was measured at all
  // four levels when written (β 1.5327, 1.5314, 1.5325, 1.5323; floor 0.0107 at each): the planar
  // model's structural floor is resolution-independent from 0.4 um on, and the cell of revolution
  // on the axisymmetric lattice (validation.deoxygenation_axisymmetric) now closes the gap itself,
  // so the finer levels' runs (about 4 minutes) went to that case.
  const std::size_t closure_levels = 2;
  std::vector<std::unique_ptr<deoxy::Runner>> runs;
  for (std::size_t i = 0; i < closure_levels; ++i)
    runs.push_back(std::make_unique<deoxy::Runner>(deoxy::case_setup(stage[i].h, cell.t.back()),
                                                   "validation.deoxygenation_3d", deoxy::level_priority(i)));
  std::vector<Level> levels;
  levels.push_back(closure_level(stage[0], *runs[0], cell, [&](const deoxy::PointOf& point) {
    return deoxy::fit_log(*runs[0], cell, "lnBeta", point, kLnBetaLower, kLnBetaUpper, 2e-3, vv::MisfitNorm::max_abs,
                          kFdLnBeta);
  }));
  auto joint_future = std::async(std::launch::async, [&, start = levels.front()] { return joint_fit(*runs[0], cell, start); });
  for (std::size_t i = 1; i < closure_levels; ++i) {
    const bool asserted = i + 2 >= closure_levels;
    const double x0 = levels.back().closure.r.params[0];
    // on an iterate (almost always the fit): the next level's pair starts, below this level's runs
    const auto on_iterate = [&, i](double x) {
      if (i + 1 >= closure_levels) return;
      const auto [a, b] = deoxy::warm_pair(x, kFdLnBeta);
      const double M_next = stage[i + 1].planar.value;
      runs[i + 1]->prefetch({{M_next, std::exp(a)}, {M_next, std::exp(b)}}, deoxy::level_priority(i) - 5);
    };
    levels.push_back(closure_level(stage[i], *runs[i], cell, [&](const deoxy::PointOf& point) {
      return deoxy::fit_log_warm(*runs[i], cell, "lnBeta", point, x0, asserted ? kFineTolerance : 2e-3,
                                 vv::MisfitNorm::max_abs, kFdLnBeta, -1, on_iterate);
    }));
  }
  const JointFit joint = joint_future.get();
  const Level &L2 = levels[levels.size() - 2], &L1 = levels.back();

  io::ResultRecord rec("validation.deoxygenation_3d", "deoxygenation");
  describe(rec, cell.t.back());
  rec.set_parameter("levels", "h = 0.4, 0.3 um (dt = 10, 5.625 us); stage 1 (M) at 0.4, 0.3, 0.2, 0.15 um in "
                              "validation.deoxygenation, which asserts its resolution independence");
  rec.set_parameter("stage_1_source", shared ? "validation.deoxygenation (" + deoxy::stage1_path() + ")"
                                             : std::string("computed here (no stage-1 file)"));
  rec.set_parameter("stage_1_wall_time_s", stage1_wall);
  rec.set_parameter("workers", static_cast<double>(deoxy::Slots::instance().workers()));
  rec.set_parameter("joint_fit_h0.40", "Nelder-Mead on (ln M, ln beta), max norm, from the two-stage point: M = " +
                                           fmt("%.4f", std::exp(joint.r.params[0])) +
                                           ", beta = " + fmt("%.4f", std::exp(joint.r.params[1])) +
                                           ", max " + fmt("%.5f", joint.r.misfit.max_abs) + ", correlation " +
                                           fmt("%.3f", joint.correlation));
  rec.set_parameter("joint_fit_correlation_h0.40", joint.correlation);
  io::Series mh, bh;
  mh.name = "fitted M vs h (planar stage)";
  mh.title = "rate modifier M (stage 1, planar section) against lattice spacing";
  bh.name = "fitted beta vs h (3D closure)";
  bh.title = "geometric closure beta = D_out,eff / D_out (stage 2, 3D cell) against lattice spacing";
  mh.xlabel = bh.xlabel = "h (um)";
  mh.ylabel = "M";
  bh.ylabel = "beta";
  for (const auto& L : levels) {
    add_level(rec, L);
    add_level_metrics(rec, L);
    rec.add_series(closure_series(cell, L));
    mh.x.push_back(L.h);
    mh.y.push_back(L.planar.value);
    bh.x.push_back(L.h);
    bh.y.push_back(L.closure.value);
  }
  rec.add_series(mh);
  rec.add_series(bh);
  const std::string t1 = fmt("h%.2f", L1.h), t2 = fmt("h%.2f", L2.h);
  const double dM = std::abs(L1.planar.value - L2.planar.value) / L1.planar.value;  // printed only
  const double dB = std::abs(L1.closure.value - L2.closure.value) / L1.closure.value;
  rec.add_metric({"beta_change_" + t2 + "_" + t1, "|beta(0.3 um) - beta(0.4 um)| / beta(0.3 um), stage 2", "",
                  dB, kChangeTolerance, 0.0, io::Comparison::at_most,
                  "the geometric closure must converge with the lattice like M (same 2 %; at all four levels when "
                  "written: 8.5e-4, 7.2e-4, 1.4e-4)"});
  rec.add_metric({"max_misfit_3d_" + t1,
                  "max |S_2D - S_ref,3D| at (M, beta), h = 0.3 um: DOCUMENTED DIFFERENCE, the 0.01 of issue 7 item "
                  "9 is not reached", "", L1.cell_misfit.max_abs, kCurveTolerance, 0.0, io::Comparison::at_least,
                  "measured direction: the 2D planar model with the best constant medium closure stays above 0.01 "
                  "(floor ~0.011 at every level); if a change brings it below, this fails and the docs must change"});
  add_coarse_guard(rec, levels.front());
  const double gain = 1.0 - joint.r.misfit.max_abs / levels.front().cell_misfit.max_abs;
  rec.add_metric({"joint_fit_gain_h0.40", "1 - max(joint (M, beta) fit) / max(two-stage closure), h = 0.4 um", "",
                  gain, kJointGainLimit, 0.0, io::Comparison::at_most,
                  "freeing M on top of beta hardly lowers the floor: the remaining gap to the 3D cell is geometric, "
                  "not kinetic (and M is not identifiable from the 3D curve once beta is free)"});
  rec.set_wall_time(clock.seconds());
  std::printf("M:");
  for (const auto& L : levels) std::printf(" %.4f", L.planar.value);
  std::printf("; beta:");
  for (const auto& L : levels) std::printf(" %.4f", L.closure.value);
  std::printf("; 3D max:");
  for (const auto& L : levels) std::printf(" %.5f", L.cell_misfit.max_abs);
  std::printf("; |dM|/M %.4f, |dbeta|/beta %.4f, joint gain %.3f, wall %.0f s\n", dM, dB, gain, clock.seconds());
  std::printf("written: %s\n", rec.write_to_results_dir().c_str());
  for (const auto& m : rec.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}
