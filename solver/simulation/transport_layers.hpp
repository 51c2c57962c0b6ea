#pragma once
// The per-node fields of one species from its values everywhere and its [[transport.layers]]
// bands (docs/scenes.md "[[transport.layers]]"; scene::TransportLayerSetup): a node whose square lies in one band
// takes the band's D, k and q; a node cut by a band's edge mixes them by the fractions f_j of
// its square (k and q arithmetically, D by transport.layer_mean: harmonic 1/D = Σ f_j/D_j, the
// series rule across the bands, or arithmetic), the species' values filling what no band covers.
#include <vector>

#include "lattice/grid.hpp"
#include "scene/units.hpp"

namespace erythro::sim {

// Lattice units; a field is empty where it is uniform and needs no per-node storage: D without
// layers (the species' uniform D), q and k when zero everywhere.
struct LayerFields {
  std::vector<double> D, decay, source;
};

LayerFields layer_fields(const scene::TransportSetup& setup, int species, const Grid& grid);

}  // namespace erythro::sim
