// Exploration (not a V&V case, not registered with ctest; disabled by default): does the
// "no dissociation at 100 1/s" result of validation.doublet_surface_energy depend on the
// run length or the start? docs/validation-doublet.md §3 "Longer runs and other starts".
// Run: vv_doublet --gtest_also_run_disabled_tests --gtest_filter=DoubletExplore.*
// Environment (all optional): DOUBLET_DE="0,0.25" (levels k of the old reading, γ = k·E_S0), DOUBLET_THETA0 (deg, line of
// centres at start, default 90), DOUBLET_GAP_UM (rim gap at start, µm; default d*),
// DOUBLET_TURN_DEG (stop once θ fell this far below θ0, default 360), DOUBLET_STRAIN
// (cap, default 30), DOUBLET_H_UM (lattice spacing, default 0.3), DOUBLET_KEEP (strain units
// kept after dissociation, default 0.5).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "doublet_cases.hpp"
#include "doublet_outcome.hpp"
#include "doublet_record.hpp"

using namespace erythro;

namespace {
double env_or(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v ? std::atof(v) : fallback;
}
std::vector<double> env_list(const char* name, std::vector<double> fallback) {
  const char* v = std::getenv(name);
  if (!v) return fallback;
  std::vector<double> out;
  std::stringstream ss(v);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(std::atof(item.c_str()));
  return out;
}
// Separation of centres and smallest membrane gap (µm) where the unwrapped θ crosses `level`
// (interpolated linearly between samples), each crossing in either direction.
void print_crossings(const vv::DoubletShearResult& r, double level) {
  for (std::size_t i = 1; i < r.theta_h.size(); ++i) {
    const double a = r.theta_h[i - 1] - level, b = r.theta_h[i] - level;
    if ((a > 0) == (b > 0)) continue;
    const double w = a / (a - b);
    auto lerp = [&](const std::vector<double>& y) { return y[i - 1] + w * (y[i] - y[i - 1]); };
    std::printf("  cross theta=%.0f at gt=%.2f: separation %.3f um, gap %.3f um\n", level, lerp(r.strain_h),
                lerp(r.separation_h), lerp(r.gap_h));
  }
}
}  // namespace

TEST(DoubletExplore, DISABLED_LongRunsAndStarts) {
  const std::vector<double> levels = env_list("DOUBLET_DE", {0.0, 0.25});
  const double theta0 = env_or("DOUBLET_THETA0", 90.0);
  const double gap_um = env_or("DOUBLET_GAP_UM", -1.0);
  const double turn = env_or("DOUBLET_TURN_DEG", 360.0);
  for (double de : levels) {
    vv::DoubletShearConfig c = vv::study_config();
    c.h_m = env_or("DOUBLET_H_UM", 0.3) * 1e-6;
    c.old_reading_de_star = de;  // γ = de·E_S0
    c.theta0_deg = theta0;
    c.initial_gap_m = gap_um > 0 ? gap_um * 1e-6 : -1.0;
    c.strain = env_or("DOUBLET_STRAIN", 30.0);
    c.stop_theta_deg = theta0 - turn;
    c.stop_after_dissociation = env_or("DOUBLET_KEEP", c.stop_after_dissociation);
    const std::string label = vv::fmt("De*=%.2g", de) + vv::fmt(" theta0=%.0f", theta0) +
                              (gap_um > 0 ? vv::fmt(" gap=%.2fum", gap_um) : std::string(" gap=d*"));
    const vv::DoubletShearResult r = vv::run_doublet_shear(c, "doublet_explore", label);
    vv::print_run(label, r);
    const double rc_um = (c.r0_m + c.cutoff_k / c.beta_per_m) * 1e6;
    const double max_sep = r.separation_h.empty() ? 0 : *std::max_element(r.separation_h.begin(), r.separation_h.end());
    const double max_gap = r.gap_h.empty() ? 0 : *std::max_element(r.gap_h.begin(), r.gap_h.end());
    std::printf("SUMMARY %s: outcome=%s dissociated=%d at gt=%.2f strain=%.2f theta_end=%.1f max_sep=%.3f um "
                "max_gap=%.3f um (r_c %.2f um) start gap %.3f um dA=%.2e eps=%.3f wall=%.1fs\n",
                label.c_str(), vv::doublet_outcome(r).c_str(), r.dissociated ? 1 : 0, r.dissociation_strain, r.strain,
                r.theta_h.empty() ? 0.0 : r.theta_h.back(), max_sep, max_gap, rc_um,
                r.gap_h.empty() ? 0.0 : r.gap_h.front(), r.max_area_change, r.max_edge_strain, r.wall_time_s);
    for (double level = 90.0; level >= theta0 - turn - 1.0; level -= 90.0) print_crossings(r, level);
    std::fflush(stdout);
  }
}
