#pragma once
// How close the membranes of different cells, and a membrane and a wall, have come
// (docs/model.md §4b), for scenes with [repulsion]:
//   contacts_min_gap_um       the smallest distance between two markers of different
//                             cells so far: at every sample and, with
//                             output.extremes_interval_steps = k > 0, after every k-th
//                             step; the contact cut-off while no pair has come closer
//   contacts_min_wall_gap_um  the same for a marker and a wall (the repulsion range while
//                             none has come closer, or no wall)
//   contacts_pairs            marker pairs of different cells within the cut-off, now
// Read from the contact forces' statistics of the last step (CellPhysics::contact_stats).
#include "simulation/probe.hpp"

namespace erythro::sim {

class ContactProbe : public Probe {
 public:
  // `cells` (with contact forces) must outlive the probe; extremes_interval 0: at the samples only.
  ContactProbe(const CellPhysics& cells, long extremes_interval);
  void declare(std::vector<SeriesInfo>& series) const override;
  void sample(const ProbeContext& context, std::span<double> values) override;
  void register_stages(TimeLoop& loop) override;
  void save_state(StateRecord& record, const std::string& prefix) const override {
    record.put(prefix + "closest", std::vector<double>{min_gap_, min_wall_gap_});
  }
  void restore_state(const StateRecord& record, const std::string& prefix) override {
    const std::vector<double>& v = record.get(prefix + "closest", 2);
    min_gap_ = v[0];
    min_wall_gap_ = v[1];
  }

 private:
  void track();
  const CellPhysics& cells_;
  long extremes_interval_;
  double min_gap_, min_wall_gap_;  // lattice; start at the cut-off and the range
};

}  // namespace erythro::sim
