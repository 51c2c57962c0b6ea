#pragma once
// A scene as the user wrote it: physical units throughout (µm, s, cP, kg/m³, N/m³,
// µm/s). Produced by scene_parser (TOML), consumed by units.hpp, which derives the
// lattice parameters and rejects impossible set-ups. Keys: docs/scenes.md.
//
// The keys' defaults are declared in the schema (scene_keys.cpp), which the parser reads
// them from. The initialisers below are the defaults of scenes built in code; a test
// (tests/scene/scene_schema_test.cpp) keeps them equal to the schema's.
//
// A scene declares only the modules it needs; an absent module is std::nullopt and
// nothing is allocated for it.
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace erythro::scene {

struct DomainSpec {
  std::array<double, 2> size_um{0.0, 0.0};  // [domain] size_um = [Lx, Ly]
  double spacing_um = 0.0;                  // [domain] spacing_um = h
  // "planar", or "axisymmetric" (x the axial z, y the radius; transport only, docs/model.md §7b)
  std::string geometry = "planar";
  double inner_radius_um = 0.0;  // radius of the bottom side of an axisymmetric domain (0: the axis)
};

struct TimeSpec {
  // Exactly one of the two is given: the time step, or the relaxation time from
  // which Δt = (τ − ½) h² / (3ν) follows.
  std::optional<double> step_s;  // [time] step_s
  std::optional<double> tau;     // [time] tau
};

// [[fluid.layers]]: a rectangle of another viscosity (e.g. a cytoplasm layer beside
// plasma). Nodes whose centre lies in [x0, x1) × [y0, y1) get it; later entries win.
struct ViscosityLayerSpec {
  std::array<double, 2> y_um{0.0, 0.0};  // [y0, y1], required
  std::optional<std::array<double, 2>> x_um;  // [x0, x1]; absent: the whole width
  double viscosity_cP = 0.0;             // required
};

struct FluidSpec {
  double density_kg_m3 = 1025.0;  // [fluid] density_kg_m3 (plasma, docs/parameters.md)
  double viscosity_cP = 1.2;      // [fluid] viscosity_cP (plasma, thesis §II.4)
  std::string collision = "bgk";  // [fluid] collision = "bgk" | "trt"
  double trt_magic = 3.0 / 16.0;  // [fluid] trt_magic (Λ)
  std::vector<ViscosityLayerSpec> layers;  // [[fluid.layers]]
};

// [time_mapping]: hemodynamic time through the capillary number (docs/model.md §10, eq 10.8). The
// run keeps every physical value (μ, γ̇, moduli, sizes, the clock) and raises only the fluid's
// density, to ρ = Re μ/(γ̇ a²), so that the particle Reynolds number γ̇a²ρ/μ is `reynolds` (thesis
// ch. IV: the same Ca at a larger lattice Reynolds number). Time and strain stay physical.
struct TimeMappingSpec {
  double reynolds = 0.0;                   // [time_mapping] reynolds (required)
  std::optional<double> radius_um;         // a; absent: the largest cell's radius_um × scale
  std::optional<double> shear_rate_per_s;  // γ̇; absent: the drive's (walls: ΔU/H; channel: F H/(2μ))
};

struct SideSpec {
  std::string type = "periodic";                 // "periodic" | "wall" | "moving_wall"
  std::array<double, 2> velocity_um_s{0.0, 0.0};  // moving_wall only
};

struct BoundarySpec {
  SideSpec left, right, bottom, top;  // [boundaries.left] type = ..., velocity_um_s = [...]
};

struct BodyForceSpec {
  std::array<double, 2> density_N_m3{0.0, 0.0};  // [body_force] density_N_m3 (= Pa/m)
  double frequency_Hz = 0.0;                      // F(t) = F0 cos(2π f t + phase); 0 = steady
  double phase_rad = 0.0;
};

struct InitialSpec {
  // "rest" | "uniform" | "shear" (linear profile between the bottom and top walls'
  // velocities) | "taylor_green" (u = −U cos(kx x) sin(ky y), v = U (kx/ky) sin(kx x) cos(ky y),
  // wavelengths = domain size; see simulation.cpp) | "double_shear_layer" (Minion & Brown's
  // thick layer, fluid/initial_state.hpp)
  std::string type = "rest";
  std::array<double, 2> velocity_um_s{0.0, 0.0};  // uniform: the velocity; taylor_green, double_shear_layer: [U, 0]
  // Start from the populations after a collision at t = 0: equilibrium plus the
  // Chapman–Enskog non-equilibrium part of the flow's velocity gradient (and the Guo
  // half force of [body_force]), fluid/initial_state.hpp; false: equilibrium only.
  bool non_equilibrium = false;
};

struct SteadyStateSpec {
  double tolerance = 1e-10;     // stop when max|u^{n} − u^{n−k}| / max|u^n| < tolerance
  long check_interval_steps = 100;
};

struct RunSpec {
  // Exactly one of the two.
  std::optional<long> steps;         // [run] steps
  std::optional<double> duration_s;  // [run] duration_s
  std::optional<SteadyStateSpec> steady_state;  // [run.steady_state]
};

struct MonitorSpec {
  long interval_steps = 100;  // [monitor] interval_steps: health check period K
  double max_mach = 0.3;      // [monitor] max_mach: a run whose |u|/c_s exceeds this stops
  // Membranes (scenes with moving cells): a cell whose |A/A0 − 1| or whose largest edge
  // strain |ℓ/ℓ0 − 1| exceeds these stops the run (a torn or leaking membrane).
  double max_area_change = 0.2;
  double max_edge_strain = 1.0;
  // Transport: a run whose concentration (any species, any node) leaves [lo, hi] µM stops
  // (a growing oscillation caught long before it is a NaN); absent: finite values only.
  std::optional<std::array<double, 2>> concentration_range_uM;
};

struct OutputSpec {
  long fields_interval_steps = 0;        // 0: only the initial and final states
  long diagnostics_interval_steps = 100;
  std::vector<std::string> fields{"density", "velocity"};  // allowed: density, velocity
  // Steps between updates of the running extremes of the cells (cells_max_area_change,
  // cells_max_edge_strain); 0: only at the diagnostics samples.
  long extremes_interval_steps = 0;
  // Also sample the diagnostics at every one of the first this many steps (the start of a
  // transient); 0: only every diagnostics_interval_steps.
  long dense_diagnostics_steps = 0;
  // Checkpoints (erythro run --restart, docs/cli.md): every this many steps and/or
  // after this much wall time (s); 0: off.
  long checkpoint_interval_steps = 0;
  double checkpoint_interval_s = 0.0;
};

// [[stop_when]]: ends a run (status "stopped") when a diagnostics series (any name written
// to /diagnostics, e.g. "cell_0_taylor_deformation") meets a condition at a sample.
// Exactly one of below, above, change_below.
struct StopWhenSpec {
  std::string series;
  std::optional<double> below;         // value < below
  std::optional<double> above;         // value > above
  std::optional<double> change_below;  // |value − value window_steps earlier| < change_below
  long window_steps = 0;               // change_below only (>= 1)
  bool compare_window_means = false;   // change_below only: compare the means of the samples in the
                                       // last two windows instead of two single samples
  long min_steps = 0;                  // not checked before this many steps
  long after_steps = 0;                // run on this many steps after the condition first holds
};

// [membrane]: one membrane model shared by every cell (thesis §II.3, docs/model.md §3).
struct MembraneSpec {
  std::string law = "neo_hookean";     // "neo_hookean" | "skalak" | "hookean" (tension_law.hpp)
  double shear_modulus_dyn_cm = 6e-3;  // E_s [dyn/cm] (RBC ≈ 6e-3 dyn/cm = 6 µN/m)
  double bending_modulus_dyn_cm = 0.0; // E_B [dyn·cm] (RBC ≈ 1.8e-12 dyn·cm = 1.8e-19 J)
  double area_modulus_Pa = 0.0;        // k_A [Pa] (area penalty ½k_A(A−A0)²/A0, per depth)
  double skalak_c = 1.0;               // Skalak's C (law = "skalak" only)
  std::string kernel = "cosine4";      // "cosine4" | "peskin4" | "roma3" | "linear2"
  // "none", or "projection": each cell's enclosed area restored after every marker move
  // (docs/model.md eq 3.14).
  std::string area_correction = "none";
  // Interior (cytoplasm) viscosity by the index field (thesis §II.4, eqs 26–27). Absent:
  // the interior has the fluid's viscosity and no index field is built.
  std::optional<double> interior_viscosity_cP;  // RBC cytoplasm ≈ 6.0 cP (docs/parameters.md)
  std::string interior_method = "flood_fill";   // "flood_fill" | "ray_casting" | "band_only" | "indexless"
  long index_update_interval = 1;               // rebuild the index field every k steps
};

// [[cells]]: one entry per cell. Positions in µm from the domain's lower-left corner.
struct CellSpec {
  std::string shape = "circle";            // "circle" | "ellipse" | "biconcave"
  double radius_um = 0.0;                  // circle radius; biconcave equivalent radius a
  std::array<double, 2> semi_axes_um{0.0, 0.0};  // ellipse [a along x, b along y] (before rotation)
  std::array<double, 2> center_um{0.0, 0.0};
  double angle_deg = 0.0;                  // counter-clockwise rotation about the centre
  double scale = 1.0;                      // multiplies the size
  long markers = 0;                        // marker count (equally spaced in arc length);
                                           // 0: automatic, spacing ≈ 0.7 h (units.cpp)
  // This cell's shear modulus E_s [dyn/cm]; absent: [membrane] shear_modulus_dyn_cm (e.g. a
  // doublet of cells of different deformability, thesis ch. III cases II–IV).
  std::optional<double> shear_modulus_dyn_cm;
  // The cell starts stretched by this factor over its stress-free rest shape, which is the
  // shape before placement scaled by scale / prestretch (a pre-stressed membrane, e.g. an
  // inflated circle); 1: the rest shape is the shape as placed.
  double prestretch = 1.0;
};

// [[cell_populations]]: many cells of one kind, placed at random by scene/cell_seeding.hpp
// (random sequential addition: uniform centres and orientations, a candidate that comes
// closer than min_gap_um to another cell's polygon or to a wall is drawn again). The parser
// appends them to `cells` after the [[cells]] entries, so every later stage sees ordinary cells.
// Every cell of a population shares the [membrane] model; only E_s may differ per population.
struct CellPopulationSpec {
  std::string shape = "circle";                   // as [[cells]] shape
  double radius_um = 0.0;                         // circle, biconcave
  std::array<double, 2> semi_axes_um{0.0, 0.0};   // ellipse
  long markers = 0;                               // 0: automatic, as [[cells]] markers
  std::optional<double> shear_modulus_dyn_cm;     // absent: [membrane] shear_modulus_dyn_cm
  // Exactly one: the target area fraction of the domain covered by this population's cells
  // (2D haematocrit, rounded to a whole number of cells), or the number of cells.
  std::optional<double> area_fraction;
  std::optional<long> count;
  std::optional<double> min_gap_um;  // smallest polygon–polygon and polygon–wall distance;
                                     // absent: 2 h, or limits.min_cell_gap h if larger
  long seed = 1;                     // of the std::mt19937_64 that draws the positions
  long attempts_per_cell = 1000;     // draws of one cell before the target is declared unreachable
};

// What the seeding placed (one per [[cell_populations]] entry): the cells
// Scene::cells[first_cell, first_cell + count), recorded in run.h5 /metadata.
struct PopulationPlacement {
  std::size_t first_cell = 0;
  std::size_t count = 0;
  double area_fraction = 0.0;  // of the domain, by the cells' marker polygons
};

// [aggregation]: Morse aggregation between the membranes of different cells (docs/model.md
// §4; docs/verification-aggregation.md). The strength is exactly one of: the adhesion
// energy γ of a flat contact, the dimensionless surface energy De* = γ / 2.6e−8 J/m² (the
// thesis's levels 1…5; docs/model.md eq 4.7), or the 2D pair density D_e itself; the first
// two are turned into D_e by fitting the flat contact (aggregation/morse_units.hpp).
struct AggregationSpec {
  std::optional<double> de_star;               // De* = γ / 2.6e−8 J/m² (aggregation::kDeStarUnit_J_m2)
  std::optional<double> surface_energy_J_m2;   // γ (the primary key)
  std::optional<double> pair_density_Pa;       // D_e of the 2D pair model (J/m³)
  double zero_force_distance_um = 0.49;        // r0 (Zhang et al. 2008; docs/parameters.md)
  double decay_per_um = 3.84;                  // β (docs/parameters.md, R)
  std::optional<double> cutoff_um;             // r_c > r0; default r0 + 5/β
};

// [repulsion]: short-range repulsion between the membranes of different cells and between
// a membrane and a wall (docs/model.md §4b, eqs 4.11–4.13): the pair density
// P (d/r − 1)² within the range d. Required with [[cell_populations]] (crowded cells must
// not overlap); independent of [aggregation] (both share one neighbour search).
struct RepulsionSpec {
  double pressure_Pa = 0.1;           // P (the schema's default, scene_keys.cpp)
  std::optional<double> range_um;     // d; absent: 2 h (domain.spacing_um)
  bool walls = true;                  // also against the walls of non-periodic sides
};

// [transport]: how the NO/O2 transport is coupled to the flow (docs/architecture.md
// "Time steps and coupling"). Each module keeps its own time step.
struct TransportSpec {
  // "none": no flow, no fluid is built (still medium); the run counts transport steps.
  // "subcycle": the fluid (and cells) advance every fluid step; the transport advances
  //   every `fluid_steps_per_step` fluid steps, Δt_T = that × Δt_F, with the fluid's velocity.
  std::string coupling = "none";
  std::optional<double> time_step_s;  // Δt_T [s]: required with "none", derived with "subcycle"
  long fluid_steps_per_step = 0;      // "subcycle" only (required there)
  std::string stencil = "d2q5";       // "d2q5" | "d2q9"
  std::string collision = "bgk";      // "bgk" | "trt" (docs/transport.md eqs T3, T3')
  double trt_magic = 0.25;            // Λ of "trt"
  // Uniform advecting velocity [µm/s] of a still-medium scene (coupling "none"; no fluid).
  std::optional<std::array<double, 2>> velocity_um_s;
  // How cells enter the transport lattice: "ray_cast" (nodes whose centre is inside, weight 1)
  // or "area_fraction" (each node's fraction φ of its square inside: D by the series rule, C0
  // and heme weighted by φ; docs/transport.md eq T9).
  std::string cell_representation = "ray_cast";
  // Diffusivity at the membrane with "area_fraction": "series" (node rule T9), "node_tensor"
  // (T10 on each node, TRT only), "face_tensor" (T10 on each face, correction T11; TRT Λ = 1/4).
  std::string interface = "series";
  // D of a node shared by two [[transport.layers]]: "harmonic" (series across them) or "arithmetic".
  std::string layer_mean = "harmonic";
  // Concentration handed to the observers (fields): "concentration" (C, eq T4) or
  // "source_corrected" (Ĉ = C + c q/D, eq T7: the steady finite-volume value in a source region).
  std::string readout = "concentration";
};

// [[species]]: one transported species (NO, O2, ...). Side kinds: "periodic",
// "fixed_concentration" (value in µM), "fixed_flux" (inward, value in µM·µm/s),
// "zero_flux". A side defaults to periodic where [boundaries] is periodic, else zero_flux.
struct SpeciesSpec {
  std::string name;                               // required, unique
  double diffusivity_um2_s = 0.0;                 // required, > 0 (outside cells)
  std::optional<double> cell_diffusivity_um2_s;   // inside cells (default: the same)
  double initial_uM = 0.0;
  std::optional<double> cell_initial_uM;          // inside cells (default: initial_uM)
  std::array<std::string, 4> side{"", "", "", ""};  // left, right, bottom, top ("" = default)
  std::array<double, 4> side_value{0.0, 0.0, 0.0, 0.0};
  double source_uM_per_s = 0.0;  // zero-order source everywhere (< 0: consumption), µM/s
  double decay_per_s = 0.0;      // first-order sink rate everywhere (implicit, eq T4), 1/s
};

// [[transport.layers]]: a band y_um[0] <= y < y_um[1] (within x_um, if given; like
// [[fluid.layers]]) where one species has its own diffusivity, first-order sink and zero-order
// source (absent: the species' values); a node cut by an edge mixes by the fraction of its
// square inside (transport.layer_mean for D).
struct TransportLayerSpec {
  std::string species;
  std::array<double, 2> y_um{0.0, 0.0};
  std::optional<std::array<double, 2>> x_um;  // absent: the whole width
  std::optional<double> diffusivity_um2_s, decay_per_s, source_uM_per_s;
};

// [hemoglobin]: Hb–O2 kinetics inside every cell, cell-averaged saturation
// (docs/transport.md §4.2; docs/parameters.md "Haemoglobin and O2 release").
struct HemoglobinSpec {
  std::string species = "O2";         // the [[species]] entry that is O2
  double k_off_per_s = 44.0;          // Eggleton et al. 2000
  double heme_uM = 20.3e3;            // 20.3 mM
  double solubility_uM_per_torr = 1.3;
  double p50_torr = 26.8;
  double hill_n = 2.7;
  double rate_modifier = 1.0;         // M > 0 in the rate's denominator (calibrated; M < 1 is faster)
  std::optional<double> initial_saturation;  // default: Hill at the cells' initial PO2
  // "cell_mean": one S per cell from its mean P (eqs H1–H3); "local": one S per heme node from
  // the node's own P (eq H4; still cells only).
  std::string kinetics = "cell_mean";
  // Update of S and the cell's mean P over a step (docs/transport.md §4.2): "explicit" (P of the
  // step's start, H2), "cell_implicit" (H3), "cell_implicit_outflow" (H3 with the outflow of
  // the last step predicted).
  std::string coupling = "cell_implicit";
  // Mean P from the concentration C, or "source_corrected" (the offset of eq T7 taken into the
  // implicit update; cell_implicit_outflow only).
  std::string mean_pressure = "concentration";
  // Heme weights with transport.cell_representation = "area_fraction": "area_fraction" (φ),
  // "first_moment" (φ spread from the centroid of each cut node's inside part, release and
  // mean P), "first_moment_sampling" (mean P only).
  std::string heme_weights = "area_fraction";
};

// [no_o2]: the coupled NO/O2 reactions of an arteriole's layers (docs/model.md §7c; rates R1–R5,
// parameters docs/parameters.md §4), on the compartments of [[no_o2.layers]]. It sets the
// sources and sinks of both species every transport step from their concentrations.
struct NoO2Spec {
  std::string no_species = "NO", o2_species = "O2";
  double wall_shear_stress_Pa = 2.4;        // R_max = 50 µM/s × τ_w/2.4 Pa (R1)
  double blood_no_scavenging_per_s = 382.5; // λ_b (Hct 40 %): the core's rate by R4
  double core_po2_torr = 70.0;              // the PO2 the core's exchange holds
  double core_o2_exchange_per_s = 1.0e4;    // k_ex of that exchange
  double no_consumption_per_s = 1.0;        // smooth muscle and tissue (R2)
  double sm_o2_max_consumption_uM_s = 5.0;  // Q_max of R5 in the smooth muscle
  double tissue_o2_max_consumption_uM_s = 50.0;
};

// [[no_o2.layers]]: a band y_um[0] <= y < y_um[1] of one compartment ("core", "plasma",
// "endothelium", "smooth_muscle", "tissue"); a node takes the band holding its centre, plasma
// where none does.
struct CompartmentLayerSpec {
  std::string compartment;
  std::array<double, 2> y_um{0.0, 0.0};
};

struct LimitsSpec {
  double min_tau_margin = 0.005;   // reject τ < 0.5 + margin
  double max_tau = 10.0;           // reject τ > this (the wall error grows as (τ − ½)²)
  double max_mach = 0.1;           // reject a set-up whose expected |u|/c_s exceeds this
  int min_nodes_across_channel = 4;  // reject a wall-bounded direction with fewer nodes
  // A membrane beyond the explicit-update stability estimate (membrane/stability.hpp):
  // "reject" the set-up, or "warn" (MembraneSetup::stability.warning) and run it anyway,
  // e.g. to measure where it diverges.
  std::string membrane_stability = "reject";
  // Cells (lattice spacings h): the largest marker spacing (fluid leaks between markers
  // farther apart) and the smallest distance between markers of two cells or a marker and
  // a wall. Relaxed, e.g., by the doublet cases: the thesis's 100 markers at h = 0.15 µm,
  // an aggregated pair at its flat-contact gap on a coarse lattice.
  double max_marker_spacing = 1.0;
  double min_cell_gap = 1.0;
};

struct Scene {
  std::string source_path;  // file the scene came from ("" for programmatic scenes)
  std::string source_text;  // the scene as parsed, after --set overrides (recorded in outputs)
  std::string name;         // [scene] name
  std::string description;  // [scene] description
  DomainSpec domain;
  TimeSpec time;
  FluidSpec fluid;
  std::optional<TimeMappingSpec> time_mapping;  // [time_mapping]; absent: ρ as given
  BoundarySpec boundaries;
  std::optional<BodyForceSpec> body_force;
  InitialSpec initial;
  RunSpec run;
  MonitorSpec monitor;
  OutputSpec output;
  LimitsSpec limits;
  std::optional<MembraneSpec> membrane;  // [membrane]; defaults apply when cells exist without it
  std::vector<CellSpec> cells;           // [[cells]]; empty: a fluid-only scene
  std::vector<CellPopulationSpec> cell_populations;      // [[cell_populations]]
  std::vector<PopulationPlacement> population_placements;  // one per population, set by the parser
  std::optional<AggregationSpec> aggregation;  // [aggregation] (needs cells and a fluid)
  std::optional<RepulsionSpec> repulsion;      // [repulsion] (needs cells and a fluid)
  std::optional<TransportSpec> transport;  // [transport]; absent: no transport
  std::vector<SpeciesSpec> species;        // [[species]] (needs [transport])
  std::vector<TransportLayerSpec> transport_layers;  // [[transport.layers]] (needs [[species]])
  std::optional<NoO2Spec> no_o2;                     // [no_o2] (needs the two species)
  std::vector<CompartmentLayerSpec> compartment_layers;  // [[no_o2.layers]]
  std::optional<HemoglobinSpec> hemoglobin;  // [hemoglobin] (needs cells and an O2 species)
  std::vector<StopWhenSpec> stop_when;       // [[stop_when]]
};

}  // namespace erythro::scene
