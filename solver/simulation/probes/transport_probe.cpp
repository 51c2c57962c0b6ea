#include "simulation/probes/transport_probe.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "simulation/transport_physics.hpp"

namespace erythro::sim {

TransportProbe::TransportProbe(const TransportPhysics& transport)
    : transport_(transport), worst_(transport.species_count(), 0.0) {}

void TransportProbe::declare(std::vector<SeriesInfo>& series) const {
  for (std::size_t i = 0; i < transport_.species_count(); ++i) {
    const std::string& n = transport_.name(i);
    series.push_back({n + "_mean_uM", "uM", "mean concentration of " + n + " over the nodes"});
    series.push_back({n + "_mass_balance_residual", "",
                      "relative mass-balance residual of the last transport step (docs/transport.md eq T5)"});
    series.push_back({n + "_max_mass_balance_residual", "", "largest |relative residual| of any transport step so far"});
  }
  for (std::size_t c = 0; c < transport_.saturation().size(); ++c)
    series.push_back({"cell_" + std::to_string(c) + "_saturation", "", "cell-averaged HbO2 saturation"});
}

void TransportProbe::track_residuals() {
  for (std::size_t i = 0; i < transport_.species_count(); ++i)
    worst_[i] = std::max(worst_[i], std::abs(transport_.lattice(i).mass_balance().relative_residual()));
}

void TransportProbe::register_stages(TimeLoop& loop) {
  loop.add(Phase::observe, "transport_residuals", [this](long) { track_residuals(); });
}

void TransportProbe::sample(const ProbeContext& context, std::span<double> values) {
  const double nodes = static_cast<double>(context.setup.grid.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < transport_.species_count(); ++i) {
    const auto& lat = transport_.lattice(i);
    values[k++] = lat.total_amount() / nodes;
    values[k++] = context.step == 0 ? 0.0 : lat.mass_balance().relative_residual();
    values[k++] = worst_[i];
  }
  for (double S : transport_.saturation()) values[k++] = S;
}

}  // namespace erythro::sim
