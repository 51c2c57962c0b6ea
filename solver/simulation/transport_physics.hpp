#pragma once
// The NO/O2 transport of a scene (docs/transport.md): one advection–diffusion–reaction
// lattice per [[species]] (BGK or TRT, transport.collision), zero-order sources and
// first-order sinks everywhere and per [[transport.layers]] band, the cells as a compartment with
// their own diffusivity and initial concentration (ray-cast nodes, or area fractions with
// a membrane rule: series, node or face subpixel tensor, eqs T9–T11), and Hb–O2 kinetics
// per cell (cell-averaged saturation, release spread over the cell's heme weights; coupling
// explicit, cell-implicit or cell-implicit with the outflow predictor, eqs H1–H3) or per heme
// node (local kinetics, eq H4) for the species named by [hemoglobin]. On an axisymmetric lattice
// the cells are bodies of revolution (docs/model.md §7b). Advanced with its own time step; the simulation decides
// when (docs/architecture.md "Time steps and coupling").
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "common/health.hpp"
#include "geometry/domain.hpp"
#include "geometry/polygon.hpp"
#include "scene/units.hpp"
#include "simulation/cell_transport.hpp"
#include "simulation/local_hb.hpp"
#include "transport/face_flux_correction.hpp"
#include "transport/transport_lattice.hpp"

namespace erythro::sim {

class TransportPhysics {
 public:
  // Cells (lattice units) define the interior compartment; may be empty. Throws InputError
  // when the face-flux correction of transport.interface = "face_tensor" would be unstable.
  TransportPhysics(const scene::TransportSetup& setup, const geometry::Domain& domain,
                   std::span<const geometry::Polygon> cells);

  // The cells moved: recomputes the interior nodes, the diffusivity field and the membrane
  // rule (the species keep their concentrations, the cells their saturation).
  void place_cells(std::span<const geometry::Polygon> cells);

  // One transport step. Velocity in FLUID lattice units (scaled by the set-up's
  // Δt_T/Δt_F), or empty spans for a still medium (uniform transport.velocity_um_s, if any).
  void step(std::span<const double> fluid_ux, std::span<const double> fluid_uy);

  std::size_t species_count() const { return lattices_.size(); }
  const std::string& name(std::size_t i) const { return setup_.species[i].name; }
  const scene::TransportSetup& setup() const { return setup_; }
  const transport::TransportLattice& lattice(std::size_t i) const { return lattices_[i]; }
  // For setting state before the run (a per-node D or velocity field, e.g. a manufactured
  // problem's); call initialize() after changing what the start depends on.
  transport::TransportLattice& lattice(std::size_t i) { return lattices_[i]; }
  // Zero-order source of species i, lattice units (concentration per step), as set by the
  // scene (species and layers): written into the lattice before the first step and, where
  // the physics rewrites the source each step (Hb release, face-flux correction), under it.
  // Writable before the run (a manufactured source); then call initialize().
  std::span<double> base_source(std::size_t i);
  // Equilibrium start of species i at concentration C (µM) with the current source, sink and
  // velocity (the source acts time-centred from the first step, docs/transport.md "Start").
  void initialize(std::size_t i, std::span<const double> C);
  // What the observers receive as species i's field: C, or with transport.readout =
  // "source_corrected" Ĉ = C + c q/D (eq T7).
  std::span<const double> readout(std::size_t i) const;

  // Cell-averaged HbO2 saturation per cell; empty without [hemoglobin].
  std::span<const double> saturation() const { return saturation_; }
  // O2 released by cell c since the start, lattice units: C_heme (S0 − S) × the heme volume
  // (Σ heme weights; axisymmetric Σ φ r, per radian); local kinetics: Σ over its nodes.
  double released(std::size_t c) const;
  // Stored amount M = Σ g* at the start (or the last initialize) and the net amount that has
  // entered through the sides since, lattice units (eq T5: M(t) − M0 = inflow + Σ sources).
  double initial_amount(std::size_t i) const { return initial_amount_[i]; }
  double boundary_inflow(std::size_t i) const { return inflow_[i]; }
  // Lagged gain of species i's face-flux correction (0 without one).
  double face_correction_gain(std::size_t i) const;
  // Largest |M(t+1) − M(t) − sources − boundary flux| / Σ|g| of any species, last step.
  double max_relative_residual() const;
  // Finite concentrations within monitor.concentration_range_uM (when absent: not below
  // −1 % of the start's concentration scale, no upper limit; transport_physics.cpp), valid
  // relaxation times in every species, the last step's relative mass-balance residual at
  // most kMaxRelativeResidual, saturations within [0, 1].
  static constexpr double kMaxRelativeResidual = 1e-9;
  HealthReport check_health() const;

  // Checkpoint (common/state_record.hpp), under `prefix`: every species lattice, the cells
  // where they were last placed (restoring places them there again: interior nodes,
  // diffusivity fields, membrane rule), their Hb state, the start amounts and the inflow.
  void save_state(StateRecord& record, const std::string& prefix) const;
  void restore_state(const StateRecord& record, const std::string& prefix);

 private:
  void apply_species_fields(std::size_t i);
  void apply_compartments();
  void release_oxygen();
  std::span<const double> row_radius() const;  // the lattices' r per row (empty: planar)
  void update_no_o2_reactions();

  scene::TransportSetup setup_;
  geometry::Domain domain_;
  HbCoupling coupling_ = HbCoupling::cell_implicit;
  std::vector<transport::TransportLattice> lattices_;
  std::vector<std::vector<double>> base_D_;       // per species: D from the layers (empty: uniform)
  std::vector<std::vector<double>> base_source_;  // per species (empty: none)
  std::vector<geometry::Polygon> cells_;
  std::vector<CellNodes> nodes_;                  // per cell
  std::vector<std::unique_ptr<transport::FaceFluxCorrection>> corrections_;  // per species (may be null)
  std::vector<HbCell> hb_;                        // per cell, with [hemoglobin] (cell-mean kinetics)
  std::vector<LocalHb> local_hb_;                 // per cell, with hemoglobin.kinetics = "local"
  std::vector<double> saturation_;
  std::vector<double> initial_amount_, inflow_;
  std::vector<double> floor_;                     // per species: the default lower limit of C (µM), set by initialize
  std::vector<double> ux_, uy_;                   // scaled velocity (scratch)
  mutable std::vector<std::vector<double>> readout_;  // Ĉ per species (scratch)
  std::vector<std::uint8_t> compartment_ids_;     // [no_o2]: transport::Compartment per node
};

}  // namespace erythro::sim
