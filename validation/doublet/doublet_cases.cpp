#include "doublet_cases.hpp"

#include <algorithm>

namespace erythro::vv {

DoubletShearConfig study_config() {
  DoubletShearConfig c;
  c.h_m = 0.3e-6;
  c.reynolds = 0.1;
  c.strain = 14.0;
  c.stop_theta_deg = -92.0;          // half a revolution of the pair done (θ: +90° → −90°)
  c.stop_after_dissociation = 0.5;
  return c;
}

DoubletShearConfig ci_config() {
  DoubletShearConfig c = study_config();
  c.h_m = 0.5e-6;
  c.area_modulus = 50.0;  // k_A ∝ E_S/a ∝ 1/a²: 100 E_S/a exceeds the explicit IB limit at a/h = 7.8
  return c;
}

std::vector<double> surface_energy_levels() { return {0.0, 0.25, 0.5, 1.0}; }

double wide_start_gap_m() { return 1.0e-6; }
std::vector<double> wide_start_levels() { return {0.0, 0.25}; }

std::vector<DeformabilityCase> deformability_cases() {
  return {{"I", 0.0}, {"II", 3.0}, {"III", 4.5}, {"IV", 12.0}};
}

double deformability_old_reading_de_star() { return 0.5; }

DoubletShearConfig deformability_config(const DeformabilityCase& cs) {
  DoubletShearConfig c = study_config();
  c.shear_rate = 50.0;
  c.old_reading_de_star = deformability_old_reading_de_star();
  c.Es1_N_m = c.Es0_N_m + cs.delta_Es * 1e-6;  // 1e-3 dyn/cm = 1e-6 N/m
  c.initial_gap_m = 1.0e-6;  // rims 1 µm apart (within r_c = 1.79 µm): the approach is part of the run
  return c;
}

std::vector<double> de_star_levels() { return {1.0, 2.0, 3.0, 4.0, 5.0}; }

DoubletShearConfig de_star_config(double de_star) {
  DoubletShearConfig c = study_config();
  c.de_star = de_star;
  return c;
}

std::vector<double> dissociation_map_levels() { return {1.0, 2.0, 3.0, 4.0, 5.0}; }

ShearBracket dissociation_map_bracket() { return {1.0, 100.0, 6}; }

DoubletShearConfig dissociation_map_config(double de_star, double shear_rate) {
  DoubletShearConfig c = de_star_config(de_star);
  c.initial_gap_m = wide_start_gap_m();
  c.shear_rate = shear_rate;
  // At fixed lattice Re the explicit IB limit of the area penalty, Π_A = k_A Δt²/(ρ0 h²), grows
  // as 1/γ̇ (Δt ∝ 1/γ̇, ρ0 ∝ 1/γ̇): 100 E_S/a is within it down to 50 1/s (validation.doublet_deformability);
  // below, k_A is lowered in proportion to γ̇ (fixed in lattice units, as rigid_config). The area
  // change stays asserted (≤ 0.5 %).
  c.area_modulus = 100.0 * std::min(1.0, shear_rate / 50.0);
  return c;
}

double deformability_de_star() { return 5.0; }

DoubletShearConfig deformability_de_star_config(const DeformabilityCase& cs) {
  DoubletShearConfig c = deformability_config(cs);
  c.de_star = deformability_de_star();
  return c;
}

std::vector<RigidLevel> rigid_levels() { return {{0.005, 5.0}, {0.0025, 6.5}, {0.00125, 8.0}}; }

DoubletShearConfig rigid_config(const RigidLevel& level) {
  DoubletShearConfig c = study_config();
  c.cells = 1;
  c.shape = CellShape::ellipse;
  c.ellipse_axis_ratio = 2.0;
  c.theta0_deg = 30.0;
  c.viscosity_ratio = level.viscosity_ratio;
  // E_S from Ca = μγ̇a/E_S; E_B scaled with it (E_B* fixed at the thesis value 0.0039).
  c.Es0_N_m = c.Es1_N_m = c.mu_Pa_s * c.shear_rate * c.a_m / level.capillary;
  c.Eb_J = 3.6e-19 * c.Es0_N_m / 6e-6;
  // k_A in units of E_S/a lowered in proportion to Ca (k_A fixed in lattice units at the
  // value of the thesis cell, 100 E_S/a at Ca = 0.0782): 100 E_S/a of a 60× stiffer
  // membrane exceeds the explicit IB limit; a stiff membrane keeps its area by tension.
  c.area_modulus = 100.0 * level.capillary / 0.0782;
  c.old_reading_de_star = 0.0;
  c.strain = 12.0;
  c.stop_theta_deg = -92.0;
  return c;
}

}  // namespace erythro::vv
