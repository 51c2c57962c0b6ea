#pragma once
// Fluid diagnostics at every sample (physical units, per metre of depth):
// total_mass_kg_per_m (Σρ h²ρ0), kinetic_energy_J_per_m (½Σρ|u|²), max_speed_um_s, max_mach,
// momentum_x_N_s_per_m and momentum_y_N_s_per_m (Σρu h²ρ0 · h/Δt).
#include "simulation/probe.hpp"

namespace erythro::sim {

class FluidProbe : public Probe {
 public:
  void declare(std::vector<SeriesInfo>& series) const override;
  void sample(const ProbeContext& context, std::span<double> values) override;
};

}  // namespace erythro::sim
