#pragma once
// `erythro run --restart DIR` (docs/cli.md "Checkpoints and restart"): continues the run
// whose output folder DIR holds a checkpoint. The scene is the checkpoint's (with any --set
// overrides), or a scene file given beside --restart; a scene that differs from the
// checkpoint's in any key but run length and output intervals
// (scene::restart_may_change) is refused with an InputError naming the key. The restarted
// run writes into DIR (or --out); there the interrupted run's run.h5 (or, after a kill,
// its run.h5.partial-<pid>) is first moved to run.interrupted.h5, and after the run its
// history is carried over into the new run.h5 (io/run_history.hpp).
#include <functional>
#include <string>

#include "app/commands.hpp"
#include "io/checkpoint.hpp"
#include "scene/scene.hpp"
#include "simulation/simulation.hpp"

namespace erythro::app {

class Restart {
 public:
  // Reads the checkpoint and builds the scene; throws InputError for a missing checkpoint or
  // a changed scene.
  explicit Restart(const RunOptions& options);

  scene::Scene take_scene() { return std::move(scene_); }
  const std::string& out_dir() const { return out_dir_; }
  long step() const { return checkpoint_.step; }
  // When the restarted run writes into the interrupted run's folder, moves that run's
  // run.h5 aside (run.interrupted.h5) and returns true: its run.xdmf, an index of run.h5, is
  // then rewritten. Returns false for another folder (the history is read in place).
  bool set_aside_interrupted_run();
  // Restores the simulation from the checkpoint (io::run_scene's `configure`).
  std::function<void(sim::Simulation&)> restore();
  // Carries the interrupted run's history over into the new run.h5; returns the note.
  std::string carry_over_history(const std::string& h5_path, const std::string& xdmf_path) const;

 private:
  io::Checkpoint checkpoint_;
  scene::Scene scene_;
  std::string restart_dir_, out_dir_;
  std::string history_;  // the interrupted run's run.h5 ("" if none)
};

}  // namespace erythro::app
