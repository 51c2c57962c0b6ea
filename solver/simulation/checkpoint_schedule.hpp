#pragma once
// When a run writes a checkpoint (scene keys output.checkpoint_interval_steps and
// output.checkpoint_interval_s; docs/cli.md "Checkpoints and restart"): after every n-th
// step, and at the first step after each interval of wall time since the start or the last
// checkpoint. The clock is read only when a wall-time interval is set.
#include <chrono>

namespace erythro::sim {

class CheckpointSchedule {
 public:
  CheckpointSchedule(long interval_steps, double interval_s) : steps_(interval_steps), seconds_(interval_s) {}

  bool enabled() const { return steps_ > 0 || seconds_ > 0.0; }
  // Whether the state after `step` steps is to be written.
  bool due(long step) const {
    if (steps_ > 0 && step % steps_ == 0) return true;
    return seconds_ > 0.0 && std::chrono::duration<double>(clock::now() - last_).count() >= seconds_;
  }
  // A checkpoint was written: the wall-time interval starts again.
  void written() { last_ = clock::now(); }

 private:
  using clock = std::chrono::steady_clock;
  long steps_;
  double seconds_;
  clock::time_point last_ = clock::now();
};

}  // namespace erythro::sim
