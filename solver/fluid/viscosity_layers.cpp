#include "fluid/viscosity_layers.hpp"

namespace erythro::fluid {

long covered_nodes(const Grid& g, const ViscosityLayer& layer) {
  long count = 0;
  for (int y = 0; y < g.ny; ++y)
    for (int x = 0; x < g.nx; ++x) count += layer.covers(x, y) ? 1 : 0;
  return count;
}

void apply_viscosity_layers(FluidLattice& lattice, std::span<const ViscosityLayer> layers) {
  if (layers.empty()) return;
  lattice.enable_tau_field();
  const Grid& g = lattice.grid();
  const std::span<double> tau = lattice.tau_field();
  for (const ViscosityLayer& layer : layers)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (layer.covers(x, y)) tau[g.index(x, y)] = layer.tau;
  lattice.refresh_tau_rows();
}

}  // namespace erythro::fluid
