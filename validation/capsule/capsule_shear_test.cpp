// Cases validation.capsule_shear (full tier) and validation.capsule_shear_ci (CI)
// (issue 4 items 7, 8, 10).
//
// Requirement: a circular neo-Hookean capsule (no bending, no prestress) in simple
// shear reaches the steady Taylor deformation D and inclination θ of the Re = 0,
// unbounded 2D boundary-integral reference (D within 0.01, θ within 2°) once the
// lattice results are extrapolated to a/h → ∞ (Richardson), Re → 0 and a large domain.
// Reference: docs/validation-capsule.md, "Reference" (2D Stokes boundary integrals,
// converged to 1e−6 in D); published comparison Breyiannis & Pozrikidis 2000,
// Theor Comput Fluid Dyn 13:327.
//
// Measured ingredients (all cosine4 = thesis kernel, eq 24, unless named):
//  1. resolution study at Re = 0.1, H = L_x = 16a: a/h = 6, 8, 12, 16, 24 (G ≥ 0.05) or
//     6, 8, 12, 16 (G < 0.05) → Richardson over the three finest levels;
//  2. inertia: a/h = 6 at Re = 0.05 and 0.025 → linear extrapolation to Re = 0
//     (the shift is linear in Re: measured D(0.1) − D(0.05) ≈ 2 [D(0.05) − D(0.025)]);
//  3. domain: a/h = 6, Re = 0.025, H = L_x = 32a against 16a (confinement by the
//     walls raises D, periodic images along x lower it; their sum is applied);
//  D_est = D_Rich + [D_Re→0 − D_Re=0.1](a/h = 6) + [D_32a − D_16a](a/h = 6, Re = 0.025),
//  the corrections being taken as additive (each is measured at the coarse level).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "capsule_run.hpp"
#include "common/case_support.hpp"
#include "common/concurrent_runs.hpp"
#include "common/convergence.hpp"
#include "richardson.hpp"

using namespace erythro;

namespace {

struct Reference {
  double G, D, theta;
};
// docs/validation-capsule.md, "Reference" table.
constexpr Reference kReference[] = {{0.01, 0.1630, 36.0}, {0.02, 0.2044, 33.8}, {0.05, 0.2748, 30.4}, {0.1, 0.3423, 27.4}};
// a/h levels (issue 4 item 7: about 6 to 24): five for the two largest G, four for the
// smaller G, whose a/h = 24 runs would double the case's time (their a/h = 16 level
// already changes D by < 1e-3 from the a/h = 12 level).
const std::vector<double> kLevelsLargeG = {6, 8, 12, 16, 24};
const std::vector<double> kLevelsSmallG = {6, 8, 12, 16};
const std::vector<double> kOtherKernelLevels = {6, 8, 12};  // peskin4, roma3, linear2 at G = 0.1

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

struct Bookkeeping {
  io::ResultRecord& record;
  int capped = 0;         // runs that reached the strain cap before the drift criterion
  double max_area = 0;    // max |A/A0 − 1|
  double t_ib = 0, t_fluid = 0, marker_steps = 0, node_steps = 0;
  double t_forces = 0, t_zero = 0, t_spread = 0, t_moments = 0, t_move = 0;
  std::vector<double> run_markers = {}, run_marker_us = {};  // marker work per step (µs) against marker count

  std::map<std::string, vv::CapsuleResult> prefetched = {};  // results of prefetch(), by label

  static std::string label_of(const vv::CapsuleConfig& c, const std::string& role) {
    return role + "_" + std::string(ib::to_string(c.kernel)) + fmt("_G%g", c.capillary) + fmt("_a%g", c.radius) +
           fmt("_Re%g", c.reynolds) + fmt("_H%g", c.height) + fmt("_L%g", c.length);
  }

  // Runs a study's independent runs at once on the case's cores (vv::run_concurrently: one
  // OpenMP thread each, the same bits as one after the other), the most expensive first;
  // run() then takes each result from here instead of running it again.
  void prefetch(const std::vector<std::pair<vv::CapsuleConfig, std::string>>& plan) {
    std::vector<std::size_t> order(plan.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    const auto cost = [&](std::size_t i) {  // nodes × steps ∝ (a/h)^4 H L
      const vv::CapsuleConfig& c = plan[i].first;
      return std::pow(c.radius, 4) * c.height * c.length / c.reynolds;
    };
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cost(a) > cost(b); });
    std::vector<vv::CapsuleResult> results(plan.size());
    std::vector<std::function<void()>> jobs;
    for (std::size_t i : order)
      jobs.push_back([&, i] {
        results[i] = vv::run_capsule(plan[i].first, record.case_name(), label_of(plan[i].first, plan[i].second));
      });
    vv::run_concurrently(jobs);
    for (std::size_t i = 0; i < plan.size(); ++i) prefetched[label_of(plan[i].first, plan[i].second)] = results[i];
  }

