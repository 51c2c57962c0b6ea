#pragma once
// The 2D single-RBC deoxygenation model of the validation case (docs/validation-deoxygenation.md):
// a still Evans–Fung biconcave section (membrane::biconcave) centred in a square box of
// half-width L held at C_b on all four sides (fixed_concentration), D2Q5 O2 transport
// (transport::TransportLattice, no fluid lattice), interior nodes by ray casting
// (Setup::representation) and ONE cell-averaged saturation S driven by the mean P over
// the cell's nodes (transport/hb_kinetics.hpp):
//   dS/dt = −(k_off/M)[S − (1 − S)(P/P50)ⁿ],  release −C_heme dS/dt spread over the cell.
#include <cstddef>
#include <string>
#include <vector>

#include "common/calibration.hpp"
#include "membrane/polygon.hpp"
#include "transport/hb_kinetics.hpp"

namespace erythro::deoxy {

// How the cell is put on the lattice (docs/validation-deoxygenation.md, "Representation").
enum class Representation {
  // Nodes inside the polygon by ray casting (interior::ray_cast_inside_nodes), each a full
  // heme node (weight 1), D_in there, D_out elsewhere. The cell's area is N_int h²: a
  // first-order staircase (13.44 / 13.64 µm² at h = 0.2 / 0.1 µm, exact 13.627).
  ray_cast,
  // Area fraction φ_n ∈ [0, 1] of each node's square (x ± h/2, y ± h/2) inside the polygon
  // (exact polygon–square clipping): heme weight φ_n (release −C_heme φ_n ΔS, mean P
  // weighted by φ_n), D_n = 1/(φ_n/D_in + (1 − φ_n)/D_out), initial C = φ_n αP0 + (1 − φ_n) C_b
  // — the lattice counterpart of the reference's volume-fraction mask (reference_rbc.py).
  // Σ φ_n h² equals the polygon's area to round-off at every h.
  area_fraction,
};

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
  Representation representation = Representation::area_fraction;
};

struct Result {
  vv::Curve S;                 // cell-averaged saturation vs t (s)
  long steps = 0;
  int nodes = 0;               // per side
  long interior_nodes = 0;             // nodes carrying heme (φ > 0, or inside by ray casting)
  double interior_area_um2 = 0.0;      // Σ φ_n h² (ray casting: N_int h²)
  double polygon_area_um2 = 0.0;       // area of the marker polygon (exact section: 13.627)
  double released_uM_um2 = 0.0;       // Σ O2 released by Hb (per unit depth)
  double medium_change_uM_um2 = 0.0;  // M(end) − M(0) of the transport lattice
  double boundary_in_uM_um2 = 0.0;    // Σ boundary_in (negative: outflow)
  double balance_residual = 0.0;      // (change − boundary_in − released) / released
  double max_step_residual = 0.0;     // max relative_residual() of the module's balance
  double wall_s = 0.0;
};

Result run(const Setup& s);

// Time step for spacing h keeping D_lat = DΔt/h² of the base level: Δt = dt_at_0p2 (h/0.2 µm)².
// dt_at_0p2 = 10 µs: the thesis point (τ_out = 2.6); 2.5 µs: τ_out = 1.025, τ_in = 0.678.
double diffusive_dt(double h_um, double dt_at_0p2_s = 1e-5);

// Area fraction of each lattice node's unit square [i, i+1] × [j, j+1] inside the polygon
// p (lattice units), for the nodes of an nx × ny grid whose square meets p's bounding box;
// exact for the polygon (Sutherland–Hodgman clipping against the convex square; a
// non-convex polygon clips to the correct area). Returns (node index, φ > 0) pairs.
struct NodeFraction {
  std::size_t node = 0;
  double phi = 0.0;
};
std::vector<NodeFraction> area_fractions(const membrane::Polygon& p, int nx, int ny);

// Reads reference_data/deoxygenation/reference_S.csv (columns t_s, S_fine, ...):
// the curve of column `column` (1 = S_fine). Throws InputError when missing.
vv::Curve read_reference(const std::string& path, int column = 1);

}  // namespace erythro::deoxy
