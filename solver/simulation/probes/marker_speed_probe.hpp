#pragma once
// Speed of the membrane markers (docs/model.md §2: U_m, the fluid velocity interpolated
// at marker m, which moved it in the last step), over all cells:
//   cells_max_marker_speed_um_s  max |U_m| over the markers, at every sample and, with
//                                output.extremes_interval_steps = k > 0, after every k-th
//                                step: the running maximum so far (e.g. k = 1: over every
//                                step of a cell at rest, verification.membrane_rest_in_fluid)
// 0 at step 0 (no marker has moved yet).
#include "simulation/probe.hpp"

namespace erythro::sim {

class MarkerSpeedProbe : public Probe {
 public:
  // `cells` must outlive the probe; extremes_interval 0: at the samples only.
  MarkerSpeedProbe(const CellPhysics& cells, long extremes_interval);
  void declare(std::vector<SeriesInfo>& series) const override;
  void sample(const ProbeContext& context, std::span<double> values) override;
  void register_stages(TimeLoop& loop) override;
  void save_state(StateRecord& record, const std::string& prefix) const override {
    record.put_scalar(prefix + "max_speed", max_speed_);
  }
  void restore_state(const StateRecord& record, const std::string& prefix) override {
    max_speed_ = record.scalar(prefix + "max_speed");
  }

 private:
  const CellPhysics& cells_;
  long extremes_interval_;
  double max_speed_ = 0.0;  // lattice
};

}  // namespace erythro::sim
