#pragma once
// Stability limit of the explicit membrane update X ← X + U Δt coupled to the
// lattice fluid (thesis §II.3), as three capillary-type numbers
//
//   Π_T = K_T Δt² / (ρ0 h³)   K_T = max dT/dλ over λ ∈ [1, max_stretch]  (tension stiffness)
//   Π_B = E_B Δt² / (ρ0 h⁵)                                              (bending)
//   Π_A = k_A Δt² / (ρ0 h²)                                              (area penalty)
//
// (lattice units: Π_T = K_T/ρ0, etc.). Π_T < C is the form of the capillary
// time-step constraint Δt < √(C ρ h³ / σ) of Brackbill, Kothe & Zemach 1992
// (J Comput Phys 100:335; C = 1/(2π) there), with the surface tension σ replaced by
// the membrane's stiffness. The constants C are MEASURED per kernel (divergence
// thresholds of an inflated circle, 10⁴ steps; docs/verification-ib-membrane.md,
// case verification.membrane_stability) and divided by a safety factor 2. The
// thresholds depend only weakly on viscosity for τ ≥ 0.6 (inertial, not Stokes-
// limited: ×2.9 for ×15 in ν); below ν = 1/30 the limits are scaled down ∝ ν.
//
// Separately, the narrow kernels (roma3, linear2) show a slowly growing grid-scale
// tangential marker instability for PRE-STRESSED membranes at every stiffness
// tried; the estimate then carries a warning.
#include <string>

#include "ib/kernel.hpp"
#include "membrane/membrane_energy.hpp"

namespace erythro::membrane {

struct StabilityInput {
  ib::KernelType kernel = ib::KernelType::cosine4;
  MembraneModel model;           // lattice moduli
  double viscosity = 1.0 / 6.0;  // smallest kinematic viscosity ν at the membranes (lattice)
  double density = 1.0;          // ρ0 (lattice)
  double max_stretch = 1.0;      // largest stretch λ expected (≥ 1); > 1 means pre-stress
};

struct StabilityEstimate {
  double tension_number = 0.0, bending_number = 0.0, area_number = 0.0;  // Π_T, Π_B, Π_A
  double tension_limit = 0.0, bending_limit = 0.0, area_limit = 0.0;     // allowed values
  // Largest time-step factor keeping every Π below its limit (Π ∝ Δt²):
  // min √(limit/Π). The set-up is accepted when ≥ 1.
  double max_dt_factor = 0.0;
  std::string problem;  // empty when accepted; otherwise one sentence (see stability.cpp)
  std::string warning;  // empty, or the narrow-kernel pre-stress warning
  bool acceptable() const { return problem.empty(); }
};

StabilityEstimate estimate_stability(const StabilityInput& in);

}  // namespace erythro::membrane
