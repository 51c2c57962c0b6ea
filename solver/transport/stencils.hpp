#pragma once
// Velocity sets of the transport lattice (docs/transport.md §1). Lattice units h = Δt = 1.
//  D2Q5: c0 = (0,0), c1 = (1,0), c2 = (0,1), c3 = (−1,0), c4 = (0,−1);
//        w0 = 1/3, w1–4 = 1/6, so Σ w_i c_i c_i = c_s² I with c_s² = 1/3.
//  D2Q9: the fluid's set (lattice/d2q9.hpp), c_s² = 1/3.
// Both share c_s² = 1/3, so τ_D = ½ + D/c_s² = ½ + 3D for either.
#include <array>

#include "lattice/d2q9.hpp"

namespace erythro::transport {

struct D2Q5 {
  static constexpr int Q = 5;
  static constexpr std::array<int, Q> cx = {0, 1, 0, -1, 0};
  static constexpr std::array<int, Q> cy = {0, 0, 1, 0, -1};
  static constexpr std::array<double, Q> w = {1.0 / 3, 1.0 / 6, 1.0 / 6, 1.0 / 6, 1.0 / 6};
  static constexpr std::array<int, Q> opposite = {0, 3, 4, 1, 2};
};

struct D2Q9 {
  static constexpr int Q = d2q9::Q;
  static constexpr std::array<int, Q> cx = d2q9::cx;
  static constexpr std::array<int, Q> cy = d2q9::cy;
  static constexpr std::array<double, Q> w = d2q9::w;
  static constexpr std::array<int, Q> opposite = d2q9::opposite;
};

inline constexpr double kCs2 = 1.0 / 3.0;  // c_s² of both sets
inline constexpr double kInvCs2 = 3.0;

// Relaxation time of diffusivity D (lattice units): D = c_s² (τ − ½).
inline constexpr double tau_for_diffusivity(double D) { return 0.5 + kInvCs2 * D; }

// Equilibrium linear in u (docs/transport.md eq T2): g_i^eq = w_i C (1 + c_i·u / c_s²).
template <class S>
inline constexpr double equilibrium(int i, double C, double ux, double uy) {
  return S::w[i] * C * (1.0 + kInvCs2 * (S::cx[i] * ux + S::cy[i] * uy));
}

}  // namespace erythro::transport
