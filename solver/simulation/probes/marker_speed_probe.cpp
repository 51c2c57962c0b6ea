#include "simulation/probes/marker_speed_probe.hpp"

#include <algorithm>

#include "simulation/cell_physics.hpp"

namespace erythro::sim {

MarkerSpeedProbe::MarkerSpeedProbe(const CellPhysics& cells, long extremes_interval)
    : cells_(cells), extremes_interval_(extremes_interval) {}

void MarkerSpeedProbe::declare(std::vector<SeriesInfo>& series) const {
  series.push_back({"cells_max_marker_speed_um_s", "um/s", "max over markers and tracked steps of the marker speed"});
}

void MarkerSpeedProbe::register_stages(TimeLoop& loop) {
  if (extremes_interval_ <= 0) return;
  // Observe phase: the markers have just moved with the velocity of this step.
  loop.add(
      Phase::observe, "marker_speed_extremes",
      [this](long) { max_speed_ = std::max(max_speed_, cells_.cells().max_marker_speed()); }, extremes_interval_,
      extremes_interval_ - 1);
}

void MarkerSpeedProbe::sample(const ProbeContext& context, std::span<double> values) {
  max_speed_ = std::max(max_speed_, cells_.cells().max_marker_speed());  // the samples count too
  values[0] = max_speed_ * context.setup.scales.velocity_m_s() * 1e6;
}

}  // namespace erythro::sim
