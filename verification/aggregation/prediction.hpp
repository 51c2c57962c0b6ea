#pragma once
// Predicted equilibrium separation of two rigid cells under the pair potential
// (aggregation/morse.hpp), independent of the marker discretization.
#include "aggregation/morse.hpp"

namespace erythro::vv {

// Net Morse force pushing two CONTINUOUS circles (radii R1, R2, centre distance D) apart,
// in lattice units: −dE/dD with E = D_e ∮∮ φ_s(|X1(s) − X2(t)|) ds dt,
// by the periodic trapezoid rule with `points` nodes per circle (only node pairs within
// the cut-off contribute; spectrally accurate for smooth integrands, O(Δs²) here because
// Φ_s'' jumps at the cut-off).
double circle_pair_force(const aggregation::MorseParameters& p, double R1, double R2, double D, int points);

// The gap d* = D* − R1 − R2 at which that force vanishes (the energy minimum):
// bisection between r0/10 and the cut-off.
double circle_pair_gap(const aggregation::MorseParameters& p, double R1, double R2, int points);

}  // namespace erythro::vv
