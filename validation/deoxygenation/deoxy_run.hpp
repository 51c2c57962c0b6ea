#pragma once
// The 2D single-RBC deoxygenation model of the validation case (docs/validation-deoxygenation.md):
// a still Evans–Fung biconcave section (geometry::biconcave) centred in a square box of
// half-width L held at C_b on all four sides (fixed_concentration), D2Q5 O2 transport
// (transport::TransportLattice, no fluid lattice; BGK or TRT, Setup::collision), the cell
// by area fractions or ray casting (Setup::representation) and ONE cell-averaged saturation
// S driven by the mean P over the cell's nodes (transport/hb_kinetics.hpp; Setup::coupling):
//   dS/dt = −(k_off/M)[S − (1 − S)(P/P50)ⁿ],  release −C_heme dS/dt spread over the cell.
#include <cstddef>
#include <string>
#include <vector>

#include "common/calibration.hpp"
#include "geometry/polygon.hpp"
#include "transport/hb_kinetics.hpp"
#include "transport/subpixel_diffusivity.hpp"
#include "transport/transport_lattice.hpp"

namespace erythro::deoxy {

// How the cell is put on the lattice (docs/validation-deoxygenation.md, "Representation").
enum class Representation {
  // Nodes inside the polygon by ray casting (geometry::ray_cast_inside_nodes), each a full
  // heme node (weight 1), D_in there, D_out elsewhere. The cell's area is N_int h²: a
  // first-order staircase (13.44 / 13.64 µm² at h = 0.2 / 0.1 µm, exact 13.627).
  ray_cast,
  // Area fraction φ_n ∈ [0, 1] of each node's square (x ± h/2, y ± h/2) inside the polygon
  // (exact polygon–square clipping): heme weight φ_n (release −C_heme φ_n ΔS, mean P
  // weighted by φ_n), D_n = 1/(φ_n/D_in + (1 − φ_n)/D_out), initial C = φ_n αP0 + (1 − φ_n) C_b
  // — the lattice counterpart of the reference's volume-fraction mask (reference_rbc.py).
  // Σ φ_n h² equals the polygon's area to round-off at every h.
  area_fraction,
  // area_fraction for D and the initial C; heme weights by first moments (deoxy_mask.hpp):
  // each cut node's φ spread bilinearly from the centroid of its inside part, so that the
  // release and the mean P see the heme where it is (first moment exact), not at the node.
  area_fraction_moment,
  // area_fraction for D, C0 and the release; the mean P sampled with the first-moment
  // weights (bilinear interpolation of C at each cut node's inside centroid) only.
  area_fraction_moment_sampling,
};

// How S and the lattice's mean P are advanced together over one step (eq H3 of
// transport/hb_kinetics.hpp; P^k = heme-weighted mean P of the lattice after step k,
// r^k = C_heme (S^k − S^{k+1})/α the release of step k in Torr):
enum class Coupling {
  // advance_saturation at P^k (the module's recipe). Stable only for λ_eff Δt < 2, accurate
  // for λ_eff Δt ≪ 1, λ_eff = (k_off/M)(1 + (P/P50)ⁿ)(1 + (C_heme/α) dS_eq/dP) ≈ 3.4e4/M 1/s.
  explicit_lagged,
  // cell-implicit: S^{k+1} from P_end = P^k + r^k (the step's release kept in the cell),
  // solved by bisection — unconditionally stable, but P_end ignores the O2 that leaves the
  // cell during the step: an O(Δt) error of P_end of ≈ r^k itself, which the heme buffer
  // (C_heme/α ≈ 1.6e4 Torr per unit S) makes large: ≈ 0.04 Torr at Δt = 2.5 µs, a shift of
  // S_eq comparable to the kinetic lag (measured: halving Δt moves the fitted ln M by 0.056
  // at h = 0.2 µm).
  cell_implicit,
  // cell-implicit with the outflow predicted from the previous step:
  //   P_end = P^k − o^{k−1} + r^k,   o^{k−1} = P^{k−1} + r^{k−1} − P^k
  // (o = what the lattice took out of the cell's mean P in the last step besides the
  // release): second order on the slow manifold (P_end = 2P^k − P^{k−1} + r^k − r^{k−1}),
  // the release still implicit (the stiff S–P exchange stays stable).
  cell_implicit_outflow,
};

using transport::InterfaceRule;  // membrane diffusivity (transport/subpixel_diffusivity.hpp)

struct Setup {
  double h_um = 0.2;          // lattice spacing
  double dt_s = 1e-5;         // time step
  double box_half_um = 6.0;   // half-width L of the held box (same as the reference)
  double t_end_s = 1.8;
  double C_b_uM = 20.0;       // held on the box
  double P0_torr = 100.0;     // initial equilibrium of the cell
  // Initial free O2 in the cell, µM; < 0: α P0 (in equilibrium with S0 = Hill(P0), the case).
  // A probe value (e.g. C_b) removes the initial jump of C at the membrane (deoxy_probe).
  double C0_in_uM = -1.0;
  double D_out = 2800.0;      // µm²/s (docs/parameters.md)
  double D_in = 950.0;        // µm²/s (Clark et al. 1985, R; PROVENANCE.md)
  double a_um = 3.91;         // equivalent radius (docs/parameters.md)
  int markers = 800;          // polygon resolution of the mask (spacing ≈ 0.024 µm)
  // Offset of the cell's centre from the box centre, in units of h (probe of how the
  // lattice cuts the cell; the centred cell is a symmetric point, so the continuum S̄(t)
  // changes only at second order in the offset).
  double offset_x_h = 0.0, offset_y_h = 0.0;
  transport::HbParameters hb{};  // k_off, C_heme, α, P50, n, M
  // Coupling of S and the lattice O2 over one step (docs/validation-deoxygenation.md):
  Coupling coupling = Coupling::cell_implicit;
  Representation representation = Representation::area_fraction;
  // Collision of the O2 lattice (transport_lattice.hpp): BGK, or TRT with a uniform Λ.
  transport::CollisionModel collision{};
  // Mean P from the source-offset-corrected concentration Ĉ_n = C_n + c q_n / D_n
  // (transport_lattice.hpp eq T7; exact steady finite-volume equivalence for TRT Λ = 1/4);
  // with Coupling::cell_implicit_outflow only (the offset enters its implicit solve).
  bool source_corrected_P = false;
  // Probe: node D by link-wise least squares (deoxy_mask.hpp link_resistivities) instead of
  // the area-fraction series rule.
  bool link_diffusivity = false;
  // Diffusivity at the membrane (area-fraction cells, TRT Λ = 1/4; docs/transport.md §1
  // "Curved diffusivity jumps"): the node series rule (T9), the node subpixel tensor (T10 on each
  // cut node's square, tensor lattice T8), or the face subpixel tensor (T10 on each face's dual
  // cell, imposed on the series lattice by the face-flux correction T11).
  InterfaceRule interface = InterfaceRule::series;
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
  double face_correction_gain = 0.0;  // FaceFluxCorrection::lagged_gain (0: no correction)
  double wall_s = 0.0;
};

Result run(const Setup& s);

// Time step for spacing h keeping D_lat = DΔt/h² of the base level: Δt = dt_at_0p2 (h/0.2 µm)².
// dt_at_0p2 = 10 µs: the thesis point (τ_out = 2.6); 2.5 µs: τ_out = 1.025, τ_in = 0.678.
double diffusive_dt(double h_um, double dt_at_0p2_s = 1e-5);

// Area fraction of each lattice node's unit square [i, i+1] × [j, j+1] inside the polygon
// p (lattice units), exact for the polygon: transport::area_fractions (node index, φ > 0).
using NodeFraction = transport::AreaFraction;
using transport::area_fractions;

// Reads reference_data/deoxygenation/reference_S.csv (columns t_s, S_fine, ...):
// the curve of column `column` (1 = S_fine). Throws InputError when missing.
vv::Curve read_reference(const std::string& path, int column = 1);

}  // namespace erythro::deoxy
