#pragma once
// The 2D single-RBC deoxygenation model of the validation case (docs/validation-deoxygenation.md):
// a still Evans–Fung biconcave section (membrane::biconcave) centred in a square box of
// half-width L held at C_b on all four sides (fixed_concentration), D2Q5 O2 transport
// (transport::TransportLattice, no fluid lattice), interior nodes by ray casting
// (interior::ray_cast_inside) with D_in, D_out elsewhere, and ONE cell-averaged
// saturation S driven by the mean P over the interior nodes (transport/hb_kinetics.hpp):
//   dS/dt = −(k_off/M)[S − (1 − S)(P/P50)ⁿ],  release −C_heme dS/dt spread uniformly.
#include <string>

#include "common/calibration.hpp"
#include "transport/hb_kinetics.hpp"

namespace erythro::deoxy {

struct Setup {
  double h_um = 0.2;          // lattice spacing
  double dt_s = 1e-5;         // time step
  double box_half_um = 6.0;   // half-width L of the held box (same as the reference)
  double t_end_s = 1.8;
  double C_b_uM = 20.0;       // held on the box
  double P0_torr = 100.0;     // initial equilibrium of the cell
  double D_out = 2800.0;      // µm²/s (parameters.md)
  double D_in = 950.0;        // µm²/s (Clark et al. 1985, R; PROVENANCE.md)
  double a_um = 3.91;         // equivalent radius (parameters.md)
  int markers = 800;          // polygon resolution of the mask (spacing ≈ 0.024 µm)
  transport::HbParameters hb{};  // k_off, C_heme, α, P50, n, M
  // Coupling of S and the lattice O2 over one step (docs/validation-deoxygenation.md):
  //  false: explicit — advance_saturation at the mean P of the step's start (the module's
  //         recipe). Stable only for λ_eff Δt < 2, accurate for λ_eff Δt ≪ 1, with
  //         λ_eff = (k_off/M)(1 + (P/P50)ⁿ)(1 + (C_heme/α) dS_eq/dP) ≈ 3.4e4/M 1/s near P50;
  //  true : cell-implicit — P at the END of the step, P_new = P + C_heme (S − S_new)/α
  //         (the released O2 still in the cell), S_new = advance_saturation(S, P_new)
  //         solved by bisection: unconditionally stable.
  bool implicit_coupling = true;
};

struct Result {
  vv::Curve S;                 // cell-averaged saturation vs t (s)
  long steps = 0;
  int nodes = 0;               // per side
  long interior_nodes = 0;
  double interior_area_um2 = 0.0;
  double released_uM_um2 = 0.0;       // Σ O2 released by Hb (per unit depth)
  double medium_change_uM_um2 = 0.0;  // M(end) − M(0) of the transport lattice
  double boundary_in_uM_um2 = 0.0;    // Σ boundary_in (negative: outflow)
  double balance_residual = 0.0;      // (change − boundary_in − released) / released
  double max_step_residual = 0.0;     // max relative_residual() of the module's balance
  double wall_s = 0.0;
};

Result run(const Setup& s);

// Time step for spacing h keeping D_lat = DΔt/h² of the base level (10 µs at 0.2 µm).
double diffusive_dt(double h_um);

// Reads reference_data/deoxygenation/reference_S.csv (columns t_s, S_fine, ...):
// the curve of column `column` (1 = S_fine). Throws InputError when missing.
vv::Curve read_reference(const std::string& path, int column = 1);

}  // namespace erythro::deoxy
