#pragma once
// Transport diagnostics at every sample: per species <name>_mean_uM (mean concentration
// over the nodes), <name>_mass_balance_residual (relative residual of the last transport
// step, docs/transport.md eq T5; 0 at step 0) and <name>_max_mass_balance_residual (the
// largest |residual| after any transport step so far); with [hemoglobin], per cell
// cell_c_saturation (cell-averaged HbO2 saturation).
#include <vector>

#include "simulation/probe.hpp"

namespace erythro::sim {

class TransportProbe : public Probe {
 public:
  explicit TransportProbe(const TransportPhysics& transport);
  void declare(std::vector<SeriesInfo>& series) const override;
  void sample(const ProbeContext& context, std::span<double> values) override;
  void register_stages(TimeLoop& loop) override;

 private:
  void track_residuals();
  const TransportPhysics& transport_;
  std::vector<double> worst_;  // per species, max |residual| so far
};

}  // namespace erythro::sim
