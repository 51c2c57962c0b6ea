#pragma once
// Wall-bounded channel flows used by several fluid cases: a periodic strip of nx × N
// nodes between halfway bounce-back walls at y = 0 and y = N (lattice units), run as
// the scene verification/fluid/channel.toml with overrides (fluid_scenes.hpp).
#include <string>
#include <vector>

#include "common/scene_case.hpp"
#include "common/scene_file.hpp"

namespace erythro::vv {

// Steps needed for a flow started from rest between walls N apart to come within
// `residual` (relative) of steady state: the slowest mode sin(πy/N) decays like
// exp(−ν(π/N)² t), so t = ln(1/residual) N² / (ν π²).
long steps_to_steady_state(int N, double nu, double residual);

struct ChannelResult {
  std::vector<double> ux;  // final velocity profile across the channel (middle column, lattice units)
  long steps = 0;
  double wall_time_s = 0.0;  // the run's time loop
  std::string scene_text;    // what ran (record.add_run(row, scene_text))
};

// Runs the channel scene with `overrides` (which set run.steps) through the product path
// and returns the final profile of the middle column, bit for bit as computed (a
// sim::FieldsRecorder besides the run writer; `options` may add stages and observers).
ChannelResult run_channel(const SceneFile& file, const std::vector<std::string>& overrides,
                          const std::string& case_name, const std::string& label, CaseRunOptions options = {});

// Exact force-driven Poiseuille profile at node centres y = j + ½: u = F y (N − y) / (2ν).
std::vector<double> poiseuille_exact(int N, double force, double nu);

}  // namespace erythro::vv
