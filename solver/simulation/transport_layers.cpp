#include "simulation/transport_layers.hpp"

#include <algorithm>

namespace erythro::sim {

namespace {
// Length of [a, b] ∩ [lo, hi].
double overlap(double a, double b, double lo, double hi) { return std::max(0.0, std::min(b, hi) - std::max(a, lo)); }
}  // namespace

LayerFields layer_fields(const scene::TransportSetup& T, int species, const Grid& grid) {
  const scene::SpeciesSetup& sp = T.species[static_cast<std::size_t>(species)];
  std::vector<const scene::TransportLayerSetup*> layers;
  for (const auto& l : T.layers)
    if (l.species == species) layers.push_back(&l);
  LayerFields f;
  const std::size_t N = grid.size();
  bool any_q = sp.source != 0.0, any_k = sp.decay != 0.0;
  for (const auto* l : layers) {
    any_q = any_q || l->source_uM_per_s != 0.0;
    any_k = any_k || l->decay_per_s != 0.0;
  }
  if (any_q) f.source.assign(N, sp.source);
  if (any_k) f.decay.assign(N, sp.decay);
  if (layers.empty()) return f;
  f.D.assign(N, sp.diffusivity);
  const bool harmonic = T.layer_mean != "arithmetic";
  for (int y = 0; y < grid.ny; ++y)
    for (int x = 0; x < grid.nx; ++x) {
      // fractions of node (x, y)'s square [x, x + 1] × [y, y + 1] in each band (lattice units;
      // a full-width band covers the whole x extent: its fraction is the y overlap itself)
      double D = sp.diffusivity, k = sp.decay, q = sp.source;
      double covered = 0.0, q_mix = 0.0, k_mix = 0.0, D_mix = 0.0;
      const scene::TransportLayerSetup* whole = nullptr;
      for (const auto* l : layers) {
        const double fy = overlap(y, y + 1.0, l->y_lo, l->y_hi);
        const double part = l->full_width ? fy : fy * overlap(x, x + 1.0, l->x_lo, l->x_hi);
        if (part <= 0.0) continue;
        if (part >= 1.0) whole = l;
        covered += part;
        q_mix += part * l->source_uM_per_s;
        k_mix += part * l->decay_per_s;
        D_mix += harmonic ? part / l->diffusivity_um2_s : part * l->diffusivity_um2_s;
      }
      if (whole) {  // the square lies in one band: its values as given
        D = T.units.diffusivity(whole->diffusivity_um2_s);
        k = T.units.rate(whole->decay_per_s);
        q = T.units.source(whole->source_uM_per_s);
      } else if (covered > 0.0) {  // cut by a band's edge: mixed, the species' values for the rest
        const double rest = std::max(0.0, 1.0 - covered);
        if (rest > 0.0) {
          q_mix += rest * sp.source_uM_per_s;
          k_mix += rest * sp.decay_per_s;
          D_mix += harmonic ? rest / sp.diffusivity_um2_s : rest * sp.diffusivity_um2_s;
        }
        D = T.units.diffusivity(harmonic ? 1.0 / D_mix : D_mix);
        k = T.units.rate(k_mix);
        q = T.units.source(q_mix);
      }
      const std::size_t n = grid.index(x, y);
      f.D[n] = D;
      if (any_k) f.decay[n] = k;
      if (any_q) f.source[n] = q;
    }
  return f;
}

}  // namespace erythro::sim
