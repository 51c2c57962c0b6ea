#include "channel_flows.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "simulation/fields_recorder.hpp"

namespace erythro::vv {

long steps_to_steady_state(int N, double nu, double residual) {
  const double pi = std::numbers::pi;
  return static_cast<long>(std::ceil(std::log(1.0 / residual) * N * N / (nu * pi * pi)));
}

ChannelResult run_channel(const SceneFile& file, const std::vector<std::string>& overrides,
                          const std::string& case_name, const std::string& label, CaseRunOptions options) {
  sim::FieldsRecorder fields;  // the initial and the final state
  options.observers.push_back(&fields);
  const CaseRun run = run_case_scene(file.scene(overrides), case_name, label, options);
  if (!run.ok()) throw std::runtime_error(case_name + " " + label + ": " + run.summary.diagnosis);
  const Grid g = run.setup.grid;
  const fluid::Moments& m = fields.last().moments;
  ChannelResult result;
  for (int y = 0; y < g.ny; ++y) result.ux.push_back(m.ux[g.index(g.nx / 2, y)]);
  result.steps = run.summary.steps;
  result.wall_time_s = run.summary.wall_time_s;
  result.scene_text = run.file.scene_text();
  return result;
}

std::vector<double> poiseuille_exact(int N, double force, double nu) {
  std::vector<double> u(static_cast<std::size_t>(N));
  for (int j = 0; j < N; ++j) {
    const double y = j + 0.5;
    u[static_cast<std::size_t>(j)] = force * y * (N - y) / (2.0 * nu);
  }
  return u;
}

}  // namespace erythro::vv
