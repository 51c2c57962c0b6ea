#pragma once
// The NO/O2 transport of a scene (docs/transport.md): one advection–diffusion–reaction
// lattice per [[species]], the cells' interiors as a compartment with their own
// diffusivity and initial concentration, and Hb–O2 kinetics per cell (cell-averaged
// saturation, release spread over the cell's interior nodes) for the species named by
// [hemoglobin]. Advanced with its own time step; the simulation decides when
// (docs/architecture.md "Time steps and coupling").
#include <span>
#include <string>
#include <vector>

#include "common/health.hpp"
#include "geometry/domain.hpp"
#include "geometry/polygon.hpp"
#include "scene/units.hpp"
#include "transport/transport_lattice.hpp"

namespace erythro::sim {

class TransportPhysics {
 public:
  // Cells (lattice units) define the interior compartment; may be empty.
  TransportPhysics(const scene::TransportSetup& setup, const geometry::Domain& domain,
                   std::span<const geometry::Polygon> cells);

  // The cells moved: recomputes the interior node lists and the diffusivity field
  // (the species keep their concentrations).
  void place_cells(std::span<const geometry::Polygon> cells);

  // One transport step. Velocity in FLUID lattice units (scaled by the set-up's
  // Δt_T/Δt_F), or empty spans for a still medium.
  void step(std::span<const double> fluid_ux, std::span<const double> fluid_uy);

  std::size_t species_count() const { return lattices_.size(); }
  const std::string& name(std::size_t i) const { return setup_.species[i].name; }
  const transport::TransportLattice& lattice(std::size_t i) const { return lattices_[i]; }
  // Cell-averaged HbO2 saturation per cell; empty without [hemoglobin].
  std::span<const double> saturation() const { return saturation_; }
  // Largest |M(t+1) − M(t) − sources − boundary flux| / Σ|g| of any species, last step.
  double max_relative_residual() const;
  // Finite concentrations and valid relaxation times in every species.
  HealthReport check_health() const;

 private:
  void apply_compartments();
  void release_oxygen();

  scene::TransportSetup setup_;
  geometry::Domain domain_;
  std::vector<transport::TransportLattice> lattices_;
  std::vector<std::vector<std::size_t>> interior_;  // per cell: its interior nodes
  std::vector<double> saturation_;
  std::vector<double> ux_, uy_;  // scaled velocity (scratch)
};

}  // namespace erythro::sim
