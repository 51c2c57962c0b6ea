#pragma once
// The configurations of the doublet cases (one place, shared by the tests and the
// documentation's figures): docs/validation-doublet.md.
#include <vector>

#include "doublet_shear_run.hpp"

namespace erythro::vv {

// Study lattice: h = 0.3 µm (a/h = 13.0, 100 × 100 nodes for 30 × 30 µm), lattice
// Re = γ̇a²/ν = 0.1 (≈ 10 100 steps per strain unit); 100 markers per cell (thesis).
DoubletShearConfig study_config();
// CI lattice: h = 0.5 µm (a/h = 7.8, 60 × 60 nodes), same groups.
DoubletShearConfig ci_config();

// Item 5: surface-energy levels at 100 1/s: levels k of the old reading, γ = k·E_S0.
std::vector<double> surface_energy_levels();
// Item 5, second start: rims 1.0 µm apart (3.3 h on the study lattice: the film between the
// membranes resolved) instead of d*, at the (old-reading) levels that bracket the transition from it
// (docs/validation-doublet.md §3 "Longer runs and other starts").
double wide_start_gap_m();
std::vector<double> wide_start_levels();
// Item 6: cases I–IV at 50 1/s, E_S of the second cell (dyn/cm ×1e-3); the first keeps 6.0.
struct DeformabilityCase {
  const char* name;
  double delta_Es;  // ×1e-3 dyn/cm
};
std::vector<DeformabilityCase> deformability_cases();
// The level k of the old reading (γ = k·E_S0, doublet_scene.hpp surface_energy_J_m2).
double deformability_old_reading_de_star();
// The run of one case: 50 1/s, the level above, second cell E_S0 + ΔE_S, start gap below.
DoubletShearConfig deformability_config(const DeformabilityCase& c);
// Issue 21 items 2, 3, 5: the same studies under the project's De* (γ = De* × 2.6e−8 J/m²,
// docs/model.md eq 4.7): the thesis's levels De* = 1…5 at 100 1/s (study lattice, the d* start
// and the 1.0 µm start of surface_energy_levels / wide_start_levels) ...
std::vector<double> de_star_levels();
DoubletShearConfig de_star_config(double de_star);
// ... and cases I–IV at 50 1/s at De* = 5 (γ = 1.3e−7 J/m², the thesis's ch. IV value; its ch. III
// level at 50 1/s is not in our copy), otherwise deformability_config's run.
double deformability_de_star();
DoubletShearConfig deformability_de_star_config(const DeformabilityCase& c);
// Issue 21 item 4, the dissociation map: per De*, the critical shear rate bisected (geometric
// midpoints) in [lo, hi] 1/s, the rims 1.0 µm apart at start (wide_start_gap_m, the film resolved);
// otherwise de_star_config's run (study lattice, lattice Re fixed: the same steps per strain unit
// at every shear rate, docs/model.md eq 10.7), k_A lowered below 50 1/s (doublet_cases.cpp).
std::vector<double> dissociation_map_levels();
struct ShearBracket {
  double lo, hi;  // 1/s
  int steps;      // bisection steps after the two ends
};
ShearBracket dissociation_map_bracket();
DoubletShearConfig dissociation_map_config(double de_star, double shear_rate);
// Item 7: rigid-limit sequence for one ellipse (a/b = 2): capillary number and viscosity ratio.
struct RigidLevel {
  double capillary, viscosity_ratio;
};
std::vector<RigidLevel> rigid_levels();
DoubletShearConfig rigid_config(const RigidLevel& level);

}  // namespace erythro::vv
