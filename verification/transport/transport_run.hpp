#pragma once
// How the transport V&V cases run the solver (docs/verification-transport.md): every run is a
// scene beside the cases (verification/transport/*.toml) with --set-style overrides, run by
// vv::run_case_scene as `erythro run` runs it; the case reads the diagnostics series (the
// transport probe: mass balance of every step, amounts, steady-state change, layer fluxes,
// saturations) and the species' final field. What a case adds through CaseRunOptions::configure
// is its manufactured data only: a per-node D, velocity or source field and an analytic start.
#include <functional>
#include <string>
#include <vector>

#include "common/scene_case.hpp"
#include "io/result_record.hpp"
#include "simulation/series_recorder.hpp"

namespace erythro::vv {

struct TransportRun {
  long steps = 0;
  double wall_time_s = 0.0;
  double worst_mass_residual = 0.0;  // <species>_max_mass_balance_residual at the end
  bool converged = true;             // steady runs: stopped by the [[stop_when]] rule
  std::vector<double> C;             // the species' final field (transport.readout), µM
  sim::SeriesRecorder series;        // every diagnostics series
  scene::LatticeSetup setup;
  std::string scene_text;
};

// Runs `scene` (case `case_name`, run folder `label`) and reads species `species` back.
TransportRun run_transport(const scene::Scene& scene, const std::string& case_name, const std::string& label,
                           const std::string& species, const std::function<void(sim::Simulation&)>& configure = {});

// Overrides of a steady run: sample every `interval` steps, stop ([[stop_when]] entry 0 of the
// scene) when the largest change of the species' C since the previous sample is below
// `tolerance` (series <species>_change_uM), at most `max_steps` steps; the health monitor at the
// same interval.
std::vector<std::string> steady_overrides(const std::string& species, long interval, double tolerance, long max_steps);

// Metric: worst relative mass-balance residual over every run of the case ≤ 1e-13.
io::Metric mass_balance_metric(double worst_relative_residual);

}  // namespace erythro::vv
