#pragma once
// One run of the RBC doublet in simple shear (thesis ch. III, docs/model.md §6), or of a
// single elliptical cell (the rigid limit, issue 6 item 7), as a scene run by the product
// path (`erythro run` does the same): validation/doublet/doublet.toml (two biconcave
// cells, Morse aggregation) or single_cell.toml (one ellipse), set for this run by
// overrides. Cells between two walls moving at ∓U (γ̇ = 2U/H), periodic in x, with
//   - the membrane of docs/model.md §3 (neo-Hookean tension, bending about the rest
//     curvature, area penalty; rest shape = initial shape), one E_S per cell;
//   - the cytoplasm viscosity by the flood-fill index field (docs/model.md §5, eqs 26–27);
//   - Morse aggregation between the cells (docs/model.md §4, thesis eq 13) at surface energy
//     γ = k·E_S0, the level k of the OLD reading De* = γ/E_S (docs/model.md eq 4.7, the documented
//     alternative), or, with DoubletShearConfig::de_star set, γ = De* × 2.6e−8 J/m² (the project's
//     De*, issue 21); either way given as aggregation.surface_energy_J_m2.
// Hemodynamic time mapping (docs/model.md §10, eq 10.7): the physical inputs fix the
// dimensionless groups Ca = μγ̇a/E_S, E_B* = E_B/(a²E_S), k_A a/E_S, γ/E_S,
// λ = μ_in/μ_ex, r0/a, βa and the box/a; the particle Reynolds number ργ̇a²/μ is chosen
// (small, stated) through the scene's density, which sets the lattice shear rate.
// The doublet diagnostics are the pair probe's series (simulation/probes/pair_probe.hpp),
// the shapes the cell-shape probe's; the stop criteria are the scene's [[stop_when]] rules.
#include <string>
#include <vector>

#include "ib/kernel.hpp"
#include "interior/index_field.hpp"
#include "io/result_record.hpp"

