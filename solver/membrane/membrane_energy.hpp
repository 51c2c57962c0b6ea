#pragma once
// The discrete membrane energy and its exact negative gradient (marker forces).
// Lattice units; energies per unit depth. For a closed polygon X_i, i = 0 … n−1:
//
//  tension  E_T = Σ_e L_e W(λ_e),  λ_e = ℓ_e / L_e         (W: tension_law.hpp, dW/dλ = T)
//           → edge e pulls its ends together with T(λ_e) along the edge (docs/model.md §3).
//  bending  E_B = ½ E_B Σ_i (κ_i − κ0_i)² D̄_i,  κ_i = θ_i / D̄_i
//           θ_i: turning angle at marker i, D̄_i: REST dual length (Lagrangian curvature,
//           curvature per rest arc length; κ_i → λκ as n → ∞). It agrees with the thesis's
//           m = E_B(κ − κ0) (eq 7) to leading order in the strain and exactly for
//           inextensible motion; a uniform dilation leaves θ_i unchanged, so a stretched
//           circle feels no bending force, as q = dm/dl = 0 in the shell model.
//  area     E_A = ½ k_A (A − A0)² / A0                      (penalty: the 2D model keeps
//           the enclosed area by penalty, docs/model.md eq 3.8; k_A has pressure units)
//
// All three depend only on lengths, angles and area, so the energy is invariant
// under rigid motions: the internal forces have zero net force and torque.
#include <span>

#include "membrane/rest_shape.hpp"
#include "membrane/tension_law.hpp"

namespace erythro::membrane {

struct MembraneModel {
  TensionLaw tension;        // law and E_s (lattice)
  double bending = 0.0;      // E_B (lattice)
  double area_modulus = 0.0; // k_A (lattice pressure)
};

struct Energy {
  double tension = 0.0, bending = 0.0, area = 0.0;
  double total() const { return tension + bending + area; }
};

// Energy of the configuration (x, y) relative to the rest shape.
Energy membrane_energy(const MembraneModel& model, const RestShape& rest, std::span<const double> x,
                       std::span<const double> y);

// ADDS F_i = −∂E/∂X_i to (fx, fy) and returns the energy. Sizes must match the rest shape.
Energy add_membrane_forces(const MembraneModel& model, const RestShape& rest, std::span<const double> x,
                           std::span<const double> y, std::span<double> fx, std::span<double> fy);

// The same forces, bit for bit, without the energy (the time step's path: it skips the
// tension law's energy per edge).
void add_membrane_forces_only(const MembraneModel& model, const RestShape& rest, std::span<const double> x,
                              std::span<const double> y, std::span<double> fx, std::span<double> fy);

}  // namespace erythro::membrane
