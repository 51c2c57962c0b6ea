#pragma once
// One run of the 2D single-RBC deoxygenation model (docs/validation-deoxygenation.md): the scene
// validation/deoxygenation/deoxygenation.toml (a still Evans–Fung biconcave section centred in a
// square box held at C_b, D2Q5 O2 transport, ONE cell-averaged saturation driven by the cell's
// mean P) with the overrides a Setup asks for, run through the product path
// (vv::run_case_scene, as `erythro run ... --set ...`); the transport options are the scene's
// ([transport], [hemoglobin]; solver/simulation/transport_physics.hpp):
//   dS/dt = −(k_off/M)[S − (1 − S)(P/P50)ⁿ],  release −C_heme dS/dt spread over the cell.
#include <cstddef>
#include <string>
#include <vector>

#include "common/calibration.hpp"
#include "io/result_record.hpp"
#include "transport/hb_kinetics.hpp"
#include "transport/transport_lattice.hpp"

namespace erythro::deoxy {

// How the cell is put on the lattice (transport.cell_representation, hemoglobin.heme_weights).
enum class Representation {
  // Nodes inside the polygon by ray casting, each a full heme node (weight 1), D_in there, D_out
  // elsewhere: a first-order staircase (13.44 / 13.64 µm² at h = 0.2 / 0.1 µm, exact 13.627).
  ray_cast,
  // Area fraction φ_n of each node's square inside the polygon (exact clipping): heme weight φ_n,
  // D_n = 1/(φ_n/D_in + (1 − φ_n)/D_out), C0 = φ_n αP0 + (1 − φ_n) C_b — the lattice counterpart
  // of the reference's volume-fraction mask (reference_rbc.py).
  area_fraction,
  // area_fraction with first-moment heme weights (transport/heme_weights.hpp) for the release
  // and the mean P, or for the mean P only.
  area_fraction_moment,
  area_fraction_moment_sampling,
};

// How S and the lattice's mean P are advanced together over one step (hemoglobin.coupling;
// docs/transport.md §4.2, simulation/cell_transport.hpp): the lagged explicit update, the plain
// cell-implicit one (P_end = P^k + r^k: an O(Δt) error ≈ r^k, which moved the fitted ln M by
// 0.056 at h = 0.2 µm when Δt was halved) and the cell-implicit one with the outflow of the last
// step predicted (P_end = P^k − o^{k−1} + r^k; second order on the slow manifold).
enum class Coupling { explicit_lagged, cell_implicit, cell_implicit_outflow };

// Membrane diffusivity (transport.interface; docs/transport.md eqs T9–T11).
enum class InterfaceRule { series, node_tensor, face_tensor };

// Which cell the lattice holds: the planar section (deoxygenation.toml) or the cell of revolution
// on the axisymmetric lattice (deoxygenation_axisymmetric.toml: the cylinder r ≤ L, |z| ≤ L of the
// 3D reference, the cell centred on the axis).
enum class Geometry { planar, axisymmetric };
// hemoglobin.kinetics: one S per cell (the thesis's model, calibrated by M) or one per heme node.
enum class Kinetics { cell_mean, local };

struct Setup {
  Geometry geometry = Geometry::planar;
  Kinetics kinetics = Kinetics::cell_mean;
  double h_um = 0.2;          // lattice spacing
  double dt_s = 1e-5;         // time step
  double box_half_um = 6.0;   // half-width L of the held box (same as the reference)
  double t_end_s = 1.8;
  double C_b_uM = 20.0;       // held on the box
  double P0_torr = 100.0;     // initial equilibrium of the cell
  // Initial free O2 in the cell, µM; < 0: α P0 (in equilibrium with S0 = Hill(P0), the case).
  double C0_in_uM = -1.0;
  double D_out = 2800.0;      // µm²/s (docs/parameters.md)
  double D_in = 950.0;        // µm²/s (Clark et al. 1985, R; PROVENANCE.md)
  double a_um = 3.91;         // equivalent radius (docs/parameters.md)
  int markers = 800;          // polygon resolution of the mask (spacing ≈ 0.024 µm)
  // Offset of the cell's centre from the box centre, in units of h (a probe of how the lattice
  // cuts the cell).
  double offset_x_h = 0.0, offset_y_h = 0.0;
  transport::HbParameters hb{};  // k_off, C_heme, α, P50, n, M (σ = 1: the scene has no shear)
  Coupling coupling = Coupling::cell_implicit;
  Representation representation = Representation::area_fraction;
  transport::CollisionModel collision{};
  // Mean P with the source offset of eq T7 in the implicit update (hemoglobin.mean_pressure =
  // "source_corrected"; with Coupling::cell_implicit_outflow only).
  bool source_corrected_P = false;
  InterfaceRule interface = InterfaceRule::series;
};

struct Result {
  vv::Curve S;                 // cell-averaged saturation vs t (s): series time_s, cell_0_saturation
  long steps = 0;
  int nodes = 0;               // per side
  long interior_nodes = 0;             // nodes carrying heme
  double interior_area_um2 = 0.0;      // Σ heme weights h² (axisymmetric: the cell's volume, 2π Σ φ r h³, µm³)
  double polygon_area_um2 = 0.0;       // area of the marker polygon (exact section: 13.627)
  // The O2 balance at the end, per unit depth (µM·µm²; axisymmetric: per radian, µM·µm³):
  double released_uM_um2 = 0.0;       // cell_0_released_…
  double medium_change_uM_um2 = 0.0;  // O2_amount_change_…
  double boundary_in_uM_um2 = 0.0;    // O2_boundary_inflow_… (negative: outflow)
  double balance_residual = 0.0;      // (change − boundary_in − released) / released
  double max_step_residual = 0.0;     // O2_max_mass_balance_residual at the end
  double wall_s = 0.0;
  std::string scene_text;             // the scene as run (for the record)
};

// The scene's overrides for a set-up (docs/validation-deoxygenation.md, "Set-up").
std::vector<std::string> scene_overrides(const Setup& s);

// Runs the scene of s into <results>/runs/<case_name>/<label> (removed after it has been read
// unless keep). Throws std::runtime_error with the monitor's diagnosis if the run diverged.
Result run(const Setup& s, const std::string& case_name, const std::string& label, bool keep = false);

// Field pictures for the report: the scene of s run to t_s (a moment of the transient) into
// <results>/runs/<case_name>/<label>, O2 concentration with the membrane at that time.
std::vector<io::FieldPicture> transient_pictures(Setup s, double t_s, const std::string& case_name,
                                                 const std::string& label);

// Time step for spacing h keeping D_lat = DΔt/h² of the base level: Δt = dt_at_0p2 (h/0.2 µm)².
// dt_at_0p2 = 10 µs: the thesis point (τ_out = 2.6); 2.5 µs: τ_out = 1.025, τ_in = 0.678.
double diffusive_dt(double h_um, double dt_at_0p2_s = 1e-5);

// Reads reference_data/deoxygenation/reference_S.csv (columns t_s, S_fine, ...):
// the curve of column `column` (1 = S_fine). Throws InputError when missing.
vv::Curve read_reference(const std::string& path, int column = 1);

}  // namespace erythro::deoxy