  vv::CapsuleResult run(const vv::CapsuleConfig& c, const std::string& role) {
    const std::string label = label_of(c, role);
    const auto found = prefetched.find(label);
    EXPECT_TRUE(prefetched.empty() || found != prefetched.end()) << label << " is missing from full_study_plan()";
    const auto r = found != prefetched.end() ? found->second : vv::run_capsule(c, record.case_name(), label);
    EXPECT_FALSE(r.diverged) << role << " a/h=" << c.radius << ": " << r.diagnosis;
    if (r.strain >= c.max_strain - 0.05) ++capped;
    max_area = std::max(max_area, std::abs(r.area_change));
    t_forces += r.t_forces;
    t_zero += r.t_zero;
    t_spread += r.t_spread;
    t_moments += r.t_moments;
    t_move += r.t_move;
    t_fluid += r.t_fluid;
    t_ib += r.t_forces + r.t_zero + r.t_spread + r.t_moments + r.t_move;
    marker_steps += static_cast<double>(r.markers) * static_cast<double>(r.steps);
    run_markers.push_back(r.markers);
    run_marker_us.push_back(1e6 * (r.t_forces + r.t_spread + r.t_move) / static_cast<double>(r.steps));
    node_steps += c.length * c.radius * c.height * c.radius * static_cast<double>(r.steps);
    record.add_run({{"role", role},
                    {"kernel", std::string(ib::to_string(c.kernel))},
                    {"G", c.capillary},
                    {"a_over_h", c.radius},
                    {"Re", c.reynolds},
                    {"H_over_a", c.height},
                    {"Lx_over_a", c.length},
                    {"markers", static_cast<double>(r.markers)},
                    {"steps", static_cast<double>(r.steps)},
                    {"strain", r.strain},
                    {"D", r.D},
                    {"theta_deg", r.theta_deg},
                    {"D_drift_last_strain_unit", r.drift},
                    {"tank_treading_period_gamma_t", r.tt_period},
                    {"area_change", r.area_change},
                    {"wall_time_s", r.wall_time_s},
                    {"t_fluid_step_s", r.t_fluid},
                    {"t_membrane_forces_s", r.t_forces},
                    {"t_zero_force_field_s", r.t_zero},
                    {"t_spread_s", r.t_spread},
                    {"t_moments_s", r.t_moments},
                    {"t_interpolate_move_s", r.t_move}},
                   r.scene_text);
    for (const io::FieldPicture& p : r.pictures) record.add_field(p);
    std::printf("%-10s %-8s G=%.3f a/h=%4.1f Re=%.3f H=%2.0f Lx=%2.0f  D=%.5f th=%6.3f T=%.2f strain=%.1f drift=%.1e %.1fs\n",
                role.c_str(), std::string(ib::to_string(c.kernel)).c_str(), c.capillary, c.radius, c.reynolds, c.height,
                c.length, r.D, r.theta_deg, r.tt_period, r.strain, r.drift, r.wall_time_s);
    std::fflush(stdout);
    return r;
  }
};

void describe(io::ResultRecord& record) {
  record.set_requirement(
      "A circular neo-Hookean capsule (no bending, no prestress) in simple shear between moving walls reaches the "
      "steady Taylor deformation D within 0.01 and inclination theta within 2 deg of the Re = 0 unbounded 2D "
      "reference, after Richardson extrapolation in a/h and measured corrections for Re and domain size.");
  record.set_reference(
      "docs/validation-capsule.md (Reference): 2D Stokes boundary-integral computation (viscosity ratio 1, neo-Hookean "
      "T = E_s(lambda^3 - 1)/lambda^1.5), D converged to 1e-6: G = 0.05: D = 0.2748, theta = 30.4 deg; G = 0.1: "
      "D = 0.3423, theta = 27.4 deg. Published comparison: Breyiannis & Pozrikidis 2000, Theor Comput Fluid Dyn 13:327.");
  record.set_parameter("collision", "BGK tau = 1 (nu = 1/6), equal viscosity inside and outside");
  record.set_parameter("walls", "bottom/top moving_wall at -U/+U (halfway bounce-back, Ladd), periodic in x");
  record.set_parameter("membrane", "neo-Hookean 2D, no bending, no area penalty, rest shape = initial circle");
  record.set_parameter("markers", "n = 12 a/h (rest spacing 0.52 h)");
  record.set_parameter("steady_criterion", "|D(t) - D(t - 1/gamma)| < 1e-4 after strain >= 4, cap strain 12");
  record.set_parameter("D_definition", "(sqrt(I1) - sqrt(I2))/(sqrt(I1) + sqrt(I2)), I = second area moments of the "
                                       "marker polygon; mean over the last strain unit");
}

