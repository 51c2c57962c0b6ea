// validation.rbc_viscosity_long_runs (full): issue 5 item 9, the part of the stability map
// at viscosity contrast 5 that validation.rbc_viscosity_stability (γ̇t = 10, about one
// tumbling period, h = 0.4 µm only) leaves open:
//  (1) long runs, γ̇t = 150 (4–12 tumbling periods of 12–37 strain units), at the map's
//      corners τ_ex ∈ {0.52, 1} × Ca ∈ {×0.1, ×10} and at τ_ex = 0.52, Ca × 1 (h = 0.4 µm):
//      no divergence; for Ca ≤ × 1 |A/A0 − 1| within 0.5 % and no secular drift; for the soft
//      membrane (Ca × 10) the secular area loss it shows is measured and bounded;
//  (2) the corners again at a second resolution, h = 0.3125 µm (a/h = 12.5), γ̇t = 10.
// Same set-up as the map (vv::stability_map_config: flood fill, ratio 5, lattice shear rate
// fixed). docs/validation-interior-viscosity.md, "Item 9".
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "common/case_support.hpp"
#include "common/concurrent_runs.hpp"
#include "visc_support.hpp"

using namespace erythro;

namespace {

constexpr double kAreaBound = 0.005;      // |A/A0 − 1| ≤ 0.5 %, as validation.rbc_shear and the map
constexpr double kTauMinAsserted = 0.52;  // the map's asserted range τ_ex ≥ 0.52
constexpr double kLongStrain = 150.0;
constexpr double kMapStrain = 10.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct StudyRun {
  std::string kind;  // "long" (γ̇t = 150, h = 0.4 µm) or "fine map" (γ̇t = 10, h = 0.3125 µm)
  double ca_factor = 1;
  vv::RbcConfig c;
  vv::RbcResult r;
};

// Area drift of one run from its history (area_h: signed A/A0 − 1 every 0.05 strain units).
struct Drift {
  double tumbling_period = kNaN;  // 180°/|body rate|: the two-fold symmetric shape repeats per half turn
  double membrane_period = kNaN;  // 360°/|marker phase rate|: one membrane revolution (lab frame)
  double periods = kNaN;          // strain reached / tumbling_period
  double max_to_10 = 0;           // max |A/A0 − 1| over γ̇t ≤ 10 (sampled)
  double max_first_half = 0, max_second_half = 0;
  std::vector<double> window_mid, window_mean;  // mean of A/A0 − 1 per complete tumbling period
  // Secular drift: least-squares slope of A/A0 − 1 against γ̇t over γ̇t ≥ 10 (the first ten
  // strain units hold the start from the rest shape), per strain unit and per tumbling period.
  double rate = kNaN, per_period = kNaN;
  double strain_at_bound = kNaN;  // first γ̇t with |A/A0 − 1| > 0.5 % (NaN: never)
};

Drift drift_of(const vv::RbcResult& r) {
  Drift d;
  if (r.strain_h.empty()) return d;
  const double end = r.strain_h.back();
  for (std::size_t i = 0; i < r.strain_h.size(); ++i) {
    const double a = std::abs(r.area_h[i]);
    if (a > kAreaBound && std::isnan(d.strain_at_bound)) d.strain_at_bound = r.strain_h[i];
    if (r.strain_h[i] <= 10.0 + 1e-9) d.max_to_10 = std::max(d.max_to_10, a);
    double& half = r.strain_h[i] <= 0.5 * end ? d.max_first_half : d.max_second_half;
    half = std::max(half, a);
  }
  if (r.diverged || r.body_rate_deg == 0.0) return d;
  d.tumbling_period = 180.0 / std::abs(r.body_rate_deg);
  if (r.marker_rate_deg != 0.0) d.membrane_period = 360.0 / std::abs(r.marker_rate_deg);
  d.periods = end / d.tumbling_period;
  const int K = static_cast<int>(std::floor(d.periods));
  for (int k = 0; k < K; ++k) {
    const double s0 = k * d.tumbling_period, s1 = (k + 1) * d.tumbling_period;
    double sum = 0;
    int n = 0;
    for (std::size_t i = 0; i < r.strain_h.size(); ++i)
      if (r.strain_h[i] >= s0 && r.strain_h[i] < s1) {
        sum += r.area_h[i];
        ++n;
      }
    d.window_mid.push_back(0.5 * (s0 + s1));
    d.window_mean.push_back(n > 0 ? sum / n : kNaN);
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < r.strain_h.size(); ++i)
    if (r.strain_h[i] >= 10.0) {
      sx += r.strain_h[i];
      sy += r.area_h[i];
      sxx += r.strain_h[i] * r.strain_h[i];
      sxy += r.strain_h[i] * r.area_h[i];
      ++n;
    }
  if (n > 2 && end > 20.0) {
    d.rate = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    d.per_period = d.rate * d.tumbling_period;
  }
  return d;
}

std::string tag(const StudyRun& m) { return vv::fmt("tau%g", m.c.tau) + vv::fmt("_ca%g", m.ca_factor); }
std::string label(const StudyRun& m) { return vv::fmt("tau_ex=%g", m.c.tau) + vv::fmt(" Ca x%g", m.ca_factor); }

StudyRun run_one(const char* case_name, const std::string& kind, double h_um, double tau, double ca, double strain) {
  StudyRun m{kind, ca, vv::stability_map_config(h_um, tau, ca, strain), {}};
  try {
    m.r = vv::run_rbc(m.c, case_name);
  } catch (const std::exception& e) {
    m.r.diverged = true;
    m.r.diagnosis = std::string("could not start: ") + e.what();
  }
  vv::print_run(m.c, m.r);
  return m;
}

std::map<std::string, io::Value> row_of(const StudyRun& m, const Drift& d) {
  auto row = vv::run_row(m.c, m.r);
  row["kind"] = m.kind;
  row["ca_factor"] = m.ca_factor;
  row["reynolds_lattice"] = m.c.reynolds;
  row["stability_max_dt_factor"] = m.r.stability_factor;
  row["status"] = std::string(m.r.diverged ? "diverged" : "stable");
  row["tumbling_period_strain"] = d.tumbling_period;
  row["membrane_period_strain"] = d.membrane_period;
  row["tumbling_periods_covered"] = d.periods;
  row["max_area_change_to_strain10"] = d.max_to_10;
  row["max_area_change_first_half"] = d.max_first_half;
  row["max_area_change_second_half"] = d.max_second_half;
  row["area_drift_rate_per_strain"] = d.rate;
  row["area_drift_per_period"] = d.per_period;
  row["strain_at_area_bound"] = d.strain_at_bound;
  return row;
}

void add_long_series(io::ResultRecord& rec, const StudyRun& m, const Drift& d) {
  const std::string p = label(m);
  // One series per history, all against shear strain.
  auto against_strain = [&](const std::string& name, const std::string& title, const std::string& ylabel,
                            const std::vector<double>& y) {
    io::Series s;
    s.name = p + " " + name;
    s.title = p + ": " + title;
    s.xlabel = "gamma t";
    s.ylabel = ylabel;
    s.x = m.r.strain_h;
    s.y = y;
    rec.add_series(s);
  };
  against_strain("area drift", "A/A0 - 1 against shear strain (h = 0.4 um)", "A/A0 - 1", m.r.area_h);
  against_strain("theta", "inclination theta (unwrapped) against shear strain", "theta (deg)", m.r.theta_h);
  against_strain("edge strain", "largest edge strain |l/l0 - 1| against shear strain", "max edge strain",
                 m.r.estrain_h);
  io::Series w;
  w.name = p + " area drift per period";
  w.title = p + ": mean of A/A0 - 1 over each tumbling period (180 deg of the axis)";
  w.xlabel = "gamma t (period centre)";
  w.ylabel = "period mean of A/A0 - 1";
  w.x = d.window_mid;
  w.y = d.window_mean;
  rec.add_series(w);
}

struct Spec {
  const char* kind;  // "long" or "fine map"
  double h_um, tau, ca, strain;
};

// The study (validation.rbc_viscosity_long_runs, label `study`): every long run and the
// whole second-resolution map. Its subset in `full` (validation.rbc_viscosity_long_runs_subset)
// keeps one run of each kind of verdict: the thesis moduli at the smallest asserted τ_ex
// (no divergence, area within 0.5 %, no secular drift over γ̇t = 150) and the two Ca corners
// at τ_ex = 0.52 at the second resolution (stable there too).
void run_long_runs(const char* case_name, const std::vector<Spec>& specs, const std::string& requirement) {
  vv::Stopwatch total;
  io::ResultRecord rec(case_name, "interior_viscosity");
  rec.set_requirement(requirement);
  rec.set_reference(
      "Stability limits of BGK near tau = 1/2 (docs/stability.md) and of the explicit IB coupling "
      "(membrane::estimate_stability); IB leakage grows when the marker spacing approaches h (Peskin 2002, Acta "
      "Numerica 11:479, recalled: spacing <= h/2). No published map for this set-up: the runs are the measurement.");
  // The runs are independent: at once on the case's cores (one OpenMP thread each, the
  // long ones first; vv::run_concurrently gives the same bits as one after the other).
  std::vector<StudyRun> runs(specs.size());
  std::vector<std::function<void()>> jobs;
  for (std::size_t i = 0; i < specs.size(); ++i)
    jobs.push_back([&, i] {
      const Spec& s = specs[i];
      runs[i] = run_one(case_name, s.kind, s.h_um, s.tau, s.ca, s.strain);
    });
  vv::run_concurrently(jobs);

  std::vector<Drift> drifts;
  for (const StudyRun& m : runs) {
    const Drift d = drift_of(m.r);
    std::printf("%-9s %-20s periods %.2f (T_tumble %.2f, T_membrane %.2f) max|dA| to 10 %.3e, halves %.3e / "
                "%.3e, rate %.3e per strain (%.3e per period), 0.5%% at %.1f\n",
                m.kind.c_str(), label(m).c_str(), d.periods, d.tumbling_period, d.membrane_period, d.max_to_10,
                d.max_first_half, d.max_second_half, d.rate, d.per_period, d.strain_at_bound);
    rec.add_run(row_of(m, d), m.r.scene_text);
    if (m.kind == "long") add_long_series(rec, m, d);
    drifts.push_back(d);
  }
  vv::describe_setup(rec, runs.front().c, runs.front().r);
  rec.set_parameter("viscosity_ratio", 5.0);
  rec.set_parameter("indicator", "flood_fill, updated every step");
  rec.set_parameter("shear_rate_lattice",
                    "fixed at its tau_ex = 1, Re = 0.05 value for every tau_ex (Re = 0.05 * (1/6) / nu_ex), as "
                    "validation.rbc_viscosity_stability");
  std::string long_list, fine_list;  // "(tau_ex, Ca factor)" of each run
  for (const Spec& sp : specs)
    (std::string(sp.kind) == "long" ? long_list : fine_list) += vv::fmt(" (%g, ", sp.tau) + vv::fmt("%g)", sp.ca);
  rec.set_parameter("long_runs", "h = 0.4 um, gamma t = 150, (tau_ex, Ca factor):" + long_list);
  rec.set_parameter("fine_map", "h = 0.3125 um, gamma t = 10, (tau_ex, Ca factor):" + fine_list);
  rec.set_parameter("tumbling_period",
                    "180 deg / |mean body rate over the second half| (the cell's shape repeats each half turn)");
  rec.set_parameter("area_drift_rate",
                    "least-squares slope of A/A0 - 1 against gamma t over gamma t >= 10 (per strain unit; times the "
                    "tumbling period: per period); the first ten strain units hold the start from the rest shape");

  // Fine-map series: stable (1/0) and max |A/A0 − 1| against τ_ex per Ca factor.
  for (double ca : {0.1, 10.0}) {
    io::Series s, st;
    s.name = vv::fmt("fine map area drift Ca x%g", ca);
    s.title = vv::fmt("h = 0.3125 um, gamma t = 10: max |A/A0 - 1| against tau_ex, Ca x%g (stable runs)", ca);
    s.xlabel = st.xlabel = "tau_ex";
    s.ylabel = "max |A/A0 - 1|";
    st.name = vv::fmt("fine map stable Ca x%g", ca);
    st.title = vv::fmt("h = 0.3125 um, gamma t = 10: 1 = stable, 0 = diverged, Ca x%g", ca);
    st.ylabel = "stable";
    for (const StudyRun& m : runs)
      if (m.kind == "fine map" && m.ca_factor == ca) {
        st.x.push_back(m.c.tau);
        st.y.push_back(m.r.diverged ? 0.0 : 1.0);
        if (!m.r.diverged) { s.x.push_back(m.c.tau); s.y.push_back(m.r.max_area_change); }
      }
    rec.add_series(s);
    rec.add_series(st);
  }

  // Metrics.
  int long_diverged = 0, fine_diverged = 0;
  double fine_worst_area = 0;
  bool diagnosed = true;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const StudyRun& m = runs[i];
    const Drift& d = drifts[i];
    if (m.r.diverged && m.r.diagnosis.empty()) diagnosed = false;
    if (m.kind == "long") {
      if (m.r.diverged) ++long_diverged;
      const double rate = (m.r.diverged || std::isnan(d.rate)) ? 1.0 : std::abs(d.rate);
      if (m.ca_factor <= 1.0) {
        rec.add_metric({"max_area_change_" + tag(m), "long run " + label(m) + ": max |A/A0 - 1| over 150 strain units",
                        "", m.r.diverged ? 1.0 : m.r.max_area_change, kAreaBound, 0.0, io::Comparison::at_most,
                        "0.5 % as validation.rbc_shear and the map. The largest edge strain is " +
                            vv::fmt("%.3f", m.r.max_edge_strain) + ", so the marker spacing stays <= " +
                            vv::fmt("%.2f", 0.5 * (1.0 + m.r.max_edge_strain)) +
                            " h and the IB leakage is small and changes sign over the tumbling cycle; a diverged "
                            "run counts as 1"});
        rec.add_metric({"area_drift_rate_" + tag(m),
                        "long run " + label(m) + ": |slope of A/A0 - 1 against gamma t| over gamma t >= 10", "",
                        rate, 1e-5, 0.0, io::Comparison::at_most,
                        "1e-5 per strain unit keeps 0.5 % for 500 strain units (about 35 tumbling periods); "
                        "bounded drift (no secular loss) is the requirement. A diverged run counts as 1"});
      } else {
        rec.add_metric({"area_drift_rate_" + tag(m),
                        "long run " + label(m) + " (soft): |slope of A/A0 - 1 against gamma t| over gamma t >= 10",
                        "", rate, 1e-4, 0.0, io::Comparison::at_most,
                        "NOT the requirement: the soft membrane loses area secularly (measured 2.9e-5 at tau_ex = "
                        "1, 4.8e-5 at 0.52; 0.5 % is crossed near gamma t = 100). Its segments stretch to 1.0-1.7, "
                        "i.e. marker spacing 1-1.4 h, where the IB leaks; a 10x stronger area penalty hardly slows "
                        "the loss (docs). The bound, about 2x the measured rate, flags a worse leak"});
      }
    } else if (m.c.tau >= kTauMinAsserted - 1e-12) {
      if (m.r.diverged) ++fine_diverged;
      fine_worst_area = std::max(fine_worst_area, m.r.diverged ? 1.0 : m.r.max_area_change);
    }
  }
  rec.add_metric({"diverged_long_runs", "long runs (gamma t = 150, h = 0.4 um) that diverged (every Ca)", "",
                  static_cast<double>(long_diverged), 0.0, 0.0, io::Comparison::at_most,
                  "measured: none. E_S/mu in lattice units is the same at every tau_ex (fixed lattice shear rate), "
                  "Ma = 0.006, and tau_in = 1/2 + 5(tau_ex - 1/2) > tau_ex (docs/validation-interior-viscosity.md)"});
  rec.add_metric({"unstable_runs_fine_in_range", "h = 0.3125 um runs with tau_ex >= 0.52 that diverged", "",
                  static_cast<double>(fine_diverged), 0.0, 0.0, io::Comparison::at_most,
                  "the map's statement must not be an artefact of h = 0.4 um. The lattice shear rate is 0.05/(6 a^2), so "
                  "E_S/nu = 0.05/(6 a Ca) and the wall speed 0.2/(6 a) both fall as a/h grows: refining moves "
                  "every point away from the IB and Mach limits"});
  rec.add_metric({"max_area_change_fine_in_range", "h = 0.3125 um, tau_ex >= 0.52: max |A/A0 - 1| over gamma t = 10",
                  "", fine_worst_area, kAreaBound, 0.0, io::Comparison::at_most,
                  "0.5 % as the map at h = 0.4 um; a diverged run counts as 1"});
  rec.add_metric({"every_divergence_diagnosed", "1 if every diverged run carries a diagnosis", "",
                  diagnosed ? 1.0 : 0.0, 1.0, 0.0, io::Comparison::at_least,
                  "a run must never stop silently (health monitor, marker, fill or area diagnosis)"});
  rec.set_wall_time(total.seconds());
  std::printf("written: %s (%.0f s)\n", rec.write_to_results_dir().c_str(), total.seconds());
  for (const auto& m : rec.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}

}  // namespace

