#pragma once
// Where a case's run picks up after its process was killed (CaseRunOptions::resume): long
// studies (hours of runs) survive a kill, a reboot or a time limit and continue where they
// were, through the product's checkpoints (docs/cli.md "Checkpoints and restart"), which end
// in the state of the uninterrupted run bit for bit.
//
// In the run's folder, in this order:
//   - a finished run.h5 of this very scene text, written by this very build: read back, not
//     run again;
//   - else a complete checkpoint of this scene text and build: the run continues from it, and
//     the interrupted run's samples are carried over into its run.h5 (io/run_history.hpp);
//   - else nothing: the run starts afresh (the folder emptied).
// "This very build" is the git revision compiled in; a build from a tree with uncommitted
// changes (revision "…-dirty", or "unknown") never resumes, since its revision does not say
// which code wrote the files.
#include <optional>
#include <string>

#include "io/checkpoint.hpp"
#include "io/run_file.hpp"

namespace erythro::vv {

struct ResumePoint {
  std::optional<io::RunFile> finished;       // a finished run to read back
  std::optional<io::Checkpoint> checkpoint;  // else a checkpoint to continue from
  std::string note;                          // what was found and why it is (not) used
};

// Whether files written by a build of `revision` can be told apart from another build's: a
// clean revision (not "…-dirty", "unknown" or empty).
bool revision_can_resume(const std::string& revision);
// The same for this build (build_info::git_revision()).
bool build_can_resume();

// What the folder `dir` offers a run of `scene_text` (the folder may be missing).
ResumePoint find_resume_point(const std::string& dir, const std::string& scene_text);

}  // namespace erythro::vv