// One resolution level at capillary number G (the pictures of the steady capsule and its
// flow for the report: cosine4, G = 0.1, a/h = 12).
vv::CapsuleConfig resolution_config(double G, double a, ib::KernelType kernel = ib::KernelType::cosine4) {
  vv::CapsuleConfig c;
  c.kernel = kernel;
  c.capillary = G;
  c.radius = a;
  c.pictures = kernel == ib::KernelType::cosine4 && G == 0.1 && a == 12;
  return c;
}

// The corrections' runs at the coarsest level a: Reynolds number Re, H = height·a, L_x = length·a.
vv::CapsuleConfig correction_config(double G, double a, double Re, double height, double length) {
  vv::CapsuleConfig c;
  c.capillary = G;
  c.radius = a;
  c.reynolds = Re;
  c.height = height;
  c.length = length;
  return c;
}

// Every run of the full study below (the same configurations, in any order: the study reads
// them back by label through Bookkeeping::run).
std::vector<std::pair<vv::CapsuleConfig, std::string>> full_study_plan() {
  std::vector<std::pair<vv::CapsuleConfig, std::string>> plan;
  for (const auto& ref : kReference) {
    const auto& levels = ref.G >= 0.05 ? kLevelsLargeG : kLevelsSmallG;
    for (double a : levels) plan.push_back({resolution_config(ref.G, a), "resolution"});
    plan.push_back({correction_config(ref.G, levels[0], 0.05, 16, 16), "inertia"});
    plan.push_back({correction_config(ref.G, levels[0], 0.025, 16, 16), "inertia"});
    plan.push_back({correction_config(ref.G, levels[0], 0.025, 32, 32), "domain"});
    if (ref.G == 0.1) {
      plan.push_back({correction_config(ref.G, levels[0], 0.025, 32, 16), "confinement"});
      for (const ib::KernelType kernel : {ib::KernelType::peskin4, ib::KernelType::roma3, ib::KernelType::linear2})
        for (double a : kOtherKernelLevels) plan.push_back({resolution_config(ref.G, a, kernel), "resolution"});
    }
  }
  return plan;
}

}  // namespace

