// Cases validation.capsule_shear (full tier) and validation.capsule_shear_ci (CI)
// (issue 4 items 7, 8, 10; issue 22 items 2 and 4).
//
// Requirement: a circular capsule (no bending, no prestress) in simple shear reaches the
// steady Taylor deformation D, inclination θ and tank-treading period T·γ̇ of the Re = 0,
// unbounded 2D boundary-integral reference (|ΔD| ≤ 0.005, |Δθ| ≤ 0.5°, |ΔT|/T ≤ 1 %) for the
// neo-Hookean law at G = 0.0025–0.2 and the Hookean law at G = 0.01 and 0.1, once the lattice
// results are extrapolated to a/h → ∞ (Richardson), Re → 0 and an unbounded domain.
// Reference: reference_data/capsule_bim/reference_capsule.csv (capsule_bim.py, a spectral
// boundary-integral solver converged to 1e-8 in D; PROVENANCE.md there); published comparison
// Breyiannis & Pozrikidis 2000, Theor Comput Fluid Dyn 13:327. docs/validation-capsule.md.
//
// Measured ingredients (all cosine4 = thesis kernel, eq 24, unless named; every run with the
// area projection, docs/model.md eq 3.14, so that every G reaches the steadiness criterion):
//  1. resolution study at Re = 0.1, H = L_x = 16a: a/h = 6, 8, 12, 16 → Richardson over the
//     three finest levels;
//  2. inertia: a/h = 6 at Re = 0.05 and 0.025 → linear extrapolation to Re = 0
//     (the shift is linear in Re: measured q(0.1) − q(0.05) ≈ 2 [q(0.05) − q(0.025)]);
//  3. domain: a/h = 6, Re = 0.025, H = L_x = 32a against 16a (confinement by the
//     walls raises D, periodic images along x lower it; their sum is applied);
//  q_est = q_Rich + [q_Re→0 − q_Re=0.1](a/h = 6) + [q_32a − q_16a](a/h = 6, Re = 0.025)
//  for q = D, θ, T·γ̇, the corrections being taken as additive (each is measured at the
//  coarse level). T·γ̇ is asserted except for the two sharp shapes (sharp()), where it is
//  recorded. The other kernels (peskin4, roma3, linear2) run a/h = 8, 12, 16 at the G their
//  explicit update allows (kOtherKernels) with the cosine4 corrections: D and θ asserted, T
//  recorded, and speed against error (issue 22 item 4).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "bim_reference.hpp"
#include "capsule_bookkeeping.hpp"
#include "capsule_run.hpp"
#include "capsule_study.hpp"
#include "common/case_support.hpp"
#include "common/convergence.hpp"
#include "richardson.hpp"

using namespace erythro;
using namespace erythro::vv::capsule;

