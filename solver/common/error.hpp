#pragma once
// Error types shared by every layer. Each maps to one documented exit code of the
// `erythro` command (docs/cli.md): the app layer catches them, nothing below does.
#include <stdexcept>
#include <string>

namespace erythro {

// Bad input: malformed scene, unknown key, wrong type, value out of range,
// impossible physics. Message names file, key, value and the allowed range.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An output could not be written (unwritable folder, folder in use by another run,
// existing output without --force, a failed write: disk full, quota).
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace exit_code {
inline constexpr int ok = 0;
inline constexpr int runtime_failure = 1;  // unexpected internal error
inline constexpr int bad_input = 2;        // scene or command-line error
inline constexpr int diverged = 3;         // health monitor stopped the run
inline constexpr int output_failure = 4;   // output folder unwritable, in use, or would be overwritten; a write failed
inline constexpr int regression = 5;       // `compare`: a quantity moved beyond its tolerance; `schema --check`: stale page
// A run ended by SIGINT or SIGTERM exits with 128 + the signal number (130, 143), as the
// shell reports a process killed by it, so scripts see the interruption either way.
inline constexpr int interrupted_base = 128;
}  // namespace exit_code

}  // namespace erythro
