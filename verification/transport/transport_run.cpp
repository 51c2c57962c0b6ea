#include "transport_run.hpp"

#include <algorithm>
#include <cmath>

namespace erythro::vv {

TransportRun run_transport(const scene::Scene& scene, const std::string& case_name, const std::string& label,
                           const std::string& species, const std::function<void(sim::Simulation&)>& configure) {
  TransportRun r;
  r.series = sim::SeriesRecorder(false, true);
  CaseRunOptions options;
  options.configure = configure;
  options.observers = {&r.series};
  const CaseRun run = run_case_scene(scene, case_name, label, options);
  r.steps = run.summary.steps;
  r.wall_time_s = run.wall_time_s;
  r.worst_mass_residual = r.series.series(species + "_max_mass_balance_residual").back();
  r.converged = run.summary.status == sim::RunStatus::stopped;
  r.C = r.series.transport_field(species);
  r.setup = run.setup;
  r.scene_text = run.file.scene_text();
  return r;
}

std::vector<std::string> steady_overrides(const std::string& species, long interval, double tolerance, long max_steps) {
  return {set("run.steps", max_steps),
          set("output.diagnostics_interval_steps", interval),
          set("monitor.interval_steps", interval),
          set("stop_when[0].series", "\"" + species + "_change_uM\""),
          set("stop_when[0].below", tolerance)};
}

io::Metric mass_balance_metric(double worst) {
  return {"mass_balance_residual",
          "worst relative mass-balance residual |dM - sources - boundary inflow| / sum|g| over every step of every run",
          "",
          worst,
          1e-13,
          0.0,
          io::Comparison::at_most,
          "the balance (docs/transport.md eq T5) is an algebraic identity of the scheme: only round-off of sums over "
          "<= 1e5 nodes remains (~1e-16 per node, random-walk accumulation stays far below 1e-13)"};
}

}  // namespace erythro::vv
