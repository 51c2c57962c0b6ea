#pragma once
// Morse parameters from physical units to lattice units, and the flat-contact
// analysis that ties the 2D pair density D_e to a surface energy.
//
// 2D pair model (cell_contacts.hpp): E = Σ Φ_s(r_mn) ℓ_m ℓ_n per unit depth, so
// D_e [energy/depth/length²] = [J/m³] = [Pa]; lattice D_e = D_e Δt²/(ρ0 h²)
// (membrane::pressure_to_lattice). r0, r_c: lengths (/h); β: inverse length (·h).
//
// Surface energy. The thesis's D_e (µJ/µm², Zhang et al. 2008 via the Derjaguin
// approximation) is an energy per unit membrane AREA: the local potential of the
// surface separation. Two flat parallel membranes at wall-to-wall gap d interact, per
// unit length of one of them (per depth: per unit area), with
//
//   w(d) = D_e J(d),   J(d) = ∫ φ_s(√(d² + u²)) du  (u along the membrane, φ_s = Φ_s/D_e),
//
// without cut-off J(d) = 2d [e^{2βr0} K1(2βd) − 2 e^{βr0} K1(βd)] (∫e^{−a√(d²+u²)}du = 2d K1(ad)).
// w has units of a surface energy. The flat contact settles at the gap d* where
// w'(d*) = 0 (the integrated Morse force vanishes); its adhesion energy is
// γ = −w(d*) = D_e |J(d*)|. For βd ≫ 1 (Laplace's method, K1(z) ~ √(π/2z)e^{−z}) d* ≈ r0 − ln 2/(2β):
// the pair potential's zero-force distance r0 is NOT the flat-contact gap.
// Matching γ to a given surface energy fixes D_e = γ / |J(d*)| (pair_density_for).
#include "aggregation/morse.hpp"
#include "membrane/membrane_units.hpp"

namespace erythro::aggregation {

inline constexpr double kMicroJoulePerMicron2 = 1e6;  // 1 µJ/µm² in J/m²

struct MorsePhysical {
  double De_Pa = 0.0;        // pair density D_e (J/m³ = Pa)
  double r0_m = 0.0;         // zero-force separation
  double beta_per_m = 0.0;   // decay
  double cutoff_m = 0.0;     // cut-off r_c > r0
};

// Converts and range-checks (std::invalid_argument names the offending quantity):
// D_e ≥ 0, r0 > 0, β > 0, r_c > r0, all finite; h, Δt, ρ0 > 0.
MorseParameters to_lattice(const MorsePhysical& p, const membrane::LatticeScales& s);

// J(d) and dJ/dd of the flat contact, with the cut-off (numerical quadrature over
// |u| < √(r_c² − d²); exact to ~1e-12 relative), in the length unit of p. D_e unused.
double flat_contact_integral(const MorseParameters& p, double d);
double flat_contact_integral_derivative(const MorseParameters& p, double d);

struct FlatContact {
  double gap = 0.0;       // d*: w'(d*) = 0
  double integral = 0.0;  // J(d*) < 0 (a length)
};
// The flat-contact equilibrium of the shifted potential: the first sign change of J'
// from − to + on (0, r_c), refined by bisection to ~1e-12 of r_c.
FlatContact flat_contact(const MorseParameters& p);

// D_e such that the flat contact's adhesion energy −w(d*) equals gamma (same units
// system as p: gamma [energy/area] / |J(d*)| [length]).
double pair_density_for(double gamma, const MorseParameters& shape);

// The thesis's dimensionless surface energy De* (docs/model.md eq 4.7, the project's decision
// of issue 21): γ = De* × kDeStarUnit_J_m2. Provenance: the thesis quotes the surface energy
// 1.3e−7 (ch. IV) and Zhang et al. (2008) 5.2e−8, both printed "µJ/µm²"; read as SI surface
// energies in J/m², their exact ratio 5 : 2 makes them De* = 5 and De* = 2, hence the unit
// 1.3e−7 / 5 = 5.2e−8 / 2 = 2.6e−8 J/m² (docs/parameters.md).
inline constexpr double kDeStarUnit_J_m2 = 2.6e-8;

// γ [J/m²] of a level De* ≥ 0 (eq 4.7); std::invalid_argument if De* is negative or not finite.
double surface_energy_for_de_star(double de_star);
// De* of a surface energy γ [J/m²] (eq 4.7 inverted).
double de_star_for_surface_energy(double gamma_J_m2);

// The estimate of the largest adhesion stress (force per contact area) of a flat contact of
// surface energy gamma: σ_M ≈ γβ/2 (docs/model.md eq 4.8), β the Morse decay. Same units
// system as the arguments (SI: J/m² × 1/m = Pa).
double peak_adhesion_stress(double gamma, double beta);

}  // namespace erythro::aggregation