TEST(CapsuleShear, FullStudy) {
  vv::Stopwatch total;
  io::ResultRecord record("validation.capsule_shear", "capsule");
  describe(record);
  Bookkeeping book{record};
  const std::string reason_D =
      "target of issue 4 item 7; the reference is converged to 1e-6, so 0.01 covers the model error left after the "
      "corrections: the domain effect beyond 32a (uncorrected), the linear Re extrapolation, and the additivity "
      "of corrections measured at a/h = 6";
  const std::string reason_theta = "target of issue 4 item 7 (2 deg); same residual model errors as for D";
  book.prefetch(full_study_plan());

  for (const auto& ref : kReference) {
    const std::string g = fmt("G=%.2f", ref.G);
    // 1. Resolution study.
    std::vector<double> h, D, th, wall;
    std::vector<vv::CapsuleResult> runs;
    const auto& kLevels = ref.G >= 0.05 ? kLevelsLargeG : kLevelsSmallG;
    for (double a : kLevels) {
      runs.push_back(book.run(resolution_config(ref.G, a), "resolution"));
      h.push_back(1.0 / a);
      D.push_back(runs.back().D);
      th.push_back(runs.back().theta_deg);
      wall.push_back(runs.back().wall_time_s);
    }
    const auto eD = vv::richardson(h, D, 1.0);
    const auto eT = vv::richardson(h, th, 1.0);
    // 2. Inertia: Re = 0.05, 0.025 at a/h = 6 (D linear in Re → D0 = 2 D(0.025) − D(0.05)).
    const double a6 = kLevels[0];
    const auto r05 = book.run(correction_config(ref.G, a6, 0.05, 16, 16), "inertia");
    const auto r025 = book.run(correction_config(ref.G, a6, 0.025, 16, 16), "inertia");
    const double D_re0 = 2.0 * r025.D - r05.D, th_re0 = 2.0 * r025.theta_deg - r05.theta_deg;
    // Quadratic through Re = 0.1, 0.05, 0.025 (Richardson in Re, order 1 then 2) as a check.
    const double D_re0_quad = (8.0 * r025.D - 6.0 * r05.D + runs[0].D) / 3.0;
    const double dD_re = D_re0 - runs[0].D, dth_re = th_re0 - runs[0].theta_deg;
    // 3. Domain: H = L_x = 32a at Re = 0.025 (a/h = 6), plus H alone for the confinement figure.
    const auto r32 = book.run(correction_config(ref.G, a6, 0.025, 32, 32), "domain");
    const double dD_dom = r32.D - r025.D, dth_dom = r32.theta_deg - r025.theta_deg;
    double dD_conf = 0, dth_conf = 0;
    if (ref.G == 0.1) {  // H alone (confinement) against H and L_x together
      const auto rH = book.run(correction_config(ref.G, a6, 0.025, 32, 16), "confinement");
      dD_conf = rH.D - r025.D;
      dth_conf = rH.theta_deg - r025.theta_deg;
      record.set_parameter("confinement_" + g, "a/h = 6, Re = 0.025, L_x = 16a: H = 16a -> 32a changes D by " +
                                                   fmt("%+.5f", dD_conf) + ", theta by " + fmt("%+.3f deg", dth_conf) +
                                                   "; H = L_x = 16a -> 32a changes D by " + fmt("%+.5f", dD_dom));
    }
    const double D_est = eD.value + dD_re + dD_dom, th_est = eT.value + dth_re + dth_dom;
    std::printf("%s: D_rich=%.5f (p=%.2f obs=%d) dRe=%+.5f (quad %+.5f) dDom=%+.5f -> D=%.5f ref %.4f | th_rich=%.3f "
                "(p=%.2f obs=%d) dRe=%+.3f dDom=%+.3f -> th=%.3f ref %.1f\n",
                g.c_str(), eD.value, eD.order, eD.observed, dD_re, D_re0_quad - runs[0].D, dD_dom, D_est, ref.D, eT.value,
                eT.order, eT.observed, dth_re, dth_dom, th_est, ref.theta);
    record.set_parameter("extrapolation_" + g,
                         "D_rich = " + fmt("%.5f", eD.value) + " (order " + fmt("%.2f", eD.order) +
                             (eD.observed ? " observed" : " assumed") + "), Re->0 " + fmt("%+.5f", dD_re) +
                             " (quadratic fit " + fmt("%+.5f", D_re0_quad - runs[0].D) + "), domain 16a->32a " +
                             fmt("%+.5f", dD_dom) + "; theta_rich = " + fmt("%.3f", eT.value) + " (order " +
                             fmt("%.2f", eT.order) + (eT.observed ? " observed" : " assumed") + "), Re->0 " +
                             fmt("%+.3f", dth_re) + ", domain " + fmt("%+.3f", dth_dom));
    record.add_metric({"D_" + g, "steady Taylor deformation, extrapolated (a/h, Re, domain), cosine4", "", D_est, ref.D,
                       0.01, io::Comparison::absolute, reason_D});
    record.add_metric({"theta_" + g, "steady inclination, extrapolated (a/h, Re, domain), cosine4", "deg", th_est,
                       ref.theta, 2.0, io::Comparison::absolute, reason_theta});
    record.add_metric({"monotone_D_" + g,
                       "D converges monotonically over a/h = 8, 12, 16, so the Richardson order is solved from "
                       "the data (1) instead of assumed (0)",
                       "", eD.observed ? 1.0 : 0.0, 1.0, 0.0, io::Comparison::at_least,
                       "the extrapolation is only meaningful if the three finest levels converge monotonically"});
    // Convergence of D towards its Richardson limit (coarsest level not used in the fit).
    io::ConvergenceSeries cs;
    cs.name = "cosine4 " + g;
    cs.norm = "|D(h) - D_Richardson| at Re = 0.1, H = Lx = 16a";
    cs.h = h;
    for (double d : D) cs.error.push_back(std::abs(d - eD.value));
    cs.formal_order = 1.0;
    cs.order_tolerance = 1.0;
    vv::fit_order(cs);
    record.add_convergence(cs);
    // Speed vs error (error = distance to the Richardson limit, Re = 0.1).
    io::SpeedErrorSeries se;
    se.name = "cosine4 " + g;
    for (std::size_t i = 0; i < D.size(); ++i) {
      se.wall_time_s.push_back(wall[i]);
      se.error.push_back(std::abs(D[i] - eD.value));
      se.label.push_back(fmt("a/h=%.0f", kLevels[i]));
    }
    record.add_speed_error(se);
    io::Series s;
    s.name = "D_vs_resolution_" + g;
    s.title = "Taylor deformation vs a/h (Re = 0.1, H = Lx = 16a), cosine4, " + g;
    s.xlabel = "a/h";
    s.ylabel = "D";
    for (std::size_t i = 0; i < D.size(); ++i) {
      s.x.push_back(kLevels[i]);
      s.y.push_back(D[i]);
      s.y_reference.push_back(ref.D);
    }
    record.add_series(s);
    io::Series hist;
    hist.name = "D_history_" + g;
    hist.title = "D(strain), a/h = 16, cosine4, " + g;
    hist.xlabel = "gamma t";
    hist.ylabel = "D";
    hist.x = runs.back().strain_history;
    hist.y = runs.back().D_history;
    record.add_series(hist);

    // The other kernels at G = 0.1 (issue 4 item 8: error against wall time per kernel):
    // the same corrections (measured with cosine4) applied to each kernel's own Richardson limit.
    if (ref.G == 0.1) {
      for (const ib::KernelType kernel : {ib::KernelType::peskin4, ib::KernelType::roma3, ib::KernelType::linear2}) {
        const std::string name(ib::to_string(kernel));
        std::vector<double> hp, Dp, thp, wp;
        for (double a : kOtherKernelLevels) {
          const auto r = book.run(resolution_config(ref.G, a, kernel), "resolution");
          hp.push_back(1.0 / a);
          Dp.push_back(r.D);
          thp.push_back(r.theta_deg);
          wp.push_back(r.wall_time_s);
        }
        const auto pD = vv::richardson(hp, Dp, 1.0);
        const auto pT = vv::richardson(hp, thp, 1.0);
        std::printf("%s %s: D_rich=%.5f (p=%.2f obs=%d) -> %.5f; th_rich=%.3f -> %.3f\n", name.c_str(), g.c_str(),
                    pD.value, pD.order, pD.observed, pD.value + dD_re + dD_dom, pT.value, pT.value + dth_re + dth_dom);
        record.add_metric({"D_" + name + "_" + g,
                           "steady D, " + name + ", Richardson over a/h = 6, 8, 12 + cosine4 corrections", "",
                           pD.value + dD_re + dD_dom, ref.D, 0.01, io::Comparison::absolute, reason_D});
        record.add_metric({"theta_" + name + "_" + g, "steady theta, " + name + ", extrapolated as above", "deg",
                           pT.value + dth_re + dth_dom, ref.theta, 2.0, io::Comparison::absolute, reason_theta});
        io::SpeedErrorSeries sp;
        sp.name = name + " " + g;
        for (std::size_t i = 0; i < Dp.size(); ++i) {
          sp.wall_time_s.push_back(wp[i]);
          sp.error.push_back(std::abs(Dp[i] - eD.value));  // against the cosine4 limit: a common target
          sp.label.push_back(fmt("a/h=%.0f", kOtherKernelLevels[i]));
        }
        record.add_speed_error(sp);
      }
    }
  }

  record.add_metric({"capped_runs", "runs that reached the strain cap 12 before |dD| < 1e-4 per strain unit", "",
                     static_cast<double>(book.capped), 0.0, 0.0, io::Comparison::at_most,
                     "every D reported must be steady to 1e-4 per strain unit (10x below the resolution effects)"});
  record.add_metric({"max_area_change", "largest |A/A0 - 1| over all runs (IB leakage; no area penalty)", "",
                     book.max_area, 0.005, 0.0, io::Comparison::at_most,
                     "an area loss of 0.5 % would change D by O(1e-3); the Laplace case measured 0.04-0.1 % leakage"});
  // Cost of the IB + membrane cycle (issue 4 item 10), summed over all runs.
  const double per_marker_ns = 1e9 * (book.t_forces + book.t_spread + book.t_move) / book.marker_steps;
  const double fluid_ns = 1e9 * book.t_fluid / book.node_steps;
  record.set_parameter("cost_per_marker_step_ns",
                       fmt("%.1f", per_marker_ns) + " ns (forces " + fmt("%.1f", 1e9 * book.t_forces / book.marker_steps) +
                           ", spread " + fmt("%.1f", 1e9 * book.t_spread / book.marker_steps) +
                           ", interpolate + move " + fmt("%.1f", 1e9 * book.t_move / book.marker_steps) + ")");
  record.set_parameter("cost_fluid_per_node_step_ns", fmt("%.2f", fluid_ns));
  {  // marker work per step = fixed + slope × markers (least squares over all runs, 72-192 markers)
    const double slope = vv::least_squares_slope(book.run_markers, book.run_marker_us);
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < book.run_markers.size(); ++i) { mx += book.run_markers[i]; my += book.run_marker_us[i]; }
    mx /= static_cast<double>(book.run_markers.size());
    my /= static_cast<double>(book.run_markers.size());
    record.set_parameter("cost_marker_work_fit", fmt("%.1f", my - slope * mx) + " us per step fixed + " +
                                                     fmt("%.0f", 1e3 * slope) + " ns per marker (forces, spread, interpolate, move)");
    std::printf("marker work fit: %.1f us/step + %.0f ns/marker\n", my - slope * mx, 1e3 * slope);
  }
  record.set_parameter("cost_grid_work_per_node_step_ns",
                       "zeroing the force field " + fmt("%.2f", 1e9 * book.t_zero / book.node_steps) +
                           ", support-node velocity for interpolation " + fmt("%.2f", 1e9 * book.t_moments / book.node_steps));
  record.set_parameter("cost_overhead_over_fluid_step",
                       fmt("%.3f", book.t_ib / book.t_fluid) + " (whole IB cycle); support-node velocity " +
                           fmt("%.3f", book.t_moments / book.t_fluid) + ", zeroing the force field " +
                           fmt("%.3f", book.t_zero / book.t_fluid) + ", marker work (forces, spread, interpolate) " +
                           fmt("%.3f", (book.t_forces + book.t_spread + book.t_move) / book.t_fluid));
  std::printf("cost: per marker-step %.1f ns (forces %.1f spread %.1f move %.1f); fluid %.2f ns/node-step; overhead "
              "IB/fluid %.3f, moments/fluid %.3f, zero/fluid %.3f, marker/fluid %.3f\n",
              per_marker_ns, 1e9 * book.t_forces / book.marker_steps, 1e9 * book.t_spread / book.marker_steps,
              1e9 * book.t_move / book.marker_steps, fluid_ns, book.t_ib / book.t_fluid, book.t_moments / book.t_fluid,
              book.t_zero / book.t_fluid,
              (book.t_forces + book.t_spread + book.t_move) / book.t_fluid);
  record.set_wall_time(total.seconds());
  std::printf("written: %s\n", record.write_to_results_dir().c_str());
  for (const auto& m : record.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}

