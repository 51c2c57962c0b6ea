#pragma once
// An observer that keeps the fluid's fields in memory, in lattice units, bit for bit as
// the simulation holds them: ρ, u_x, u_y at every field output (output.fields_interval_steps;
// 0: the initial and final states). For analyses that need the lattice values themselves
// (run.h5 stores them in physical units), e.g. the Laplace pressure jump c_s²(ρ_in − ρ_out)
// of verification.laplace_pressure; a library user can pass it to io::run_scene too.
#include <vector>

#include "simulation/run_observer.hpp"

namespace erythro::sim {

class FieldsRecorder : public RunObserver {
 public:
  struct Snapshot {
    long step = 0;
    fluid::Moments moments;  // lattice units
  };

  void on_fields(long step, const fluid::Moments& moments) override { snapshots_.push_back({step, moments}); }

  const std::vector<Snapshot>& snapshots() const { return snapshots_; }
  // The last field output (the final state of a run that did not diverge); throws
  // std::logic_error when there is none.
  const Snapshot& last() const;
  // The field output after `step` steps; throws std::logic_error naming the step if there is none.
  const fluid::Moments& at(long step) const;

 private:
  std::vector<Snapshot> snapshots_;
};

}  // namespace erythro::sim
