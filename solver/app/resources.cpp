// `erythro run`'s resource check (resources.hpp).
#include "app/resources.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "common/error.hpp"

namespace erythro::app {

std::optional<double> available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string key, unit;
    double value = 0.0;
    if (fields >> key >> value >> unit && key == "MemAvailable:" && unit == "kB") return value * 1024.0;
  }
  return std::nullopt;
}

void check_run_resources(const scene::ResourceEstimate& estimate, const std::string& scene_path,
                         bool ignore_memory_check, std::ostream& warnings) {
  const double need = estimate.memory_bytes();
  const std::optional<double> available = available_memory_bytes();
  if (available && need > *available && !ignore_memory_check) {
    const auto largest = std::max_element(estimate.memory.begin(), estimate.memory.end(),
                                          [](const auto& a, const auto& b) { return a.bytes < b.bytes; });
    throw InputError(scene_path + ": the run needs about " + scene::format_bytes(need) +
                     " of memory (an estimate; the largest part: " + largest->what + ", " +
                     scene::format_bytes(largest->bytes) + "), more than the " +
                     scene::format_bytes(*available) +
                     " available (MemAvailable, /proc/meminfo): coarsen domain.spacing_um or shrink domain.size_um "
                     "(`erythro check` shows the estimate), or pass --ignore-memory-check to run it anyway");
  }
  if (estimate.output_bytes() > kLargeOutputBytes)
    warnings << "erythro: warning: " << scene_path << ": the run will write about "
             << scene::format_bytes(estimate.output_bytes()) << " to run.h5 (an estimate: " << estimate.field_snapshots
             << " field snapshots; `erythro check` shows the parts): raise output.fields_interval_steps or "
                "output.diagnostics_interval_steps if that is not intended\n";
}

}  // namespace erythro::app