TEST(CapsuleShear, CiSubset) {
  vv::Stopwatch total;
  io::ResultRecord record("validation.capsule_shear_ci", "capsule");
  describe(record);
  Bookkeeping book{record};
  vv::CapsuleConfig c;  // a/h = 6, G = 0.1, Re = 0.1, H = Lx = 16a
  c.capillary = 0.1;
  c.radius = 6.0;
  c.min_strain = 3.0;
  c.max_strain = 4.0;
  c.pictures = true;
  const auto r = book.run(c, "ci");
  record.add_metric({"D_deforms", "the capsule deforms (a rigid or leaking membrane gives D ~ 0)", "", r.D, 0.2, 0.0,
                     io::Comparison::at_least, "reference D = 0.3423; D < 0.2 would mean the coupling is broken"});
  record.add_metric({"D_G=0.10", "D at a/h = 6, Re = 0.1, H = 16a, strain <= 4 (no extrapolation)", "", r.D, 0.3423,
                     0.05, io::Comparison::absolute,
                     "uncorrected: Re = 0.1 inertia (+0.008), H = 16a confinement and resolution (+0.003) measured in "
                     "validation.capsule_shear; 0.05 leaves room only for those known effects plus short strain"});
  record.add_metric({"theta_G=0.10", "inclination at a/h = 6, Re = 0.1 (no extrapolation)", "deg", r.theta_deg, 27.4,
                     4.0, io::Comparison::absolute,
                     "Re = 0.1 inertia tilts the capsule by +2.3 deg (measured in validation.capsule_shear)"});
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  for (const auto& m : record.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}
