#pragma once
// The coupled step of a user's scene (`erythro bench --coupled-only --scene FILE`, issue 18): the
// scene's cells and physics as it sets them, beside the same scene without its cells. The shear
// boxes of coupled_bench.hpp measure how the cost grows with the cell count; this measures what a
// study's own scene (the channel's, say) costs per cell and step. Informative only.
#include <string>

#include "app/coupled_bench.hpp"

namespace erythro::io {
class ResultRecord;
}

namespace erythro::app {

// Runs the scene at `path` (cells required) for options.steps steps (rounded up to whole index-field
// intervals), options.pairs pairs, on each of options.threads; prints the table and adds the runs
// and metrics to `record`. Throws scene::InputError for a scene without cells or with bad input.
void run_scene_bench(const std::string& path, const CoupledBenchOptions& options, io::ResultRecord& record);

}  // namespace erythro::app
