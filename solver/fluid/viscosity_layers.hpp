#pragma once
// Regions of another viscosity (a scene's [[fluid.layers]], docs/scenes.md): each node
// whose centre (x + ½, y + ½) lies in a layer's rectangle [x_lo, x_hi) × [y_lo, y_hi)
// (lattice units) gets that layer's relaxation time through the lattice's per-node τ
// field; later layers win over earlier ones, other nodes keep the collision's τ.
// ν = (τ − ½)/3 (docs/model.md eq 1.6), so a layer sets the node viscosity.
#include <span>

#include "fluid/fluid_lattice.hpp"

namespace erythro::fluid {

struct ViscosityLayer {
  double x_lo = 0.0, x_hi = 0.0, y_lo = 0.0, y_hi = 0.0;
  double tau = 0.0;
  bool covers(int x, int y) const {
    const double px = x + 0.5, py = y + 0.5;
    return px >= x_lo && px < x_hi && py >= y_lo && py < y_hi;
  }
};

// Nodes of `grid` inside the layer's rectangle.
long covered_nodes(const Grid& grid, const ViscosityLayer& layer);

// Enables the τ field (if there are layers) and writes every layer into it, in order.
void apply_viscosity_layers(FluidLattice& lattice, std::span<const ViscosityLayer> layers);

}  // namespace erythro::fluid
