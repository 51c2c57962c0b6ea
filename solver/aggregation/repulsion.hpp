#pragma once
// Short-range repulsion between the membranes of different cells and between a membrane
// and a wall (docs/model.md §4b, eqs 4.11–4.13). Lattice units (h = Δt = ρ0 = 1), per unit depth.
//
// Pair density of two membrane elements a distance r apart (eq 4.11):
//
//   Φ_r(r) = P (d/r − 1)²   for r < d,   0 beyond,     Φ_r'(r) = −2P (d/r − 1) d/r²
//
// P a pressure (the same units as the Morse D_e: the pair energy is Φ_r ℓ_m ℓ_n), d the
// range. Energy and force vanish at d (the force continuously), and the energy diverges
// as r → 0, so two flat membranes a gap s apart repel with a pressure that grows like
// πPd²/s² (eq 4.12): no finite stress presses them through each other.
//
// A halfway wall (fluid/boundary.hpp) acts on a marker a distance s from it as a straight
// membrane that is not discretised (eq 4.13): per unit length of membrane
//
//   W(s) = ∫ Φ_r(√(s² + u²)) du = P [2d² atan(a/s)/s − 4d asinh(a/s) + 2a],   a = √(d² − s²),
//   W'(s) = −2P [d² atan(a/s)/s² − a/s]                                   (s < d; 0 beyond)
#include <cmath>

namespace erythro::aggregation {

struct RepulsionParameters {
  double pressure = 0.0;  // P (lattice pressure)
  double range = 0.0;     // d (h)
  bool walls = true;      // also between membranes and the non-periodic sides' walls
};

// Throws std::invalid_argument unless P > 0 and d > 0 (both finite).
void check(const RepulsionParameters& p);

// Φ_r and dΦ_r/dr (eq 4.11).
struct Repulsion {
  explicit Repulsion(const RepulsionParameters& p);
  // Both at once; returns false (and zeros) at r ≥ d.
  bool evaluate(double r, double& phi, double& dphi) const {
    if (!(r < p_.range)) {
      phi = dphi = 0.0;
      return false;
    }
    const double q = p_.range / r - 1.0;
    phi = p_.pressure * q * q;
    dphi = -2.0 * p_.pressure * q * p_.range / (r * r);
    return true;
  }
  const RepulsionParameters& parameters() const { return p_; }

 private:
  RepulsionParameters p_;
};

// The wall's potential per unit membrane length W(s) and dW/ds (eq 4.13) at once (one square
// root and one arctangent), s > 0; returns false (and zeros) at s ≥ d. At s ≤ 0 (a marker on
// or beyond the wall) they are +inf and −inf.
bool wall_evaluate(const RepulsionParameters& p, double s, double& W, double& dW);
// Each alone (tests, diagnostics).
double wall_energy(const RepulsionParameters& p, double s);
double wall_energy_derivative(const RepulsionParameters& p, double s);

}  // namespace erythro::aggregation
