#pragma once
// An observer that keeps the fluid's fields in memory at every field output
// (output.fields_interval_steps, the first and the last state) from a given step on:
// ρ and u in lattice units, the very values the simulation computed, where run.h5
// holds them converted to kg/m³ and µm/s. For callers that judge fields bit for bit
// (the V&V cases' error norms) or post-process them without reading the file back.
#include <vector>

#include "simulation/run_observer.hpp"

namespace erythro::sim {

class FieldRecorder : public RunObserver {
 public:
  struct Frame {
    long step = 0;
    fluid::Moments fields;  // lattice units
  };

  // Keeps the outputs at steps >= first_step.
  explicit FieldRecorder(long first_step = 0) : first_step_(first_step) {}

  void on_fields(long step, const fluid::Moments& moments) override;

  const std::vector<Frame>& frames() const { return frames_; }
  bool has(long step) const;
  // The fields after `step` steps; throws std::out_of_range naming the step if not kept.
  const fluid::Moments& at(long step) const;
  // The last output (the run's final state); throws std::out_of_range if there is none.
  const Frame& last() const;

 private:
  long first_step_ = 0;
  std::vector<Frame> frames_;
};

}  // namespace erythro::sim
