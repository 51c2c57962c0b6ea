#pragma once
// A probe is a diagnostic: named scalar time series sampled at every diagnostics step
// (output.diagnostics_interval_steps, the first and the last step), in physical units.
// The simulation owns the probes its scene asks for; observers receive the names once
// (RunObserver::on_series_declared) and one row of values per sample (on_sample): the
// run writer stores them as /diagnostics/<name> in run.h5, the V&V cases read them
// from a SeriesRecorder. One function computes each diagnostic, for both.
// A probe may also sample profiles: one value per lattice row j (y = (j + ½) h), at the
// same samples (on_profiles; run.h5 /profiles/<name>, one row per diagnostics sample).
#include <span>
#include <string>
#include <vector>

#include "common/state_record.hpp"
#include "fluid/fluid_lattice.hpp"
#include "scene/units.hpp"
#include "simulation/time_loop.hpp"

namespace erythro::sim {

class CellPhysics;
class TransportPhysics;

struct SeriesInfo {
  std::string name;         // e.g. "cell_0_taylor_deformation"
  std::string unit;         // e.g. "um", "deg", "" (dimensionless)
  std::string description;  // one line
};

// A profile across the lattice rows: grid.ny values per sample, row j at y = (j + ½) h.
struct ProfileInfo {
  std::string name;         // e.g. "velocity_x_um_s"
  std::string unit;         // e.g. "um/s", "" (dimensionless)
  std::string description;  // one line
};

// What a probe may read at a sample: the state after `step` steps.
struct ProbeContext {
  long step = 0;
  const scene::LatticeSetup& setup;
  const fluid::Moments* moments = nullptr;   // the fluid's moments (nullptr without a fluid)
  const CellPhysics* cells = nullptr;        // moving cells (nullptr without)
  const TransportPhysics* transport = nullptr;
};

class Probe {
 public:
  virtual ~Probe() = default;
  // Appends the probe's series, in the order sample() writes them.
  virtual void declare(std::vector<SeriesInfo>& series) const = 0;
  // Writes one value per declared series into `values`.
  virtual void sample(const ProbeContext& context, std::span<double> values) = 0;
  // Profiles (optional): appends the probe's profiles, and writes them at a sample, one
  // after the other (grid.ny values each, in declared order), into `values`.
  virtual void declare_profiles(std::vector<ProfileInfo>& /*profiles*/) const {}
  virtual void sample_profiles(const ProbeContext& /*context*/, std::span<double> /*values*/) {}
  // Optional per-step work (e.g. an extreme over every step, not only the samples).
  virtual void register_stages(TimeLoop& /*loop*/) {}
  // Checkpoint (common/state_record.hpp): what the probe carries from sample to sample
  // (running extremes, continued angles, the previous sample), under `prefix`; nothing
  // for a probe that only reads the current state.
  virtual void save_state(StateRecord& /*record*/, const std::string& /*prefix*/) const {}
  virtual void restore_state(const StateRecord& /*record*/, const std::string& /*prefix*/) {}
};

}  // namespace erythro::sim
