// validation.rbc_index_update_interval (full): issue 5 item 1, the cost of skipping
// index-field updates. The flood-filled RBC (ratio 5, γ̇t = 3) with I and τ rebuilt every
// k = 1, 5, 20 (and 100) steps: error in D and θ against k = 1, and the wall time saved.
// docs/validation-interior-viscosity.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "common/case_support.hpp"
#include "visc_support.hpp"

using namespace erythro;

namespace {

constexpr double kStrain = 3.0;
constexpr double kRatio = 5.0;

}  // namespace

TEST(RbcIndexUpdateInterval, Full) {
  vv::Stopwatch total;
  io::ResultRecord rec("validation.rbc_index_update_interval", "interior_viscosity");
  rec.set_requirement(
      "Rebuilding the flood-filled index field every k steps instead of every step changes D and theta of the RBC "
      "at gamma t = 3 by no more than the lag bound below for k <= 20, and reduces the index-field wall time by "
      "about a factor k.");
  rec.set_reference(
      "Issue 5 item 1 (update every k steps); thesis section II.4 (the index field is rebuilt each step). The bound "
      "follows from the marker displacement during k steps (docs/validation-interior-viscosity.md).");
  const double h_um = 0.25;
  const std::vector<int> ks = {1, 5, 20, 100};
  std::vector<vv::RbcResult> res;
  io::SpeedErrorSeries se;
  se.name = "flood_fill every k steps";
  io::Series eD, eT;
  eD.name = "D error vs k";
  eD.title = "|D_k - D_1| at gamma t = 3 against the update interval k";
  eD.xlabel = "k (steps)";
  eD.ylabel = "|D_k - D_1|";
  eT.name = "theta error vs k";
  eT.title = "|theta_k - theta_1| at gamma t = 3 against the update interval k";
  eT.xlabel = "k (steps)";
  eT.ylabel = "|theta_k - theta_1| (deg)";
  for (int k : ks) {
    vv::RbcConfig c = vv::thesis_config(h_um, interior::Method::flood_fill, kRatio, kStrain);
    c.index_update_interval = k;
    res.push_back(vv::run_rbc(c, "validation.rbc_index_update_interval"));
    const vv::RbcResult& r = res.back();
    vv::print_run(c, r);
    auto row = vv::run_row(c, r);
    const double dD = std::abs(vv::final_D(r) - vv::final_D(res.front()));
    const double dT = std::abs(vv::final_theta(r) - vv::final_theta(res.front()));
    row["D_error_vs_k1"] = dD;
    row["theta_error_vs_k1_deg"] = dT;
    row["error"] = dD;
    rec.add_run(row, r.scene_text);
    if (k == 1) vv::describe_setup(rec, c, r);
    se.wall_time_s.push_back(r.wall_time_s);
    se.error.push_back(dD);
    se.label.push_back(vv::fmt("k=%.0f", k));
    eD.x.push_back(k);
    eD.y.push_back(dD);
    eT.x.push_back(k);
    eT.y.push_back(dT);
  }
  rec.add_speed_error(se);
  rec.add_series(eD);
  rec.add_series(eT);
  rec.set_parameter("h_um", h_um);
  rec.set_parameter("viscosity_ratio", kRatio);
  rec.set_parameter("strain", kStrain);
  const vv::RbcResult& r1 = res.front();
  // Lag bound: between rebuilds the membrane moves at most k·u_max, u_max ≈ γ̇(L/2 + ...)
  // ≲ γ̇a per step for a cell centred on the zero-velocity line, so the τ field is at most
  // k γ̇ a lattice units out of place. D and θ respond to the interior viscosity over a
  // strain of order 1 (Fig. II-3 case: ΔD ≈ 0.07, Δθ ≈ 16° between indexless and flood at
  // γ̇t = 3); a displacement δ of the viscous region changes them by about (δ/w)·Δ with w = 2h
  // the band half-width. With the lag averaged over the interval, δ ≈ k γ̇ a / 2.
  for (std::size_t i = 1; i < ks.size(); ++i) {
    const int k = ks[i];
    if (k > 20) continue;  // k = 100: recorded, not asserted
    const double delta = 0.5 * k * r1.gamma_lat * r1.a_lat;  // lattice units
    const double boundD = (delta / 2.0) * 0.07, boundT = (delta / 2.0) * 16.0;
    const std::string at = vv::fmt("k%.0f", k);
    rec.add_metric({"D_error_" + at, "|D_k - D_1| at gamma t = 3", "", eD.y[i], boundD, 0.0, io::Comparison::at_most,
                    vv::fmt("lag bound (delta/w) * 0.07, delta = k gamma a / 2 = %.3g h, w = 2h", delta)});
    rec.add_metric({"theta_error_" + at, "|theta_k - theta_1| at gamma t = 3", "deg", eT.y[i], boundT, 0.0,
                    io::Comparison::at_most,
                    vv::fmt("lag bound (delta/w) * 16 deg, delta = k gamma a / 2 = %.3g h, w = 2h", delta)});
    // What skipping saves is the rebuilds: their count falls by k (asserted, deterministic).
    // The index-field wall time follows it, but a time is measured, never asserted (timer
    // noise on a shared machine): recorded as a parameter.
    const long schedule = (res[i].steps + k - 1) / k;  // before steps 1, 1 + k, 1 + 2k, …
    rec.add_metric({"index_rebuilds_" + at, "index-field rebuilds over the run", "",
                    static_cast<double>(res[i].index_updates), static_cast<double>(schedule), 0.0,
                    io::Comparison::absolute, "one rebuild before every k-th step: ceil(steps/k) exactly"});
    rec.set_parameter("index_time_ratio_" + at, res[i].index_time_s > 0 ? r1.index_time_s / res[i].index_time_s : 0.0);
  }
  rec.set_parameter("index_time_share_k1", r1.wall_time_s > 0 ? r1.index_time_s / r1.wall_time_s : 0.0);
  rec.set_wall_time(total.seconds());
  std::printf("written: %s\n", rec.write_to_results_dir().c_str());
  for (const auto& m : rec.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}
