#pragma once
// D2Q9 velocity set (docs/model.md §1, thesis §II.3). Lattice units: h = Δt = 1.
#include <array>

namespace erythro::d2q9 {

inline constexpr int Q = 9;
inline constexpr double cs2 = 1.0 / 3.0;  // speed of sound squared
inline constexpr double inv_cs2 = 3.0;

// Kinematic viscosity of relaxation time τ, ν = c_s²(τ − ½) (lattice units, docs/model.md
// §1), and back. The one place this relation is written; (τ − ½)/3 and ½ + 3ν exactly.
constexpr double viscosity_of_tau(double tau) { return (tau - 0.5) / 3.0; }
constexpr double tau_of_viscosity(double nu) { return 0.5 + 3.0 * nu; }
inline constexpr double inv_cs4 = 9.0;

// c0=(0,0), c1=(1,0), c2=(0,1), c3=(-1,0), c4=(0,-1), c5=(1,1), c6=(-1,1), c7=(-1,-1), c8=(1,-1)
inline constexpr std::array<int, Q> cx = {0, 1, 0, -1, 0, 1, -1, -1, 1};
inline constexpr std::array<int, Q> cy = {0, 0, 1, 0, -1, 1, 1, -1, -1};
inline constexpr std::array<double, Q> w = {4.0 / 9,  1.0 / 9,  1.0 / 9,  1.0 / 9, 1.0 / 9,
                                            1.0 / 36, 1.0 / 36, 1.0 / 36, 1.0 / 36};
// c_i·a for a lattice direction, with c_1·a = a_x and c_2·a = a_y written without their zero
// term. Written out, a_x + 0·a_y costs a multiplication and an addition per node that strict
// IEEE rules (contraction off, signed zeros kept) do not let the compiler drop. Leaving the
// term out gives the same value always, and the same bits unless the kept component is −0
// (−0 + 0·a_y is +0 for a_y ≥ 0): only the sign of a zero can differ. The other directions
// are computed as written (for c_3, −a_x + 0·a_y is +0 where −a_x alone is −0 at a_x = +0).
// With i known at compile time (an unrolled loop) the branches fold away.
inline constexpr double dot_c(int i, double ax, double ay) {
  if (cx[i] == 1 && cy[i] == 0) return ax;
  if (cx[i] == 0 && cy[i] == 1) return ay;
  return cx[i] * ax + cy[i] * ay;
}

// opposite[i]: the direction with c = -c_i (bounce-back partner).
inline constexpr std::array<int, Q> opposite = {0, 3, 4, 1, 2, 7, 8, 5, 6};

// Second-order equilibrium, eq 16: w_i ρ [1 + c·u/cs² + (c·u)²/(2cs⁴) − u·u/(2cs²)].
inline constexpr double equilibrium(int i, double rho, double ux, double uy) {
  const double cu = cx[i] * ux + cy[i] * uy;
  const double uu = ux * ux + uy * uy;
  return w[i] * rho * (1.0 + inv_cs2 * cu + 0.5 * inv_cs4 * cu * cu - 0.5 * inv_cs2 * uu);
}

// The same, minus the rest weight: f^eq_i − w_i, computed without cancellation.
inline constexpr double equilibrium_deviation(int i, double rho, double ux, double uy) {
  const double cu = cx[i] * ux + cy[i] * uy;
  const double uu = ux * ux + uy * uy;
  return w[i] * ((rho - 1.0) + rho * (inv_cs2 * cu + 0.5 * inv_cs4 * cu * cu - 0.5 * inv_cs2 * uu));
}

}  // namespace erythro::d2q9