namespace erythro::vv {

enum class CellShape { biconcave, ellipse };

struct DoubletShearConfig {
  ib::KernelType kernel = ib::KernelType::cosine4;
  // Physical inputs (SI), docs/model.md §6 / docs/parameters.md.
  double a_m = 3.91e-6;            // equivalent radius (biconcave) or semi-major axis (ellipse)
  double h_m = 0.3e-6;             // lattice spacing (thesis: 0.15 µm)
  double box_m = 30e-6;            // square box 30 × 30 µm (walls at y = 0, H)
  double mu_Pa_s = 1.2e-3;         // plasma
  interior::Method indicator = interior::Method::flood_fill;
  double viscosity_ratio = 5.0;    // cytoplasm 6.0 cP / plasma 1.2 cP
  int index_update_interval = 5;   // docs/validation-interior-viscosity.md item 1: k = 5–20 safe
  double shear_rate = 100.0;       // γ̇ [1/s]
  double Es0_N_m = 6e-6, Es1_N_m = 6e-6;  // E_S of cell 0 / cell 1 (6e-3 dyn/cm)
  double Eb_J = 3.6e-19;           // E_B = 3.6e-12 dyn·cm (thesis), both cells
  double area_modulus = 100.0;     // k_A in units of E_S0/a (as validation/rbc)
  double old_reading_de_star = 2.0;  // level k of the old reading: γ = k·E_S0 (surface_energy_J_m2(); both cells)
  double de_star = -1.0;           // ≥ 0: the project's De* instead, γ = De* × 2.6e−8 J/m² (docs/model.md eq 4.7);
                                   // old_reading_de_star is then unused
  double r0_m = 0.49e-6;           // Morse zero-force separation (docs/parameters.md)
  double beta_per_m = 3.84e6;      // Morse decay (docs/parameters.md, confidence R)
  double cutoff_k = 5.0;           // r_c = r0 + k/β (docs/verification-aggregation.md §1)
  // Lattice choices.
  double tau = 1.0;                // BGK exterior relaxation time (ν = (τ − ½)/3)
  double reynolds = 0.1;           // particle Reynolds number γ̇a²/ν_ex of the run (sets the scene's density)
  int markers = 100;               // per cell (thesis: 100 segments)
  // Geometry.
  int cells = 2;                   // 2: doublet; 1: single cell (rigid limit)
  CellShape shape = CellShape::biconcave;
  double ellipse_axis_ratio = 2.0; // a/b of the ellipse (single cell)
  double theta0_deg = 90.0;        // doublet: line of centres (90 = stacked, face to face); single: long axis
  double initial_gap_m = -1.0;     // smallest rim-to-rim gap at start; < 0: the flat-contact gap d*
  // Run control.
  double strain = 14.0;            // cap on γ̇t
  double sample_strain = 0.05;     // sampling interval of the histories
  double stop_theta_deg = -1e9;    // stop at the first sample where the unwrapped θ is below this
  double stop_after_dissociation = 1.0;  // strain units kept after dissociation, then stop (doublet)
  double max_mach = 0.3;
  bool pictures = false;           // keep pictures of the last field output (speed, membranes) for the report
};

struct DoubletShearResult {
  bool diverged = false;
  std::string diagnosis;
  std::string scene_text;          // the scene as run (after overrides)
  int nx = 0, ny = 0, markers = 0;
  long steps = 0;
  double strain = 0;               // γ̇t reached
  double wall_time_s = 0;
  // Mapping.
  double a_lat = 0, gamma_lat = 0, tau_in = 0;
  double Es0_lat = 0, Es1_lat = 0, Eb_lat = 0, kA_lat = 0;
  double capillary0 = 0, capillary1 = 0;  // Ca_i = μγ̇a/E_S,i
  double bending_reduced = 0;      // E_B/(a²E_S0)
  double reynolds_physical = 0;    // ργ̇a²/μ
  double De_lat = 0, r0_lat = 0, beta_lat = 0, cutoff_lat = 0;
  double flat_gap_lat = 0;         // d* of the flat contact
  // The adhesion strength as the scene derives it (scene::AggregationStrength; 0 / −1 without
  // aggregation): γ, the project's De*, σ_M = γβ/2 (docs/model.md eq 4.8) and σ_M/(μγ̇).
  double surface_energy_J_m2 = 0, de_star = 0, peak_adhesion_stress_Pa = 0, adhesion_to_viscous_stress = -1;
  double stability_factor = 0;
  // Histories (every sample_strain): strain, θ (deg, unwrapped; doublet: line of centres,
  // single: long axis), contact area per cell, centre separation (µm), smallest
  // membrane gap (µm), Taylor D per cell, contact-shape amplitudes (µm), equivalent
  // ellipse axis ratio, area change (max over cells).
  std::vector<double> strain_h, theta_h, contact0_h, contact1_h, separation_h, gap_h, D0_h, D1_h;
  std::vector<double> sigmoid_h, bow_h, aspect_h, area_h;
  double max_area_change = 0, max_edge_strain = 0;
  double max_edge_strain_cell[2] = {0, 0};  // per cell, max over samples of |ℓ/ℓ0 − 1|
  // Outcome.
  bool dissociated = false;
  double dissociation_strain = -1; // first sample with no marker pair within the Morse cut-off
  double min_contact_after1 = 0;   // min over strain ≥ 1 of the smaller contact area (till dissociation)
  double t_theta0 = -1, t_theta_m90 = -1, t_theta_m180 = -1;  // first strain with θ ≤ 0, −90, −180 deg
  double aspect_quadrant = 0;      // mean equivalent-ellipse a/b over [t(θ=0), t(θ=−90)]
  std::vector<double> snap_strain; // outline snapshots (µm, absolute, cell 1 moved next to cell 0)
  std::vector<std::vector<double>> snap_x, snap_y;
  std::vector<io::FieldPicture> pictures;  // DoubletShearConfig::pictures: the last field output
};

// Runs the scene into <results>/runs/<case_name>/<label>/ and reads its series back.
DoubletShearResult run_doublet_shear(const DoubletShearConfig& c, const std::string& case_name,
                                     const std::string& label);

// The runs of one case, at the same time on the cores the case was given (OMP_NUM_THREADS;
// vv::run_concurrently: one OpenMP thread per run, the same bits as one after the other),
// the most expensive first (nodes × steps ∝ strain/h⁴); results in the order given.
struct DoubletRun {
  DoubletShearConfig config;
  std::string label;
};
std::vector<DoubletShearResult> run_doublet_shears(const std::vector<DoubletRun>& runs, const std::string& case_name);

}  // namespace erythro::vv
