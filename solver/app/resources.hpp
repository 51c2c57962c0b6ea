#pragma once
// The resource check of `erythro run` (docs/cli.md): refuse a run whose estimated memory
// (scene/resource_estimate.hpp) exceeds the memory available, and warn about a large output,
// before anything is allocated or written.
#include <optional>
#include <ostream>
#include <string>

#include "scene/resource_estimate.hpp"

namespace erythro::app {

// Output volume above which `run` warns (a full disk mid-run loses the run's end).
inline constexpr double kLargeOutputBytes = 10e9;

// MemAvailable of /proc/meminfo in bytes (the kernel's estimate of what can be allocated
// without swapping), or nothing where it cannot be read (then no memory check is made).
std::optional<double> available_memory_bytes();

// Throws InputError (exit code 2) when the estimate exceeds the available memory, unless
// `ignore_memory_check`; writes a warning to `warnings` when the output exceeds kLargeOutputBytes.
// `scene_path` starts the messages.
void check_run_resources(const scene::ResourceEstimate& estimate, const std::string& scene_path,
                         bool ignore_memory_check, std::ostream& warnings);

}  // namespace erythro::app
