#pragma once
// A simulation assembled from a scene: it owns the modules the scene declares
// (the fluid unless transport.coupling = "none"; immersed cells, with their interior
// viscosity when asked, when the scene has [[cells]]; the NO/O2 transport when it has
// [transport]) and runs the time loop
// with the health monitor, the steady-state criterion and the output schedule.
#include <memory>

#include "fluid/fluid_lattice.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"
#include "simulation/cell_physics.hpp"
#include "simulation/run_observer.hpp"
#include "simulation/transport_physics.hpp"

namespace erythro::sim {

class Simulation {
 public:
  Simulation(scene::Scene scene, scene::LatticeSetup setup);

  // Runs to the end, to steady state, or until the health monitor stops it.
  // Never throws for divergence: the summary says so (status diverged).
  RunSummary run(RunObserver& observer);

  const scene::Scene& scene() const { return scene_; }
  const scene::LatticeSetup& setup() const { return setup_; }
  // The fluid, or nullptr in a still-medium transport scene.
  fluid::FluidLattice* fluid() { return fluid_.get(); }
  // The transport, or nullptr when the scene has no [transport].
  const TransportPhysics* transport() const { return transport_.get(); }
  // The immersed cells, or nullptr when the scene declares none.
  const membrane::ImmersedCells* cells() const { return cells_ ? &cells_->cells() : nullptr; }
  // The index field of the interior viscosity, or nullptr when the scene sets none.
  const interior::IndexField* index_field() const { return cells_ ? cells_->index_field() : nullptr; }
  const CellPhysics* cell_physics() const { return cells_.get(); }

 private:
  void apply_initial_condition();
  void apply_body_force(long step);

  scene::Scene scene_;
  scene::LatticeSetup setup_;
  std::unique_ptr<fluid::FluidLattice> fluid_;
  std::unique_ptr<CellPhysics> cells_;
  std::vector<geometry::Polygon> fixed_cells_;  // cells without a fluid: fixed shapes
  std::unique_ptr<TransportPhysics> transport_;
};

// Lattice diagnostics of given moments.
DiagnosticsSample diagnose(long step, const fluid::Moments& m);

// Taylor deformation D = (L − B)/(L + B) of a closed polygon: L, B are the semi-axes
// of the ellipse with the same second area moments (L/B = √(λ_max/λ_min)).
double taylor_deformation(const geometry::Polygon& p);

// "step 1200: velocity_x = nan at node (12, 3) (x = 6.25 µm, y = 1.75 µm): ..."
std::string describe_divergence(long step, const HealthReport& report, const scene::LatticeSetup& setup);
// The same for the transport ("O2 concentration = nan at node ...").
std::string describe_transport_divergence(long step, const HealthReport& report, const scene::LatticeSetup& setup);

}  // namespace erythro::sim