TEST(RbcViscosityLongRuns, Full) {
  std::vector<Spec> specs;
  // (1) Long runs at the corners, h = 0.4 µm.
  for (double ca : {0.1, 10.0})
    for (double tau : {0.52, 1.0}) specs.push_back({"long", 0.4, tau, ca, kLongStrain});
  specs.push_back({"long", 0.4, 0.52, 1.0, kLongStrain});  // the thesis moduli at the smallest tau_ex
  // (2) Second resolution, h = 0.3125 µm, γ̇t = 10; τ_ex = 0.505 recorded beyond the asserted range.
  for (double ca : {0.1, 10.0})
    for (double tau : {0.505, 0.52, 1.0}) specs.push_back({"fine map", 0.3125, tau, ca, kMapStrain});
  run_long_runs(
      "validation.rbc_viscosity_long_runs", specs,
      "At viscosity ratio 5 (flood fill), RBC-in-shear runs of 150 strain units (4-12 tumbling periods) at the "
      "corners of the stability map (tau_ex = 0.52 and 1, Ca x0.1 and x10) and at tau_ex = 0.52, Ca x1, h = 0.4 um, "
      "complete without divergence. For Ca <= x1 |A/A0 - 1| stays within 0.5 % and its secular drift is below "
      "1e-5 per strain unit. For Ca x10 the secular area loss is measured (it crosses 0.5 % near gamma t = 100) and "
      "bounded by 1e-4 per strain unit. The corners with tau_ex >= 0.52 are stable at h = 0.3125 um too. A run that "
      "diverges stops with a diagnosis.");
}

TEST(RbcViscosityLongRuns, Subset) {
  run_long_runs("validation.rbc_viscosity_long_runs_subset",
                {{"long", 0.4, 0.52, 1.0, kLongStrain},
                 {"fine map", 0.3125, 0.52, 0.1, kMapStrain},
                 {"fine map", 0.3125, 0.52, 10.0, kMapStrain}},
                "At viscosity ratio 5 (flood fill), the RBC-in-shear run with the thesis moduli at tau_ex = 0.52, "
                "h = 0.4 um, runs 150 strain units without divergence, with |A/A0 - 1| within 0.5 % and a secular "
                "area drift below 1e-5 per strain unit; the Ca x0.1 and x10 corners at tau_ex = 0.52 are stable at "
                "h = 0.3125 um. The verdict-bearing subset of validation.rbc_viscosity_long_runs (label study).");
}
