#pragma once
// Membrane moduli from physical (SI) to lattice units, 2D model per unit depth.
//
// Lattice units: length h, time Δt, density ρ0 (the fluid's 3D density; the 2D
// model is a slab of unit depth). Derived lattice units:
//   force density (per volume)   ρ0 h / Δt²          [N/m³]
//   force per unit depth         ρ0 h³ / Δt²         [N/m]   (marker force F_m, tension T, E_s)
//   energy per unit depth        ρ0 h⁴ / Δt²         [N = J/m]
//   pressure, k_A                ρ0 h² / Δt²         [Pa]
//   bending modulus E_B          ρ0 h⁵ / Δt²         [J = N·m]
// Reasoning: a tension is a force per unit length of membrane line, i.e. per unit
// depth in 2D: T_lat = T Δt²/(ρ0 h³). The bending energy per depth ½E_B∫(κ−κ0)²dl
// has units [E_B]/m, so E_B is an energy per depth times a length:
// E_B,lat = E_B Δt²/(ρ0 h⁵) (NOT h⁴). Check: the reduced modulus E_B/(a² E_s) is the
// same in both systems. The area penalty ½k_A(A − A0)²/A0 is an energy per depth,
// so k_A is a pressure: k_A,lat = k_A Δt²/(ρ0 h²).
// CGS conveniences: 1 dyn/cm = 1e−3 N/m; 1 dyn·cm = 1e−7 J.
namespace erythro::membrane {

inline constexpr double kDynPerCm = 1e-3;  // N/m
inline constexpr double kDynCm = 1e-7;     // J

struct LatticeScales {
  double h_m = 0.0;            // lattice spacing
  double dt_s = 0.0;           // time step
  double rho_kg_m3 = 0.0;      // fluid density ρ0
};

// E_s (or any tension) [N/m] → lattice.
double tension_to_lattice(double tension_N_m, const LatticeScales& s);
// E_B [J] → lattice.
double bending_to_lattice(double bending_J, const LatticeScales& s);
// k_A [Pa] → lattice.
double pressure_to_lattice(double pressure_Pa, const LatticeScales& s);
// Marker force per unit depth [N/m] → lattice (same unit as a tension).
inline double force_to_lattice(double force_N_m, const LatticeScales& s) { return tension_to_lattice(force_N_m, s); }

}  // namespace erythro::membrane
