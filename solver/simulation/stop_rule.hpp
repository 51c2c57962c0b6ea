#pragma once
// A [[stop_when]] rule (scene.hpp StopWhenSpec): evaluated at every diagnostics sample
// on one named series; once its condition holds (and min_steps has passed), the run
// ends after_steps later with status "stopped" and a diagnosis naming the rule.
#include <span>
#include <string>
#include <vector>

#include "common/state_record.hpp"
#include "scene/scene.hpp"
#include "simulation/probe.hpp"

namespace erythro::sim {

class StopRule {
 public:
  // Throws InputError (naming the scene key) when the series is not among `series`.
  StopRule(const scene::StopWhenSpec& spec, std::size_t index, std::span<const SeriesInfo> series,
           const std::string& scene_origin);

  // Shown the row of values of the sample after `step` steps; true when the run ends now.
  bool check(long step, std::span<const double> row);
  // "stop_when[0]: cell_0_taylor_deformation changed by 8.2e-05 < 0.0001 over 1000 steps at step 9000"
  const std::string& diagnosis() const { return diagnosis_; }
  // Checkpoint (common/state_record.hpp), under `prefix`: the earlier samples, when the
  // condition first held and the diagnosis.
  void save_state(StateRecord& record, const std::string& prefix) const;
  void restore_state(const StateRecord& record, const std::string& prefix);

 private:
  scene::StopWhenSpec spec_;
  std::size_t rule_index_ = 0, column_ = 0;
  std::vector<long> steps_;      // earlier samples (change_below only)
  std::vector<double> values_;
  long triggered_at_ = -1;
  std::string diagnosis_;

  // Mean of the earlier samples with after < step ≤ up_to (compare = "window_means"); NaN when
  // there is none.
  double window_mean(long after, long up_to) const;
};

}  // namespace erythro::sim
