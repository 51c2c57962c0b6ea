#pragma once
// Progress of a run on stderr: a one-line display redrawn in place on a terminal
// (step, %, MLUPS, ETA), plain lines every 10 % when stderr is not a terminal.
#include <chrono>

#include "simulation/run_observer.hpp"

namespace erythro::app {

class ProgressDisplay : public sim::RunObserver {
 public:
  explicit ProgressDisplay(bool quiet);
  void on_progress(long step, long total, double mlups) override;
  void on_finish(const sim::RunSummary& summary) override;

 private:
  bool quiet_;
  bool terminal_;
  long next_percent_ = 10;
  long first_step_ = -1;  // the step the run started from (ETA from the steps since)
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace erythro::app
