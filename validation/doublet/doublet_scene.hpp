#pragma once
// The scene of one doublet (or single-cell) run: validation/doublet/doublet.toml or
// single_cell.toml with the overrides that set a DoubletShearConfig's physical inputs,
// the cells' placement and the run control, exactly as `erythro run FILE --set ...`
// would read them.
#include <string>
#include <vector>

#include "doublet_shear_run.hpp"
#include "scene/scene.hpp"

namespace erythro::vv {

struct DoubletScene {
  std::string path;                     // the TOML beside the case (from the source tree)
  std::vector<std::string> overrides;   // --set overrides
  scene::Scene scene;                   // parsed and checked
  double gamma = 0.0;                   // lattice shear rate γ̇Δt (strain per step)
  long sample_every = 1;                // steps between samples (output.diagnostics_interval_steps)
};

DoubletScene doublet_scene(const DoubletShearConfig& c);

// The surface energy γ [J/m²] of the run: the old reading's level k times E_S0 (docs/model.md
// eq 4.7, the documented alternative), with E_S0 as the scene reads it back from
// membrane.shear_modulus_dyn_cm: bit for bit the γ the former `aggregation.de_star = k` gave;
// with c.de_star ≥ 0 the project's reading instead, γ = De* × 2.6e−8 J/m²
// (aggregation::surface_energy_for_de_star: the γ the scene key aggregation.de_star gives).
double surface_energy_J_m2(const DoubletShearConfig& c);
// The old reading's level γ/E_S0 of the run (= c.old_reading_de_star unless c.de_star is set).
double old_reading_level(const DoubletShearConfig& c);

// The series of the run's angle θ: the pair's line of centres, or the single cell's long axis.
const char* theta_series(const DoubletShearConfig& c);

}  // namespace erythro::vv
