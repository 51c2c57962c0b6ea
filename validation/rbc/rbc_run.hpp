#pragma once
// One run of the red-blood-cell-in-shear set-up (validation.rbc_shear and the interior-
// viscosity cases): the scene rbc.toml (a 2D Evans–Fung biconcave cell, docs/model.md
// eq 3.9, between two walls moving at ∓U, periodic in x), set for one run by overrides and
// run as `erythro run` runs it (vv::run_case_scene); everything below is read from the
// run.h5 it wrote (the cell-shape and interior probes' series, the cells' markers at the
// field outputs, the summary). Interior viscosity (docs/model.md §5, thesis eqs 26–27):
// `indicator` picks how the cytoplasm is marked (indexless: one fluid), rebuilt every
// `index_update_interval` steps with ν_in = viscosity_ratio·ν_ex.
// Physical inputs are turned into the dimensionless groups the 2D Stokes problem depends
// on (Ca, E_B*, k_A a/E_S, H/a, L/a); the lattice Reynolds number is a separate choice
// that sets the scene's shear rate (rbc_run.cpp).
#include <string>
#include <vector>

#include "ib/kernel.hpp"
#include "interior/index_field.hpp"
#include "io/result_record.hpp"

namespace erythro::vv {

struct RbcConfig {
  ib::KernelType kernel = ib::KernelType::cosine4;
  // Physical (SI) inputs, docs/parameters.md.
  double a_m = 3.91e-6;          // Evans–Fung equivalent radius
  double h_m = 0.25e-6;          // lattice spacing
  double mu_Pa_s = 1.2e-3;       // plasma viscosity (1.2 cP): the exterior viscosity μ_ex
  // Interior viscosity (issue 5). indexless: uniform μ_ex everywhere (viscosity_ratio is
  // then ignored; the τ field is never enabled). Otherwise τ(x) from eq 27 with
  // ν_in = viscosity_ratio·ν_ex (cytoplasm 6.0 cP / plasma 1.2 cP = 5).
  interior::Method indicator = interior::Method::indexless;
  double viscosity_ratio = 1.0;  // μ_in/μ_ex
  int index_update_interval = 1; // rebuild I and τ every k steps (1 = every step)
  double shear_rate = 100.0;     // γ̇ [1/s]
  double Es_N_m = 6e-6;          // E_S = 6e-3 dyn/cm
  double Eb_J = 3.6e-19;         // E_B = 3.6e-12 dyn·cm (thesis)
  double area_modulus = 100.0;   // k_A in units of E_S/a
  // Lattice choices.
  double tau = 1.0;              // BGK (ν = (τ − ½)/3)
  double reynolds = 0.05;        // lattice particle Reynolds number γ̇a²/ν
  double height = 8.0;           // H/a (wall to wall) = 4 cell diameters
  double length = 8.0;           // L_x/a (periodic)
  double marker_spacing = 0.5;   // rest marker spacing in h
  double strain = 20.0;          // γ̇t to run
  double max_mach = 0.3;         // health monitor: |u|/c_s limit (monitor.max_mach)
  double max_edge_strain = 1.0;  // health monitor: max |ℓ/ℓ0 − 1| of a membrane (monitor.max_edge_strain)
  // The scene rejects a set-up membrane::estimate_stability finds unstable (default). The
  // stability map (validation.rbc_viscosity_stability) runs such set-ups anyway
  // (limits.membrane_stability = "warn") to see what they do.
  bool require_stability_estimate = true;
  // Outlines to keep (shear strains); the nearest field output to each (one every half
  // strain unit when any is inside the run, else the first and last states only).
  std::vector<double> snapshot_strains = {0, 2, 5, 10, 15, 20};
  bool pictures = false;  // keep pictures of the last field output (speed, membrane) for the report
};

struct ShapeSnapshot {
  double strain = 0;
  std::vector<double> x_um, y_um;  // closed polygon relative to its centroid
};

struct RbcResult {
  bool diverged = false;
  std::string diagnosis;         // why the run stopped early (health monitor, marker, fill, area)
  double tau_ex = 0, tau_in = 0; // relaxation times outside / inside (τ_in = τ_ex when indexless)
  long index_updates = 0;        // index-field rebuilds
  double index_time_s = 0;       // wall time of the rebuilds and τ writes
  int fallback_cells = 0;        // max over updates of cells filled by ray casting (flood fill)
  double max_fill_mismatch = 0;  // max over updates of |Σ(1 − I) − A| / A0
  double interior_fraction = 0;  // at the end: Σ(1 − I) / A (1 for a filled cell)
  long steps = 0;
  double strain = 0;
  int markers = 0;
  int nx = 0, ny = 0;
  double a_lat = 0, gamma_lat = 0, Es_lat = 0, Eb_lat = 0, kA_lat = 0;
  double capillary = 0;          // Ca = μγ̇a/E_S
  double bending_reduced = 0;    // E_B* = E_B/(a² E_S)
  double reynolds_physical = 0;  // γ̇a²ρ/μ of the physical cell
  double stability_factor = 0;   // membrane::StabilityEstimate::max_dt_factor of the scene check
  double max_area_change = 0;    // max over every step of |A/A0 − 1|
  double max_edge_strain = 0;    // max over every step and edge of |ℓ/ℓ0 − 1|
  double body_rotation_deg = 0;  // change of the unwrapped inclination θ over the run
  double marker_rotation_deg = 0;// mean over markers of the unwrapped angle change about the centroid
  double marker0_rotation_deg = 0; // same for marker 0 alone
  // Rates over the second half of the run (deg per unit strain; negative = clockwise,
  // with the vorticity): mean marker angle about the centroid, and the long axis.
  double marker_rate_deg = 0, body_rate_deg = 0;
  double theta_min = 0, theta_max = 0;  // range of unwrapped θ after strain 2 (final θ if shorter)
  double D_mean = 0, theta_mean = 0;    // means over the last 2 strain units
  double centre_drift = 0;       // |y_c − H/2| / a at the end
  double wall_time_s = 0;
  std::string scene_text;        // the scene as run (after overrides)
  std::vector<double> strain_h, D_h, theta_h, area_h, estrain_h, psi_h;  // every 0.05 strain units
  std::vector<double> phase_h;   // mean marker angle about the centroid (deg, unwrapped, from 0)
  std::vector<ShapeSnapshot> snapshots;
  std::vector<io::FieldPicture> pictures;  // RbcConfig::pictures: the last field output
};

// `case_name` and `label` name the run's folder <results>/runs/<case>/<label>/.
RbcResult run_rbc(const RbcConfig& c, const std::string& case_name, const std::string& label);
// run_rbc with the label run_folder(c).
inline RbcResult run_rbc(const RbcConfig& c, const std::string& case_name);

// A folder name that tells runs of one case apart: method, ratio, h, τ, E_S, k, strain,
// e.g. "flood_fill_x5_h0.25_tau1_Es6e-06_k1_strain3".
std::string run_folder(const RbcConfig& c);
inline RbcResult run_rbc(const RbcConfig& c, const std::string& case_name) {
  return run_rbc(c, case_name, run_folder(c));
}

// "tumbling" if the long axis turns by ≥ 90° (it passes the normal to the flow);
// "tank-treading" if it does not and the membrane turns round it by ≥ 90°;
// otherwise "undetermined".
std::string classify(const RbcResult& r);

}  // namespace erythro::vv
