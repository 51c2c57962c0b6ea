#include "capsule_bookkeeping.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "capsule_study.hpp"
#include "common/concurrent_runs.hpp"
#include "common/convergence.hpp"

namespace erythro::vv {

using capsule::fmt;

std::string CapsuleBookkeeping::label_of(const CapsuleConfig& c, const std::string& role) {
  return role + "_" + c.law + "_" + std::string(ib::to_string(c.kernel)) + fmt("_G%g", c.capillary) +
         fmt("_a%g", c.radius) + fmt("_Re%g", c.reynolds) + fmt("_H%g", c.height) + fmt("_L%g", c.length);
}

void CapsuleBookkeeping::prefetch(const std::vector<std::pair<CapsuleConfig, std::string>>& plan) {
  // Every set-up is checked before any runs: a rejected scene ends the case at once instead
  // of after the runs' minutes.
  for (const auto& [config, role] : plan) check_capsule(config);
  std::vector<std::size_t> order(plan.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto cost = [&](std::size_t i) {  // nodes × steps per strain unit ∝ (a/h)^4 H L / Re
    const CapsuleConfig& c = plan[i].first;
    return std::pow(c.radius, 4) * c.height * c.length / c.reynolds;
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cost(a) > cost(b); });
  std::vector<CapsuleResult> results(plan.size());
  std::vector<std::function<void()>> jobs;
  for (std::size_t i : order)
    jobs.push_back([&, i] {
      results[i] = run_capsule(plan[i].first, record.case_name(), label_of(plan[i].first, plan[i].second));
    });
  run_concurrently(jobs);
  for (std::size_t i = 0; i < plan.size(); ++i) prefetched[label_of(plan[i].first, plan[i].second)] = results[i];
}

CapsuleResult CapsuleBookkeeping::run(const CapsuleConfig& c, const std::string& role) {
  const std::string label = label_of(c, role);
  const auto found = prefetched.find(label);
  EXPECT_TRUE(prefetched.empty() || found != prefetched.end()) << label << " is missing from the study's plan";
  const CapsuleResult r = found != prefetched.end() ? found->second : run_capsule(c, record.case_name(), label);
  EXPECT_FALSE(r.diverged) << label << ": " << r.diagnosis;
  if (r.strain >= c.max_strain - 0.05) ++capped;
  if (!(std::abs(r.D_unit_change) < c.steady_drift)) ++unsteady;
  max_area = std::max(max_area, std::abs(r.area_change));
  max_restored = std::max(max_restored, std::abs(r.area_restored));
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
                  {"law", c.law},
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
                  {"D_unit_mean_change", r.D_unit_change},
                  {"tank_treading_period_gamma_t", r.tt_period},
                  {"area_change", r.area_change},
                  {"area_restored", r.area_restored},
                  {"wall_time_s", r.wall_time_s},
                  {"t_fluid_step_s", r.t_fluid},
                  {"t_membrane_forces_s", r.t_forces},
                  {"t_zero_force_field_s", r.t_zero},
                  {"t_spread_s", r.t_spread},
                  {"t_moments_s", r.t_moments},
                  {"t_interpolate_move_s", r.t_move}},
                 r.scene_text);
  for (const io::FieldPicture& p : r.pictures) record.add_field(p);
  std::printf("%-11s %-11s %-8s G=%.4f a/h=%4.1f Re=%.3f H=%2.0f Lx=%2.0f  D=%.5f th=%6.3f T=%.3f strain=%.1f "
              "dD=%.1e %.1fs\n",
              role.c_str(), c.law.c_str(), std::string(ib::to_string(c.kernel)).c_str(), c.capillary, c.radius,
              c.reynolds, c.height, c.length, r.D, r.theta_deg, r.tt_period, r.strain, r.D_unit_change, r.wall_time_s);
  std::fflush(stdout);
  return r;
}

void CapsuleBookkeeping::record_cost() const {
  const double per_marker_ns = 1e9 * (t_forces + t_spread + t_move) / marker_steps;
  const double fluid_ns = 1e9 * t_fluid / node_steps;
  record.set_parameter("cost_per_marker_step_ns",
                       fmt("%.1f", per_marker_ns) + " ns (forces " + fmt("%.1f", 1e9 * t_forces / marker_steps) +
                           ", spread " + fmt("%.1f", 1e9 * t_spread / marker_steps) + ", interpolate + move " +
                           fmt("%.1f", 1e9 * t_move / marker_steps) + ")");
  record.set_parameter("cost_fluid_per_node_step_ns", fmt("%.2f", fluid_ns));
  {  // marker work per step = fixed + slope × markers (least squares over all runs)
    const double slope = least_squares_slope(run_markers, run_marker_us);
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < run_markers.size(); ++i) {
      mx += run_markers[i];
      my += run_marker_us[i];
    }
    mx /= static_cast<double>(run_markers.size());
    my /= static_cast<double>(run_markers.size());
    record.set_parameter("cost_marker_work_fit", fmt("%.1f", my - slope * mx) + " us per step fixed + " +
                                                     fmt("%.0f", 1e3 * slope) +
                                                     " ns per marker (forces, spread, interpolate, move)");
  }
  record.set_parameter("cost_grid_work_per_node_step_ns",
                       "zeroing the force field " + fmt("%.2f", 1e9 * t_zero / node_steps) +
                           ", support-node velocity for interpolation " + fmt("%.2f", 1e9 * t_moments / node_steps));
  record.set_parameter("cost_overhead_over_fluid_step",
                       fmt("%.3f", t_ib / t_fluid) + " (whole IB cycle); support-node velocity " +
                           fmt("%.3f", t_moments / t_fluid) + ", zeroing the force field " +
                           fmt("%.3f", t_zero / t_fluid) + ", marker work (forces, spread, interpolate) " +
                           fmt("%.3f", (t_forces + t_spread + t_move) / t_fluid));
  std::printf("cost: per marker-step %.1f ns; fluid %.2f ns/node-step; IB/fluid %.3f\n", per_marker_ns, fluid_ns,
              t_ib / t_fluid);
}

}  // namespace erythro::vv
