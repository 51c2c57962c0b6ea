#pragma once
// A simulation assembled from a scene: it owns the modules the scene declares (the fluid
// unless transport.coupling = "none"; immersed cells, with their interior viscosity and
// aggregation when asked, when the scene has [[cells]]; the NO/O2 transport when it has
// [transport]), each of which registers its stages in the time loop (time_loop.hpp), and
// the probes (probe.hpp) whose series the observers receive. run() adds the observe
// stage (health monitor, diagnostics, output, steady state, stop rules) and runs the loop.
//
// Extension points, for library users and the V&V cases alike: add_stage (e.g. a
// manufactured source written into a field before the fluid step) and add_probe (a
// diagnostic of one's own), both before run(). Mutable access to the modules is meant
// for setting their state before run() (an initial field, a τ field).
//
// Checkpoints (docs/architecture.md "Checkpoints and restart"): with a checkpoint writer
// set, run() hands it the state of every module at the steps the scene asks for;
// restore() continues from such a state.
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "common/state_record.hpp"

#include "fluid/fluid_lattice.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"
#include "simulation/cell_physics.hpp"
#include "simulation/probe.hpp"
#include "simulation/run_observer.hpp"
#include "simulation/time_loop.hpp"
#include "simulation/transport_physics.hpp"

namespace erythro::sim {

class Observation;

class Simulation {
 public:
  Simulation(scene::Scene scene, scene::LatticeSetup setup);

  // Runs to the end, to steady state, until a stop rule holds, until the health monitor
  // stops it, or until an interrupt is requested (interrupt.hpp; checked before every
  // step). Never throws for divergence: the summary says so (status diverged).
  // Call once.
  RunSummary run(RunObserver& observer);

  // A stage of the caller's own (time_loop.hpp), run in `phase` after the modules' stages
  // of that phase.
  void add_stage(Phase phase, std::string name, TimeLoop::Function function, long every = 1, long first = 0);
  // A probe of the caller's own; its series follow the built-in ones.
  void add_probe(std::unique_ptr<Probe> probe);

  // Checkpoints (docs/cli.md "Checkpoints and restart"): `writer` receives the state after
  // `step` steps whenever output.checkpoint_interval_steps or _s asks for one, taken before
  // that step's observation (so a restart observes it as an uninterrupted run does). Set
  // before run(); without a writer no checkpoint is taken.
  using CheckpointWriter = std::function<void(long step, const StateRecord& state)>;
  void set_checkpoint_writer(CheckpointWriter writer);
  // Continues from a checkpoint of a simulation of the same scene: the modules take their
  // state back now, the observation (probes, stop rules, steady-state detector) at the start
  // of run(), which then goes on from the checkpoint's step. Call before run(). Throws
  // InputError when the checkpoint lies past the run's end.
  void restore(StateRecord state);

  const scene::Scene& scene() const { return scene_; }
  const scene::LatticeSetup& setup() const { return setup_; }
  // The fluid, or nullptr in a still-medium transport scene.
  fluid::FluidLattice* fluid() { return fluid_.get(); }
  const fluid::FluidLattice* fluid() const { return fluid_.get(); }
  // The transport, or nullptr when the scene has no [transport].
  TransportPhysics* transport() { return transport_.get(); }
  const TransportPhysics* transport() const { return transport_.get(); }
  // The immersed cells, or nullptr when the scene declares none (or has no fluid).
  const membrane::ImmersedCells* cells() const { return cells_ ? &cells_->cells() : nullptr; }
  // The index field of the interior viscosity, or nullptr when the scene sets none.
  const interior::IndexField* index_field() const { return cells_ ? cells_->index_field() : nullptr; }
  const CellPhysics* cell_physics() const { return cells_.get(); }
  CellPhysics* cell_physics() { return cells_.get(); }  // e.g. to pin the index field's arrangement
  const TimeLoop& time_loop() const { return loop_; }

 private:
  void apply_initial_condition();
  void apply_body_force(long step);
  void register_fluid_stages();
  void register_transport_stages();
  StateRecord capture_state(long step, const Observation& observation) const;

  scene::Scene scene_;
  scene::LatticeSetup setup_;
  std::unique_ptr<fluid::FluidLattice> fluid_;
  std::unique_ptr<CellPhysics> cells_;
  std::vector<geometry::Polygon> fixed_cells_;  // cells without a fluid: fixed shapes
  std::unique_ptr<TransportPhysics> transport_;
  std::vector<std::unique_ptr<Probe>> probes_;
  TimeLoop loop_;
  std::vector<geometry::Polygon> moved_;  // scratch: the cells' polygons for the transport
  bool ran_ = false;
  CheckpointWriter checkpoint_writer_;
  long start_step_ = 0;                // the checkpoint's step after restore(), else 0
  std::optional<StateRecord> restored_;  // kept for the observation until run() starts
};

}  // namespace erythro::sim
