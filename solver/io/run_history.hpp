#pragma once
// The run.h5 of a restarted run (docs/cli.md "Checkpoints and restart"). The restarted run
// writes its own run.h5 from the checkpoint's step on; afterwards the interrupted run's
// history is carried over into it: the diagnostics samples before the checkpoint's step go
// in front of the restarted run's own (series by name; the rows of /profiles of the same
// samples likewise), and its field and cell frames
// before that step are copied into /fields and /cells; run.xdmf is then rewritten to index
// every frame. /metadata records restarted_from_step and history (where the samples before
// it came from, or that the file starts at the checkpoint).
#include <string>

namespace erythro::io {

inline constexpr const char* kInterruptedRunName = "run.interrupted.h5";

// The interrupted run's file in run folder `dir`: run.h5, else the newest
// run.h5.partial-<pid> a killed run left behind (io/atomic_file.hpp), else the
// run.interrupted.h5 an earlier restart set aside and did not replace (it failed before its
// run), else "".
std::string interrupted_run_file(const std::string& dir);

// Before a restart writes into `dir`: moves the interrupted run's `file` (interrupted_run_file)
// to dir/run.interrupted.h5 and returns that path ("" for ""). Throws OutputError.
std::string set_aside_interrupted_run(const std::string& file, const std::string& dir);

// `previous_h5`: the interrupted run's file ("" if there is none). Returns the history note
// written to /metadata: "carried over from <file>", or why the file starts at the
// checkpoint (no earlier file, unreadable, different series). Throws OutputError only when
// `h5` itself cannot be updated.
std::string carry_over_history(const std::string& previous_h5, const std::string& h5, const std::string& xdmf,
                               long checkpoint_step);

}  // namespace erythro::io
