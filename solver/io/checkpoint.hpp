#pragma once
// Checkpoints of a run (docs/cli.md "Checkpoints and restart"): OUT/checkpoint.h5 holds the
// state of every module after one step (sim::Simulation::set_checkpoint_writer, a
// StateRecord) and the scene text the run ran, so that `erythro run --restart OUT`
// continues it bit for bit.
//
// checkpoint.h5 layout:
//   /metadata       attrs step, scene_text, format, erythro_version, git_revision
//   /state/<name>   one float64 dataset per state entry (common/state_record.hpp); the
//                   group's attribute empty_entries (absent if none) lists the entries
//                   with no values
//   /texts          one string attribute per text entry
//
// Rotation: a new checkpoint is written under a temporary name; once it is complete the
// current checkpoint.h5 becomes checkpoint.previous.h5 and the new file takes its place.
// A run killed at any moment leaves at least one complete checkpoint, which
// read_checkpoint finds.
#include <string>

#include "common/state_record.hpp"

namespace erythro::io {

struct Checkpoint {
  std::string path;        // the file it was read from
  long step = 0;           // steps done
  std::string scene_text;  // the scene as it ran (after --set overrides)
  std::string git_revision;  // of the build that wrote it ("" in files that do not say)
  StateRecord state;
};

inline constexpr const char* kCheckpointName = "checkpoint.h5";
inline constexpr const char* kPreviousCheckpointName = "checkpoint.previous.h5";

// Writes the state after `step` steps to OUT/checkpoint.h5 with rotation. Throws OutputError.
void write_checkpoint(const std::string& out_dir, const std::string& scene_text, long step, const StateRecord& state);

// The newest complete checkpoint of a run folder: checkpoint.h5, or checkpoint.previous.h5
// when the first is missing or unreadable. Throws InputError when neither can be read.
Checkpoint read_checkpoint(const std::string& dir);

}  // namespace erythro::io