namespace {

const std::vector<double> kLevels = {6, 8, 12, 16};  // cosine4's levels a/h
const std::vector<double> kOtherKernelLevels = {8, 12, 16};  // cosine4's three finest
// The other kernels (neo-Hookean) at G = 0.1 and at the smallest G of the reference their explicit
// update is stable at from a/h = 8 on (membrane/stability.hpp: Π_T ∝ 1/(G a/h) against limits
// 17× (roma3) and 81× (linear2) below cosine4's; at a/h = 8 the scene check gives Π_T = 0.104 >
// 0.072 for roma3 at G = 0.01 and 0.0208 > 0.0148 for linear2 at G = 0.05). Not at G = 0.2, a
// sharp shape (sharp()).
struct OtherKernel {
  ib::KernelType kernel;
  std::vector<double> G;
};
const OtherKernel kOtherKernels[] = {{ib::KernelType::peskin4, {0.0025, 0.1}},
                                     {ib::KernelType::roma3, {0.02, 0.1}},
                                     {ib::KernelType::linear2, {0.1}}};
// The other kernels that run at this (law, G).
std::vector<ib::KernelType> other_kernels(const vv::BimReference& ref) {
  std::vector<ib::KernelType> kernels;
  if (ref.law != "neo_hookean") return kernels;
  for (const OtherKernel& k : kOtherKernels)
    for (double G : k.G)
      if (same(ref.G, G)) kernels.push_back(k.kernel);
  return kernels;
}

// Every run of the full study (the same configurations, in any order: the study reads them
// back by label through CapsuleBookkeeping::run).
std::vector<std::pair<vv::CapsuleConfig, std::string>> full_study_plan() {
  std::vector<std::pair<vv::CapsuleConfig, std::string>> plan;
  const double a6 = kLevels.front();
  for (const vv::BimReference& ref : reference()) {
    for (double a : kLevels) plan.push_back({config(ref.law, ref.G, a), "resolution"});
    plan.push_back({config(ref.law, ref.G, a6, ib::KernelType::cosine4, 0.05), "inertia"});
    plan.push_back({config(ref.law, ref.G, a6, ib::KernelType::cosine4, 0.025), "inertia"});
    plan.push_back({config(ref.law, ref.G, a6, ib::KernelType::cosine4, 0.025, 32, 32), "domain"});
    if (ref.law == "neo_hookean" && same(ref.G, 0.1))
      plan.push_back({config(ref.law, ref.G, a6, ib::KernelType::cosine4, 0.025, 32, 16), "confinement"});
    for (const ib::KernelType kernel : other_kernels(ref))
      for (double a : kOtherKernelLevels) plan.push_back({config(ref.law, ref.G, a, kernel), "resolution"});
  }
  return plan;
}

void describe(io::ResultRecord& record) {
  record.set_requirement(
      "A circular capsule (no bending, no prestress) in simple shear between moving walls reaches the steady Taylor "
      "deformation D within 0.005, inclination theta within 0.5 deg and tank-treading period T*gamma within 1 % of "
      "the Re = 0 unbounded 2D boundary-integral reference (neo-Hookean G = 0.0025-0.2, Hookean G = 0.01 and 0.1; "
      "T recorded, not asserted, for the two sharp shapes), after Richardson extrapolation in a/h and measured "
      "corrections for Re and domain size.");
  record.set_reference(
      "reference_data/capsule_bim/reference_capsule.csv: spectral 2D Stokes boundary-integral solver capsule_bim.py "
      "(viscosity ratio 1; neo-Hookean T = E_s(lambda^3 - 1)/lambda^1.5, Hookean T = E_s(lambda - 1)), converged to "
      "1e-8 in D (PROVENANCE.md there). Published comparison: Breyiannis & Pozrikidis 2000, Theor Comput Fluid "
      "Dyn 13:327.");
  record.set_parameter("collision", "BGK tau = 1 (nu = 1/6), equal viscosity inside and outside");
  record.set_parameter("walls", "bottom/top moving_wall at -U/+U (halfway bounce-back, Ladd), periodic in x");
  record.set_parameter("membrane", "2D neo-Hookean or Hookean, no bending, no area penalty, rest shape = initial "
                                   "circle, membrane.area_correction = projection (docs/model.md eq 3.14)");
  record.set_parameter("markers", "n = 12 a/h (rest spacing 0.52 h)");
  record.set_parameter("steady_criterion", "stop when |D(t) - D(t - 1/gamma)| < 1e-4 after strain >= 4 (cap 16); "
                                           "asserted on the means of the last two strain units");
  record.set_parameter("D_definition", "(sqrt(I1) - sqrt(I2))/(sqrt(I1) + sqrt(I2)), I = second area moments of the "
                                       "marker polygon; mean over the last strain unit");
  record.set_parameter("T_definition", "360 deg over the mean marker phase rate about the centroid over the last "
                                       "strain unit (exact for a steady shape: the markers' density is 1/omega)");
}

// One (law, G) of the reference: its runs, estimates, metrics and figures.
struct VsG {
  std::vector<double> G, D, theta, T, D_ref, theta_ref, T_ref;
  void add(const vv::BimReference& ref, double d, double th, double t) {
    G.push_back(ref.G);
    D.push_back(d);
    theta.push_back(th);
    T.push_back(t);
    D_ref.push_back(ref.D);
    theta_ref.push_back(ref.theta_deg);
    T_ref.push_back(ref.T_gamma);
  }
};

void add_vs_G_series(io::ResultRecord& record, const std::string& law, const VsG& v) {
  const auto add = [&](const std::string& name, const std::string& label, const std::vector<double>& y,
                       const std::vector<double>& y_ref) {
    io::Series s;
    s.name = name + "_vs_G_" + law;
    s.title = label + " vs G, " + law + " (dashed: boundary integrals)";
    s.xlabel = "G = mu gamma a / E_s";
    s.ylabel = label;
    s.x = v.G;
    s.y = y;
    s.y_reference = y_ref;
    s.log_x = true;
    record.add_series(s);
  };
  add("D", "D", v.D, v.D_ref);
  add("theta", "theta (deg)", v.theta, v.theta_ref);
  add("T", "T gamma", v.T, v.T_ref);
}

void add_history(io::ResultRecord& record, const vv::CapsuleResult& r, const std::string& tag) {
  io::Series hist;
  hist.name = "D_history_" + tag;
  hist.title = "D(strain), a/h = 16, cosine4, " + tag;
  hist.xlabel = "gamma t";
  hist.ylabel = "D";
  hist.x = r.strain_history;
  hist.y = r.D_history;
  record.add_series(hist);
}

}  // namespace

