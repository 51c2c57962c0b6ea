#include "simulation/probes/contact_probe.hpp"

#include <algorithm>
#include <stdexcept>

#include "simulation/cell_physics.hpp"

namespace erythro::sim {

namespace {
double repulsion_range(const aggregation::CellContacts& c) {
  return c.law().repulsion ? c.law().repulsion->range : 0.0;
}
}  // namespace

ContactProbe::ContactProbe(const CellPhysics& cells, long extremes_interval)
    : cells_(cells), extremes_interval_(extremes_interval) {
  if (!cells.contacts()) throw std::logic_error("ContactProbe: the cells have no contact forces");
  min_gap_ = cells.contacts()->cutoff();
  min_wall_gap_ = repulsion_range(*cells.contacts());
}

void ContactProbe::declare(std::vector<SeriesInfo>& series) const {
  series.push_back({"contacts_min_gap_um", "um",
                    "smallest distance so far between markers of different cells (the contact cut-off while none "
                    "came closer)"});
  series.push_back({"contacts_min_wall_gap_um", "um",
                    "smallest distance so far between a marker and a wall (the repulsion range while none came "
                    "closer)"});
  series.push_back({"contacts_pairs", "", "marker pairs of different cells within the contact cut-off, now"});
}

void ContactProbe::track() {
  const aggregation::ContactStats& s = cells_.contact_stats();
  min_gap_ = std::min(min_gap_, s.min_pair_distance);
  min_wall_gap_ = std::min(min_wall_gap_, s.min_wall_distance);
}

void ContactProbe::register_stages(TimeLoop& loop) {
  if (extremes_interval_ <= 0) return;
  // Observe phase: the contact forces of this step were computed from its marker positions.
  loop.add(Phase::observe, "contact_extremes", [this](long) { track(); }, extremes_interval_, extremes_interval_ - 1);
}

void ContactProbe::sample(const ProbeContext& context, std::span<double> values) {
  track();
  const double um = context.setup.scales.length_m * 1e6;
  values[0] = min_gap_ * um;
  values[1] = min_wall_gap_ * um;
  values[2] = static_cast<double>(cells_.contact_stats().pairs);
}

}  // namespace erythro::sim
