// validation.rbc_viscosity_contrast (full): issue 5 item 8, viscosity ratio 1 against 5.
// The RBC-in-shear set-up at ratio 1 (indexless: one fluid) and ratio 5 (flood-filled
// cytoplasm, 6.0 cP / 1.2 cP) over γ̇t = 12 at two resolutions: tumbling or
// tank-treading, the rate at which the long axis turns, the strain at which it first
// passes the normal to the flow, and the membrane's rotation relative to the body
// (the tank-treading frequency). docs/validation-interior-viscosity.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <vector>

#include "common/case_support.hpp"
#include "common/concurrent_runs.hpp"
#include "visc_support.hpp"

using namespace erythro;

namespace {

constexpr double kStrain = 12.0;
constexpr double kRatio = 5.0;

// γ̇t at which the long axis has first turned by 90° (passed the normal to the flow);
// +inf if it never does.
double tumble_onset(const vv::RbcResult& r) {
  for (std::size_t i = 0; i < r.theta_h.size(); ++i)
    if (std::abs(r.theta_h[i] - r.theta_h.front()) >= 90.0) return r.strain_h[i];
  return std::numeric_limits<double>::infinity();
}

// Membrane rotation about the centroid relative to the long axis, per unit strain, over
// the whole run (deg; the tank-treading frequency is |this|/360 per unit strain).
double relative_rate(const vv::RbcResult& r) {
  return r.strain > 0 ? (r.marker_rotation_deg - r.body_rotation_deg) / r.strain : 0.0;
}

}  // namespace

TEST(RbcViscosityContrast, FullCase) {
  vv::Stopwatch total;
  io::ResultRecord rec("validation.rbc_viscosity_contrast", "interior_viscosity");
  rec.set_requirement(
      "Raising the interior viscosity ratio from 1 to 5 (flood-filled cytoplasm) makes the RBC in simple shear "
      "tumble, turn its long axis faster, pass the normal to the flow at a smaller strain and lowers the rotation "
      "of its membrane relative to the long axis (tank-treading frequency), at two resolutions.");
  rec.set_reference(
      "Keller & Skalak 1982, J Fluid Mech 120:27 (tank-treading to tumbling as the viscosity ratio rises; the "
      "critical ratio falls as the cell gets less round); 2D capsules and vesicles: Beaucourt et al. 2004 Phys Rev E "
      "69:011906, Kaoui et al. 2009 Phys Rev E 80:061905 (recalled, confidence R: no numbers asserted from them).");
  struct Pair {
    double h;
    vv::RbcResult r1, r5;
  };
  std::vector<Pair> pairs = {{0.3125, {}, {}}, {0.25, {}, {}}};
  auto config = [](double h, bool contrast) {
    return contrast ? vv::thesis_config(h, interior::Method::flood_fill, kRatio, kStrain)
                    : vv::thesis_config(h, interior::Method::indexless, 1.0, kStrain);
  };
  // The four runs are independent: at once on the case's cores (one OpenMP thread each, the
  // finer pair first; vv::run_concurrently gives the same bits as one after the other).
  std::vector<std::function<void()>> jobs;
  for (std::size_t i = pairs.size(); i-- > 0;)
    for (bool contrast : {true, false})
      jobs.push_back([&, i, contrast] {
        const vv::RbcConfig c = config(pairs[i].h, contrast);
        vv::RbcResult& r = contrast ? pairs[i].r5 : pairs[i].r1;
        r = vv::run_rbc(c, "validation.rbc_viscosity_contrast");
        vv::print_run(c, r);
      });
  vv::run_concurrently(jobs);
  bool first = true;
  for (const Pair& p : pairs) {
    const double h = p.h;
    const vv::RbcConfig c1 = config(h, false), c5 = config(h, true);
    if (first) vv::describe_setup(rec, c1, p.r1);
    first = false;
    for (const auto* cr : {&c1, &c5}) {
      const vv::RbcResult& r = cr == &c1 ? p.r1 : p.r5;
      auto row = vv::run_row(*cr, r);
      row["tumble_onset_strain"] = std::isfinite(tumble_onset(r)) ? tumble_onset(r) : -1.0;
      row["body_rate_run_deg_per_strain"] = r.strain > 0 ? r.body_rotation_deg / r.strain : 0.0;
      row["membrane_relative_rate_deg_per_strain"] = relative_rate(r);
      row["tank_treading_frequency_per_strain"] = std::abs(relative_rate(r)) / 360.0;
      row["theta_max_deg"] = r.theta_max;
      rec.add_run(row, r.scene_text);
      vv::add_run_series(rec, vv::run_label(*cr), r, true);
    }
  }
  rec.set_parameter("strain", kStrain);
  rec.set_parameter("ratios", "1 (indexless) and 5 (flood_fill, tau_in = 3)");
  for (const Pair& p : pairs) {
    const std::string at = vv::fmt("h=%g", p.h);
    rec.add_metric({"ratio5_tumbles_" + at, "1 if the ratio-5 cell tumbles (long axis turns >= 90 deg)", "",
                    vv::classify(p.r5) == "tumbling" ? 1.0 : 0.0, 1.0, 0.0, io::Comparison::at_least,
                    "Keller-Skalak: a viscous interior cannot tank-tread fast enough, the body turns with the "
                    "vorticity; the cell (reduced area 0.46) is far from round, so the critical ratio is low"});
    const double b1 = std::abs(p.r1.body_rotation_deg) / p.r1.strain, b5 = std::abs(p.r5.body_rotation_deg) / p.r5.strain;
    rec.add_metric({"body_rate_ratio_" + at, "mean |d theta / d(gamma t)|, ratio 5 over ratio 1", "", b5 / b1, 1.0,
                    0.0, io::Comparison::at_least,
                    "ordering only: more of the vorticity turns the body when tank-treading is hindered"});
    const double o1 = tumble_onset(p.r1), o5 = tumble_onset(p.r5);
    rec.add_metric({"tumble_onset_earlier_" + at, "strain to the first 90 deg turn: ratio 1 minus ratio 5", "",
                    std::isfinite(o1) ? o1 - o5 : kStrain, 0.0, 0.0, io::Comparison::at_least,
                    "ordering only (ratio 1 never turning by 90 deg counts as the run length)"});
    const double t1 = std::abs(relative_rate(p.r1)), t5 = std::abs(relative_rate(p.r5));
    rec.add_metric({"tank_treading_rate_ratio_" + at,
                    "|membrane rotation relative to the long axis| per unit strain, ratio 5 over ratio 1", "",
                    t1 > 0 ? t5 / t1 : 1e9, 1.0, 0.0, io::Comparison::at_most,
                    "ordering only: the viscous interior resists the membrane's circulation round the cell "
                    "(Keller-Skalak: the tank-treading frequency falls as the viscosity ratio rises)"});
  }
  rec.set_wall_time(total.seconds());
  std::printf("written: %s\n", rec.write_to_results_dir().c_str());
  for (const auto& m : rec.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}
