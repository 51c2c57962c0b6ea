#pragma once
// The one module that converts physical units to lattice units (h = Δt = 1, ρ0 = 1)
// and rejects impossible or unstable set-ups before anything runs.
#include <optional>
#include <string>
#include <vector>

#include "aggregation/morse.hpp"
#include "aggregation/repulsion.hpp"
#include "fluid/boundary.hpp"
#include "fluid/collision.hpp"
#include "fluid/viscosity_layers.hpp"
#include "geometry/polygon.hpp"
#include "ib/kernel.hpp"
#include "interior/index_field.hpp"
#include "lattice/grid.hpp"
#include "membrane/membrane_energy.hpp"
#include "membrane/stability.hpp"
#include "scene/scene.hpp"
#include "scene/time_mapping.hpp"
#include "transport/compartments.hpp"
#include "transport/hb_kinetics.hpp"
#include "transport/transport_lattice.hpp"
#include "transport/transport_units.hpp"

namespace erythro::scene {

// Conversion factors: physical = lattice × factor (SI units).
struct UnitScales {
  double length_m = 0.0;     // h
  double time_s = 0.0;       // Δt
  double density_kg_m3 = 0.0;  // ρ0
  double velocity_m_s() const { return length_m / time_s; }
  double force_density_N_m3() const { return density_kg_m3 * length_m / (time_s * time_s); }
  double kinematic_viscosity_m2_s() const { return length_m * length_m / time_s; }
  double pressure_Pa() const { return density_kg_m3 * velocity_m_s() * velocity_m_s(); }
};

// One cell placed on the lattice (lattice units: nodes at i + ½, walls at 0 and n).
struct CellSetup {
  geometry::Polygon shape;        // markers, counter-clockwise; also the stress-free rest shape
                                  // unless `rest` is given
  geometry::Polygon rest;         // the stress-free rest shape of a pre-stressed cell (cells.prestretch:
                                  // unplaced, scaled by scale / prestretch); empty: `shape`
  membrane::MembraneModel model;  // lattice moduli of this cell (MembraneSetup::model unless overridden)
  double equivalent_radius = 0.0; // √(A/π)
  double min_edge = 0.0, max_edge = 0.0;  // marker spacing
};

// The strength of [aggregation] in physical terms (docs/model.md §4, eqs 4.6–4.8), whichever
// key gave it: shown by `erythro check`, recorded in run.h5's /metadata.
struct AggregationStrength {
  double surface_energy_J_m2 = 0.0;  // γ of the flat contact (eq 4.6: D_e |J(d*)|)
  double de_star = 0.0;              // γ / 2.6e−8 J/m² (eq 4.7)
  double peak_stress_Pa = 0.0;       // γβ/2: the estimate of the largest Morse stress (eq 4.8)
  // Only in a wall-driven simple shear (wall_shear_rate_per_s): γ̇, and σ_M / (μγ̇) with μ the
  // plasma viscosity fluid.viscosity_cP.
  std::optional<double> shear_rate_per_s;
  std::optional<double> adhesion_to_viscous_stress;
};

// The membranes, present only when the scene declares [[cells]].
struct MembraneSetup {
  ib::KernelType kernel = ib::KernelType::cosine4;
  membrane::MembraneModel model;  // lattice moduli of [membrane] (a cell may override its shear modulus)
  membrane::StabilityEstimate stability;
  std::vector<CellSetup> cells;
  // Interior viscosity (thesis eq 27): with `indicator` = indexless nothing is built and
  // the interior keeps the fluid's viscosity.
  interior::Method indicator = interior::Method::indexless;
  double interior_viscosity = 0.0;  // lattice ν_in (= exterior ν when no interior viscosity is set)
  double interior_tau = 0.0;        // ½ + 3ν_in
  long index_update_interval = 1;  // k, resolved (membrane.index_update_interval = 0: supported_index_interval)
  bool area_projection = false;  // membrane.area_correction = "projection" (docs/model.md eq 3.14)
  // Morse aggregation between cells (lattice units), only with [aggregation].
  std::optional<aggregation::MorseParameters> aggregation;
  double aggregation_flat_gap = 0.0;  // flat-contact equilibrium gap d* (h), shown by `check`
  std::optional<AggregationStrength> aggregation_strength;  // with [aggregation]
  // Short-range repulsion between cells and against walls (lattice units), only with [repulsion].
  std::optional<aggregation::RepulsionParameters> repulsion;
};

// Fixed set-up rules for cells (docs/scenes.md "Checks done by units.cpp"), in h. The two
// defaults read from LimitsSpec are const, not constexpr: LimitsSpec holds a std::string,
// which clang 14 cannot build at compile time with GCC 12's library (the fuzzing build).
inline constexpr double kMinCellRadius = 3.0;   // equivalent radius >= 3 h
inline const double kMaxMarkerSpacing = LimitsSpec{}.max_marker_spacing; // default: every edge <= h (no leaks)
inline constexpr double kMinMarkerSpacing = 0.3; // every edge >= 0.3 h (over-resolved markers stiffen)
// default: markers of two cells, or a marker and a wall, >= h apart
inline const double kMinCellGap = LimitsSpec{}.min_cell_gap;
inline constexpr double kAutoMarkerSpacing = 0.7; // cells.markers absent: perimeter / 0.7 h markers (>= 16)

// One transported species in transport lattice units (h, Δt_T; concentrations in µM).
struct SpeciesSetup {
  std::string name;
  double diffusivity = 0.0, cell_diffusivity = 0.0;  // D Δt_T / h², outside / inside cells
  double initial = 0.0, cell_initial = 0.0;          // µM
  transport::TransportBoundaries boundaries;
  // The same diffusivities in µm²/s (the series rule of nodes cut by a membrane or a layer
  // edge mixes physical values, then converts), and the sources everywhere (lattice units:
  // q = q_phys Δt_T, k = k_phys Δt_T).
  double diffusivity_um2_s = 0.0, cell_diffusivity_um2_s = 0.0;
  double source = 0.0, decay = 0.0;
  double source_uM_per_s = 0.0, decay_per_s = 0.0;
};

// [[transport.layers]]: a band (rectangle) of one species' own D, k, q; x, y in lattice units
// (node (i, j) spans [i, i+1] × [j, j+1]), values physical (mixed by the fractions of a cut
// node's square, then converted).
struct TransportLayerSetup {
  int species = 0;
  double y_lo = 0.0, y_hi = 0.0;
  bool full_width = true;  // no x_um: x_lo = 0, x_hi = nx
  double x_lo = 0.0, x_hi = 0.0;
  double diffusivity_um2_s = 0.0, decay_per_s = 0.0, source_uM_per_s = 0.0;
};

// [no_o2] in the transport's terms (docs/model.md §7c): the compartment model (rates in µM, Torr,
// s: transport::update_reactions converts them), the two species' indices and the bands in
// lattice units (y from the bottom side, node centres at y + ½).
struct NoO2Setup {
  transport::NoO2Model model;
  int no_species = -1, o2_species = -1;
  struct Band {
    double y_lo = 0.0, y_hi = 0.0;
    transport::Compartment compartment = transport::Compartment::plasma;
  };
  std::vector<Band> bands;
  double core_radius_um = 0.0, cell_free_layer_um = 0.0;  // the core band's top, the plasma beside it
};

// [transport]: the transport's own time step and its coupling to the flow
// (docs/architecture.md "Time steps and coupling").
struct TransportSetup {
  std::string coupling = "none";   // "none" | "subcycle"
  transport::Stencil stencil = transport::Stencil::d2q5;
  double time_step_s = 0.0;        // Δt_T
  long fluid_steps_per_step = 0;   // subcycle: Δt_T = this × Δt_F
  double velocity_scale = 0.0;     // u_T = velocity_scale × u_F (lattice units) = Δt_T/Δt_F
  std::vector<SpeciesSetup> species;
  // Hb–O2 kinetics in every cell (physical units: k_off in 1/s, µM, Torr), for species
  // `hemoglobin_species`; the update takes Δt_T in seconds.
  std::optional<transport::HbParameters> hemoglobin;
  int hemoglobin_species = -1;
  std::optional<double> initial_saturation;
  // The options of transport_physics.hpp (scene.hpp TransportSpec, HemoglobinSpec; strings
  // as in the scene, checked), the unit conversion, the uniform velocity of a still medium
  // (lattice units), the layers and the monitor's concentration range (µM).
  transport::TransportUnits units;
  transport::CollisionModel collision;
  std::optional<std::array<double, 2>> velocity;
  std::string cell_representation = "ray_cast", interface = "series", layer_mean = "harmonic";
  std::string readout = "concentration";
  std::string hb_kinetics = "cell_mean";
  std::string hb_coupling = "cell_implicit", mean_pressure = "concentration", heme_weights = "area_fraction";
  std::vector<TransportLayerSetup> layers;
  std::optional<std::array<double, 2>> concentration_range;
  // domain.geometry = "axisymmetric": the radius of the bottom side in lattice units (0: the
  // axis); absent for a planar domain (docs/model.md §7b).
  std::optional<double> axisymmetric_inner_radius;
  std::optional<NoO2Setup> no_o2;  // [no_o2]
};

// Everything the simulation needs, in lattice units, plus derived numbers to show.
struct LatticeSetup {
  Grid grid;
  UnitScales scales;
  fluid::CollisionConfig collision;
  fluid::BoundaryConfig boundaries;
  std::array<double, 2> body_force{0.0, 0.0};  // lattice force density
  double force_frequency = 0.0;                // per step (lattice)
  double force_phase = 0.0;
  std::array<double, 2> initial_velocity{0.0, 0.0};  // lattice
  std::vector<fluid::ViscosityLayer> viscosity_layers;  // [[fluid.layers]], lattice rectangles and τ
  long total_steps = 0;
  double viscosity = 0.0;           // lattice kinematic viscosity ν = (τ − ½)/3
  double expected_max_speed = 0.0;  // lattice, estimated from walls, force, initial state
  std::string speed_source;         // the scene key that sets expected_max_speed ("" if at rest)
  bool speed_is_estimate = false;   // force along a periodic direction: no steady state, bounded guess
  double mach = 0.0;                // expected_max_speed / c_s
  double reynolds = 0.0;            // expected_max_speed × L / ν (L: channel width or domain)
  double reynolds_length_m = 0.0;
  // [time_mapping] (docs/model.md eq 10.8): scales.density_kg_m3 is then its run density.
  std::optional<TimeMapping> time_mapping;
  std::optional<MembraneSetup> membrane;  // only when the scene has cells
  // false for a still-medium transport scene (transport.coupling = "none"): no fluid is
  // built, scales.time_s is the transport step and total_steps counts transport steps.
  bool has_fluid = true;
  std::optional<TransportSetup> transport;  // only when the scene has [transport]
};

// Converts and checks. Throws InputError naming the scene file, the key, its value
// and the allowed range when the set-up is impossible or unstable.
LatticeSetup derive_lattice(const Scene& scene);

// The shear rate γ̇ [1/s] of a wall-driven simple shear: walls at bottom and top, at least
// one moving, left/right periodic, no body force; γ̇ = relative wall speed / channel height
// (lattice: |u_top − u_bottom| / n_y per step, the profile of initial.type = "shear").
// Otherwise none. `L` needs its grid, scales, boundaries and body force.
std::optional<double> wall_shear_rate_per_s(const LatticeSetup& L);

// The largest index-field interval k with k·U ≤ 0.1 h for the fastest speed U (lattice units
// per step), at least 1: the lag δ = kU/2 ≤ 0.05 h that verification.suspension_index_interval
// and validation.rbc_index_update_interval cover (docs/model.md §5).
// U ≤ 0 (nothing moves) gives 1.
long supported_index_interval(double fastest_speed_lattice);

// Human-readable table of the derived parameters (h, Δt, τ, ν, Ma, Re, steps...)
// printed by `erythro check`.
std::string format_lattice_report(const Scene& scene, const LatticeSetup& setup);

}  // namespace erythro::scene
