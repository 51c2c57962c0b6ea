#pragma once
// The composed time loop (docs/architecture.md "The time loop"): each module of a
// simulation registers named stages in a phase; one step runs the due stages phase by
// phase, in registration order within a phase, and times each. A new module adds
// stages, not branches. (After waLBerla's SweepTimeloop: functions before and after
// the sweeps of a step.)
//
// Step n advances the state from n to n + 1 steps; every stage is called with n. A
// stage runs at step n when n ≥ first and (n − first) is a multiple of `every`.
// Nothing is allocated per step.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace erythro::sim {

// Where a stage runs within a step. The order is the order of the physics of one step
// (thesis §II.3: forces, spreading, stream–collide, interpolation, marker update).
enum class Phase : std::uint8_t {
  prepare,      // time-dependent inputs (body force), user stages that set fields
  forces,       // index field, membrane and aggregation forces
  spread,       // force field: reset, spreading
  fluid,        // the lattice Boltzmann step
  interpolate,  // fluid velocity at the markers' supports
  advect,       // marker update
  transport,    // species lattices (sub-cycled)
  observe,      // progress, health, diagnostics, output, stop criteria (state after the step)
};
const char* to_string(Phase phase);

struct StageTiming {
  std::string name;
  Phase phase;
  double seconds = 0.0;  // wall time summed over calls
  long calls = 0;
};

class TimeLoop {
 public:
  using Function = std::function<void(long step)>;

  // Adds a stage. Stages of one phase run in the order they were added.
  void add(Phase phase, std::string name, Function function, long every = 1, long first = 0);

  // Runs the due stages of step n in phase order.
  void run_step(long step);

  bool has(const std::string& name) const;
  // Per stage, in execution order.
  std::vector<StageTiming> timings() const;
  // Summed wall time of the stages whose name is `name`.
  double seconds(const std::string& name) const;

 private:
  struct Stage {
    StageTiming timing;
    Function function;
    long every = 1, first = 0;
  };
  std::vector<Stage> stages_;  // sorted by phase, stable
};

}  // namespace erythro::sim
