#pragma once
// Health of the immersed cells (the run monitor, docs/architecture.md): every marker
// position and force finite, every cell's area within max_area_change of its rest area
// (|A/A0 − 1|), every edge within max_edge_strain of its rest length (|ℓ/ℓ0 − 1|). A torn
// or leaking membrane fails here before anything of it is written.
#include "common/health.hpp"
#include "membrane/immersed_cells.hpp"

namespace erythro::membrane {

struct CellHealthLimits {
  double max_area_change = 0.2;
  double max_edge_strain = 1.0;
};

// The first violation: quantity "cell <c> marker position" / "cell <c> marker force" (NaN
// limit: not finite), "cell <c> area change", "cell <c> edge strain"; node_x holds the
// cell, node_y the marker (−1 for the area).
HealthReport check_health(const ImmersedCells& cells, const CellHealthLimits& limits);

}  // namespace erythro::membrane