TEST(CapsuleShear, FullStudy) {
  vv::Stopwatch total;
  io::ResultRecord record("validation.capsule_shear", "capsule");
  describe(record);
  vv::CapsuleBookkeeping book{record};
  const std::string reason_D =
      "issue 22 item 2; the reference is converged to 1e-8, so 0.005 covers the model error left after the "
      "corrections: the domain effect beyond 32a (uncorrected), the linear Re extrapolation, and the additivity of "
      "corrections measured at a/h = 6 (below 1e-3 where measured, 2.2e-3 at the most deformed shape, Hookean "
      "G = 0.1: validation.capsule_shear_sharp)";
  const std::string reason_theta = "issue 22 item 2 (0.5 deg); the same residual model errors as for D";
  const std::string reason_T = "issue 22 item 2 (1 %); the same residual model errors as for D";
  const std::string reason_T_sharp =
      "informative: at a sharp shape T is not in the asymptotic range of a/h at the case's levels (observed orders "
      "0.5; docs/validation-capsule.md, Sharp shapes), so its 1 % cannot be asserted at an affordable resolution";
  const std::string reason_T_kernels =
      "informative: the other kernels' T over a/h = 8, 12, 16 is for speed against error; its observed order is "
      "not asymptotic for the narrow kernels (0.9 for roma3, 7.5 for linear2 at G = 0.1)";
  book.prefetch(full_study_plan());

  VsG neo, hooke;
  for (const vv::BimReference& ref : reference()) {
    const std::string tag = case_tag(ref);
    std::vector<double> h, wall;
    std::vector<vv::CapsuleResult> levels;
    for (double a : kLevels) {
      levels.push_back(book.run(config(ref.law, ref.G, a), "resolution"));
      h.push_back(1.0 / a);
      wall.push_back(levels.back().wall_time_s);
    }
    const double a6 = kLevels.front();
    Corrections c;
    c.re_0p1 = levels.front();
    c.re_0p05 = book.run(config(ref.law, ref.G, a6, ib::KernelType::cosine4, 0.05), "inertia");
    c.re_0p025 = book.run(config(ref.law, ref.G, a6, ib::KernelType::cosine4, 0.025), "inertia");
    c.wide = book.run(config(ref.law, ref.G, a6, ib::KernelType::cosine4, 0.025, 32, 32), "domain");
    c.narrow = c.re_0p025;
    const Estimates est = estimate_all(h, levels, c);
    const Estimate &eD = est.D, &eth = est.theta, &eT = est.T;
    record_estimates(record, ref, est);
    if (ref.law == "neo_hookean" && same(ref.G, 0.1)) {  // H alone (confinement) against H and L_x together
      const auto rH = book.run(config(ref.law, ref.G, a6, ib::KernelType::cosine4, 0.025, 32, 16), "confinement");
      record.set_parameter("confinement_" + tag, "a/h = 6, Re = 0.025, L_x = 16a: H = 16a -> 32a changes D by " +
                                                     fmt("%+.5f", rH.D - c.re_0p025.D) + ", theta by " +
                                                     fmt("%+.3f deg", rH.theta_deg - c.re_0p025.theta_deg) +
                                                     "; H = L_x = 16a -> 32a changes D by " + fmt("%+.5f", eD.d_domain));
    }
    record.add_metric({"D_" + tag, "steady Taylor deformation, extrapolated (a/h, Re, domain), cosine4", "", eD.value,
                       ref.D, kTolD, io::Comparison::absolute, reason_D});
    record.add_metric({"theta_" + tag, "steady inclination, extrapolated (a/h, Re, domain), cosine4", "deg",
                       eth.value, ref.theta_deg, kTolTheta, io::Comparison::absolute, reason_theta});
    if (!sharp(ref))
      record.add_metric({"T_" + tag, "tank-treading period T gamma, extrapolated (a/h, Re, domain), cosine4", "",
                         eT.value, ref.T_gamma, kTolT, io::Comparison::relative, reason_T});
    else
      record.add_metric({"T_deviation_" + tag,
                         "(T_est - T_ref)/T_ref of the tank-treading period, cosine4, a sharp shape (tip radius < 5 h "
                         "at a/h = 16)",
                         "", (eT.value - ref.T_gamma) / ref.T_gamma, -std::numeric_limits<double>::infinity(), 0.0,
                         io::Comparison::at_least, reason_T_sharp});
    // Resolved to the steadiness noise: the finest levels' D differ by less than twice the stop rule's 1e-4.
    const double d_fine = std::max(std::abs(levels[1].D - levels[2].D), std::abs(levels[2].D - levels[3].D));
    record.add_metric({"monotone_D_" + tag,
                       "D converges monotonically over a/h = 8, 12, 16, so the Richardson order is solved from the "
                       "data, or those levels agree within twice the steadiness criterion (1); otherwise 0",
                       "", eD.rich.observed || d_fine < 2e-4 ? 1.0 : 0.0, 1.0, 0.0, io::Comparison::at_least,
                       "the extrapolation is only meaningful if the finest levels converge monotonically or are "
                       "already resolved to the noise of a steady D (neo-Hookean G = 0.2: 0.43909, 0.43909, 0.43900)"});
    (ref.law == "neo_hookean" ? neo : hooke).add(ref, eD.value, eth.value, eT.value);
    // Convergence of D towards its Richardson limit (the coarsest level not used in the fit).
    io::ConvergenceSeries cs;
    cs.name = "cosine4 " + tag;
    cs.norm = "|D(h) - D_Richardson| at Re = 0.1, H = Lx = 16a";
    cs.h = h;
    for (const vv::CapsuleResult& r : levels) cs.error.push_back(std::abs(r.D - eD.rich.value));
    cs.formal_order = 1.0;
    cs.order_tolerance = 1.0;
    vv::fit_order(cs);
    record.add_convergence(cs);
    // Speed against error: each level's D with the corrections, against the reference.
    const auto speed_error = [&](const std::string& kernel, const std::vector<vv::CapsuleResult>& runs,
                                 const std::vector<double>& a) {
      io::SpeedErrorSeries se;
      se.name = kernel + " " + tag;
      for (std::size_t i = 0; i < runs.size(); ++i) {
        se.wall_time_s.push_back(runs[i].wall_time_s);
        se.error.push_back(std::abs(runs[i].D + eD.d_re + eD.d_domain - ref.D));
        se.label.push_back(fmt("a/h=%.0f", a[i]));
      }
      record.add_speed_error(se);
    };
    // Drawn where another kernel runs too (one figure; the other G's errors are in the runs table).
    if (!other_kernels(ref).empty()) speed_error("cosine4", levels, kLevels);
    if (ref.law == "neo_hookean" && (same(ref.G, 0.0025) || same(ref.G, 0.2))) add_history(record, levels.back(), tag);

    // The other kernels (issue 22 item 4): their own Richardson limits over a/h = 6, 8, 12
    // with the corrections measured with cosine4.
    for (const ib::KernelType kernel : other_kernels(ref)) {
      const std::string name(ib::to_string(kernel));
      std::vector<double> hk;
      std::vector<vv::CapsuleResult> runs;
      for (double a : kOtherKernelLevels) {
        runs.push_back(book.run(config(ref.law, ref.G, a, kernel), "resolution"));
        hk.push_back(1.0 / a);
      }
      const Estimate kD = estimate(hk, runs, c, D_of), kth = estimate(hk, runs, c, theta_of),
                     kT = estimate(hk, runs, c, period_of);
      std::printf("%s %s: D %s | theta %s | T %s\n", name.c_str(), tag.c_str(), describe_estimate(kD, "%.5f").c_str(),
                  describe_estimate(kth, "%.3f").c_str(), describe_estimate(kT, "%.4f").c_str());
      record.add_metric({"D_" + name + "_" + tag,
                         "steady D, " + name + ", Richardson over a/h = 8, 12, 16 + cosine4 corrections", "", kD.value,
                         ref.D, kTolD, io::Comparison::absolute, reason_D});
      record.add_metric({"theta_" + name + "_" + tag, "steady theta, " + name + ", extrapolated as above", "deg",
                         kth.value, ref.theta_deg, kTolTheta, io::Comparison::absolute, reason_theta});
      record.add_metric({"T_deviation_" + name + "_" + tag,
                         "(T_est - T_ref)/T_ref of the tank-treading period, " + name + ", extrapolated as above", "",
                         (kT.value - ref.T_gamma) / ref.T_gamma, -std::numeric_limits<double>::infinity(), 0.0,
                         io::Comparison::at_least, reason_T_kernels});
      speed_error(name, runs, kOtherKernelLevels);
    }
  }
  add_vs_G_series(record, "neo_hookean", neo);
  add_vs_G_series(record, "hookean", hooke);

  record.add_metric({"unsteady_runs",
                     "runs whose D changed by 1e-4 or more between the means of their last two strain units", "",
                     static_cast<double>(book.unsteady), 0.0, 0.0, io::Comparison::at_most,
                     "every D reported must be steady to 1e-4 per strain unit (10x below the tolerance's share of "
                     "the resolution effects)"});
  record.add_metric({"max_area_change", "largest |A/A0 - 1| at the end of any run (with the area projection)", "",
                     book.max_area, 1e-6, 0.0, io::Comparison::at_most,
                     "the projection restores the area every step (eq 3.14); what remains is its Newton tolerance"});
  record.set_parameter("capped_runs", fmt("%.0f", book.capped) + " runs reached the strain cap 16 before the stop rule");
  record.set_parameter("max_area_restored", fmt("%.2e", book.max_restored) +
                                                " (the largest area the projection gave back over one run, over A0: "
                                                "the leak it corrected)");
  book.record_cost();
  record.set_wall_time(total.seconds());
  std::printf("written: %s\n", record.write_to_results_dir().c_str());
  for (const auto& m : record.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}

TEST(CapsuleShear, CiSubset) {
  vv::Stopwatch total;
  io::ResultRecord record("validation.capsule_shear_ci", "capsule");
  describe(record);
  vv::CapsuleBookkeeping book{record};
  vv::CapsuleConfig c = config("neo_hookean", 0.1, 6.0);  // a/h = 6, G = 0.1, Re = 0.1, H = Lx = 16a
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
