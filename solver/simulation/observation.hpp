#pragma once
// The observe stage of a run (docs/architecture.md "The time loop"): at every step where
// something is due (field output, diagnostics sample, health check, steady-state check)
// it checks the health of every module first (transport, cells, fluid: nothing unhealthy
// reaches an observer), then samples the probes, hands out fields, and evaluates the
// steady-state criterion and the [[stop_when]] rules.
#include <memory>
#include <string>
#include <vector>

#include "fluid/fluid_lattice.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"
#include "simulation/cell_physics.hpp"
#include "simulation/probe.hpp"
#include "simulation/run_observer.hpp"
#include "simulation/stop_rule.hpp"
#include "simulation/transport_physics.hpp"

namespace erythro::sim {

// How a run ends: set once by the stage that ends it.
struct RunControl {
  bool stop = false;
  RunStatus status = RunStatus::completed;
  std::string diagnosis;
  void end(RunStatus s, std::string why) {
    stop = true;
    status = s;
    diagnosis = std::move(why);
  }
};

class Observation {
 public:
  Observation(const scene::Scene& scene, const scene::LatticeSetup& setup, fluid::FluidLattice* fluid,
              const CellPhysics* cells, const TransportPhysics* transport, std::vector<std::unique_ptr<Probe>>& probes,
              RunObserver& observer, RunControl& control);

  // Sends the series names (and the profiles', if any) to the observer and binds the stop
  // rules to the series.
  void declare();
  // Observes the state after `step` steps (`final_state`: the run's last step).
  void observe(long step, bool final_state);

  // Checkpoint (common/state_record.hpp), under `prefix`: the steady-state detector's last
  // velocity, the stop rules and every probe's memory (the output schedule itself is a
  // function of the step).
  void save_state(StateRecord& record, const std::string& prefix) const;
  void restore_state(const StateRecord& record, const std::string& prefix);

 private:
  void sample(long step, const fluid::Moments* moments);
  void output_fields(long step, const fluid::Moments* moments);
  bool healthy(long step);

  const scene::Scene& scene_;
  const scene::LatticeSetup& setup_;
  fluid::FluidLattice* fluid_;
  const CellPhysics* cells_;
  const TransportPhysics* transport_;
  std::vector<std::unique_ptr<Probe>>& probes_;
  RunObserver& observer_;
  RunControl& control_;
  std::vector<SeriesInfo> series_;
  std::vector<std::size_t> probe_offset_;  // first column of each probe in row_
  std::vector<double> row_;
  std::vector<ProfileInfo> profiles_;
  std::vector<std::size_t> profile_offset_;  // first value of each probe's profiles in profile_row_
  std::vector<double> profile_row_;
  std::vector<StopRule> stop_rules_;
  std::vector<double> previous_ux_, previous_uy_;  // steady-state check
};

// "diverged at step 1200: velocity_x = nan at node (12, 3) [x = 6.25 um, y = 1.75 um] ..."
std::string describe_divergence(long step, const HealthReport& report, const scene::LatticeSetup& setup);
// The same for the transport ("O2 concentration = nan at node ...").
std::string describe_transport_divergence(long step, const HealthReport& report, const scene::LatticeSetup& setup);
// The same for a membrane ("cell 0 area change = 0.25 exceeds the limit 0.2 (monitor.max_area_change) ...").
std::string describe_cell_divergence(long step, const HealthReport& report);

}  // namespace erythro::sim
