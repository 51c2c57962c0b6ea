// Case verification.couette (issue 2 §9b).
//
// Requirement: plane Couette flow between a fixed wall and a moving wall (halfway
// bounce-back with the wall-momentum term) is reproduced to round-off.
// Reference: u(y) = U y / H, walls at y = 0 and H (exact NS solution). A linear
// profile has no second-derivative truncation error and halfway bounce-back places
// a wall exactly halfway for linear flows, for any τ (Ladd 1994; Krüger et al.
// 2017, The Lattice Boltzmann Method, §5.3.3), so only round-off remains.
// Runs: verification/fluid/channel.toml with boundaries.top a moving wall (U = 0.05
// lattice), from rest to 1e-15 of steady state; the profile is the final middle column.
#include <gtest/gtest.h>

#include "channel_flows.hpp"
#include "common/case_support.hpp"
#include "fluid_scenes.hpp"

using namespace erythro;

TEST(Couette, ExactToRoundOff) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.couette", "fluid");
  record.set_requirement(
      "Plane Couette flow with a moving bounce-back wall is reproduced to round-off (relative L2 <= 1e-12) "
      "for BGK and TRT at several tau and resolutions.");
  record.set_reference("u(y) = U y / H (exact); exactness of halfway bounce-back for linear flow: Krueger et al. "
                       "2017, sec. 5.3.3.");
  record.set_parameter("wall_velocity_lattice", 0.05);
  const vv::SceneFile channel("verification/fluid/channel.toml");
  double worst = 0.0;
  for (auto model : {fluid::CollisionModel::bgk, fluid::CollisionModel::trt}) {
    for (double tau : {0.6, 1.0, 1.5}) {
      for (int N : {8, 16, 32}) {
        const double nu = (tau - 0.5) / 3.0;
        std::vector<std::string> o = {vv::set_grid(4, N), vv::set_collision(model),
                                      vv::set("boundaries.top.type", "\"moving_wall\""),
                                      vv::set("run.steps", vv::steps_to_steady_state(N, nu, 1e-15))};
        o.push_back(vv::set_tau(channel, o, tau));
        o.push_back(vv::set_top_wall_velocity(channel, o, 0.05));
        const std::string label =
            std::string(fluid::to_string(model)) + "_tau" + std::to_string(tau).substr(0, 3) + "_N" + std::to_string(N);
        const auto result = vv::run_channel(channel, o, "verification.couette", label);
        std::vector<double> exact;
        for (int j = 0; j < N; ++j) exact.push_back(0.05 * (j + 0.5) / N);
        const double error = vv::relative_l2(result.ux, exact);
        worst = std::max(worst, error);
        record.add_run({{"model", std::string(fluid::to_string(model))}, {"tau", tau}, {"N", double(N)},
                        {"error_l2", error}, {"wall_time_s", result.wall_time_s}},
                       result.scene_text);
      }
    }
  }
  EXPECT_TRUE(record.add_metric({"max error", "largest relative L2 error over all runs", "", worst, 1e-12, 0.0,
                                 io::Comparison::at_most,
                                 "the scheme is exact for linear flow; only round-off and the 1e-15 steady-state "
                                 "residual remain"}))
      << worst;
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
