#pragma once
// Hemodynamic time through the capillary number ([time_mapping]; docs/model.md §10, eq 10.8):
// the density the run uses so that the particle Reynolds number takes the scene's value while
// every other physical value, and so the clock and the strain, stay as written.
#include <optional>
#include <string>

#include "scene/scene.hpp"

namespace erythro::scene {

struct TimeMapping {
  double reynolds = 0.0;            // Re = γ̇a²ρ_run/μ (time_mapping.reynolds)
  double physical_reynolds = 0.0;   // γ̇a²ρ/μ with fluid.density_kg_m3
  double shear_rate_per_s = 0.0;    // γ̇
  std::string shear_rate_source;    // the key or the rule γ̇ came from
  double radius_m = 0.0;            // a
  std::string radius_source;        // the key or the rule a came from
  double physical_density_kg_m3 = 0.0;  // fluid.density_kg_m3
  double run_density_kg_m3 = 0.0;       // ρ_run = Re μ/(γ̇a²) (eq 10.8)
  double density_factor() const { return run_density_kg_m3 / physical_density_kg_m3; }
};

// Without [time_mapping]: nothing. Otherwise the mapping, or InputError naming the key when γ̇
// or a cannot be found, the scene has no fluid, or the mapping would lower the density.
std::optional<TimeMapping> derive_time_mapping(const Scene& s);

// The density the fluid's lattice runs with: ρ_run with [time_mapping], else fluid.density_kg_m3.
inline double run_density_kg_m3(const Scene& s, const std::optional<TimeMapping>& m) {
  return m ? m->run_density_kg_m3 : s.fluid.density_kg_m3;
}

}  // namespace erythro::scene
