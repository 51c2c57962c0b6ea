#pragma once
// A simulation assembled from a scene: it owns the modules the scene declares
// (today the fluid; later membranes, aggregation, species) and runs the time loop
// with the health monitor, the steady-state criterion and the output schedule.
#include <memory>

#include "fluid/fluid_lattice.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"
#include "simulation/run_observer.hpp"

namespace erythro::sim {

class Simulation {
 public:
  Simulation(scene::Scene scene, scene::LatticeSetup setup);

  // Runs to the end, to steady state, or until the health monitor stops it.
  // Never throws for divergence: the summary says so (status diverged).
  RunSummary run(RunObserver& observer);

  const scene::Scene& scene() const { return scene_; }
  const scene::LatticeSetup& setup() const { return setup_; }
  fluid::FluidLattice& fluid() { return *fluid_; }

 private:
  void apply_initial_condition();
  void apply_body_force(long step);

  scene::Scene scene_;
  scene::LatticeSetup setup_;
  std::unique_ptr<fluid::FluidLattice> fluid_;
};

// Lattice diagnostics of given moments.
DiagnosticsSample diagnose(long step, const fluid::Moments& m);

// "step 1200: velocity_x = nan at node (12, 3) (x = 6.25 µm, y = 1.75 µm): ..."
std::string describe_divergence(long step, const HealthReport& report, const scene::LatticeSetup& setup);

}  // namespace erythro::sim
