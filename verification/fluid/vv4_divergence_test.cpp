// Case verification.divergence_diagnosis (issue 3 item 7).
//
// Requirement: every diverging run stops with the health monitor's diagnosis. A few
// deliberately unstable set-ups run as scenes through the product path
// (verification/fluid/periodic_box.toml and double_shear_layer.toml with overrides, run
// by vv::run_case_scene with an extra observer); each must end with status `diverged`
// and a diagnosis naming the step (the step at which the run stopped), the node (inside
// the grid) and the quantity (density, velocity_x, velocity_y or mach), and no observer
// may ever receive a non-finite density or velocity.
// Reference: the monitor of solver/simulation/observation.cpp (health scan before
// anything is handed to an observer; describe_divergence). The runaway set-up has an
// exact stop step: in a periodic box from rest under a uniform force F (Guo forcing)
// the velocity of the s-th collision is u_s = (s − ½)F at every node, so the first
// health scan with u_s/c_s > max_mach comes at the first step ≥ s* = ⌊max_mach c_s/F + ½⌋ + 1
// at which the loop observes the state (a multiple of the monitor, fields or
// diagnostics interval: the scan precedes every observation), at node (0, 0)
// (row-major scan, all nodes equal).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <regex>

#include "common/case_support.hpp"
#include "common/scene_case.hpp"
#include "fluid_scenes.hpp"
#include "lattice/d2q9.hpp"
#include "simulation/simulation.hpp"

using namespace erythro;

namespace {

// Checks every field and diagnostics sample it receives is finite.
class FiniteObserver : public sim::RunObserver {
 public:
  void on_sample(long, std::span<const double> values) override {
    ++samples;
    for (double v : values)
      if (!std::isfinite(v)) ++non_finite;
  }
  void on_fields(long step, const fluid::Moments& m) override {
    ++fields;
    last_step = step;
    for (const auto* v : {&m.rho, &m.ux, &m.uy})
      for (double x : *v)
        if (!std::isfinite(x)) ++non_finite;
  }
  void on_finish(const sim::RunSummary& s) override { finished = s; }
  long samples = 0, fields = 0, non_finite = 0, last_step = -1;
  sim::RunSummary finished;
};

struct Diagnosis {
  bool parsed = false;
  long step = -1, x = -1, y = -1;
  std::string quantity;
};

// "diverged at step S: Q = V at node (X, Y) ..." (sim::describe_divergence).
Diagnosis parse(const std::string& text) {
  static const std::regex re(R"(step (\d+): (\w+) = \S+ at node \((-?\d+), (-?\d+)\))");
  std::smatch m;
  Diagnosis d;
  if (!std::regex_search(text, m, re)) return d;
  d.parsed = true;
  d.step = std::stol(m[1]);
  d.quantity = m[2];
  d.x = std::stol(m[3]);
  d.y = std::stol(m[4]);
  return d;
}

bool complete(const Diagnosis& d, long stop_step, const Grid& g) {
  const bool known = d.quantity == "density" || d.quantity == "velocity_x" || d.quantity == "velocity_y" ||
                     d.quantity == "mach";
  return d.parsed && known && d.step == stop_step && d.x >= 0 && d.x < g.nx && d.y >= 0 && d.y < g.ny;
}

struct UnstableSetup {
  std::string name;
  const vv::SceneFile* file = nullptr;
  std::vector<std::string> overrides;
  long predicted_step = -1;  // -1: not predicted
};

const vv::SceneFile& box_scene() {
  static const vv::SceneFile f("verification/fluid/periodic_box.toml");
  return f;
}

// The monitor every 10 steps, fields every 7 (not a multiple of it), diagnostics every 5.
UnstableSetup base(const std::string& name, int n, fluid::CollisionModel model, double tau, long steps,
                   double max_mach) {
  UnstableSetup s;
  s.name = name;
  s.file = &box_scene();
  s.overrides = {vv::set_grid(n, n), vv::set_collision(model), vv::set("run.steps", steps),
                 vv::set("monitor.interval_steps", 10L), vv::set("monitor.max_mach", max_mach),
                 vv::set("output.fields_interval_steps", 7L), vv::set("output.diagnostics_interval_steps", 5L),
                 vv::set("limits.min_tau_margin", 0.0), vv::set("limits.max_mach", 10.0)};  // built to diverge
  s.overrides.push_back(vv::set_tau(*s.file, s.overrides, tau));
  return s;
}

// Taylor–Green vortex of amplitude U on 32 x 32 at τ = 0.5001 (TRT: Λ = 3/16).
UnstableSetup taylor_green(const std::string& name, fluid::CollisionModel model, double U, double max_mach,
                           long steps) {
  UnstableSetup s = base(name, 32, model, 0.5001, steps, max_mach);
  s.overrides.push_back(vv::set("initial.type", "\"taylor_green\""));
  s.overrides.push_back(vv::set_initial_velocity(*s.file, s.overrides, {U, 0.0}));
  return s;
}

std::vector<UnstableSetup> unstable_setups() {
  std::vector<UnstableSetup> out;
  {  // Uniform force in a periodic box: unbounded acceleration, exact stop step.
    UnstableSetup s = base("runaway_force", 32, fluid::CollisionModel::bgk, 0.8, 2000, 0.3);
    s.overrides.push_back(vv::set_body_force(*s.file, s.overrides, {1e-3, 0.0}));
    const scene::Scene scene = s.file->scene(s.overrides);
    const double F = s.file->setup(s.overrides).body_force[0];
    const double limit = scene.monitor.max_mach * std::sqrt(d2q9::cs2);
    // The scan runs whenever anything is observed (monitor, fields or diagnostics due):
    // the first such step at or after the first s with (s − ½)F > limit.
    const long K = scene.monitor.interval_steps, Kf = scene.output.fields_interval_steps,
               Kd = scene.output.diagnostics_interval_steps;
    long step = static_cast<long>(std::floor(limit / F + 0.5)) + 1;
    while (step % K != 0 && step % Kf != 0 && step % Kd != 0) ++step;
    s.predicted_step = step;
    out.push_back(s);
  }
  // Taylor–Green vortex at BGK/TRT/regularized τ = 0.5001: blows up. The regularized
  // model survives U = 0.3 longer, so it gets a larger amplitude. The last set-up keeps
  // the Mach limit out of reach: only the non-finite / density checks can stop it,
  // while fields go to the observer every 7 steps.
  out.push_back(taylor_green("taylor_green_bgk_tau0.5001", fluid::CollisionModel::bgk, 0.3, 1.0, 4000));
  out.push_back(taylor_green("taylor_green_trt_tau0.5001", fluid::CollisionModel::trt, 0.3, 1.0, 4000));
  out.push_back(
      taylor_green("taylor_green_regularized_tau0.5001", fluid::CollisionModel::regularized, 0.4, 1.0, 4000));
  // No Mach limit in effect: 1e30, the largest value monitor.max_mach takes (only a
  // non-finite velocity can stop this run).
  out.push_back(taylor_green("taylor_green_bgk_no_mach_limit", fluid::CollisionModel::bgk, 0.3, 1e30, 20000));
  {  // The double shear layer of the stability map, BGK τ = 0.5001, U = 0.2 (unstable
     // there), on 32 × 32 for 2 convective times, the map's monitor (every 16 steps).
    static const vv::SceneFile layer("verification/fluid/double_shear_layer.toml");
    UnstableSetup s;
    s.name = "double_shear_layer_bgk_tau0.5001";
    s.file = &layer;
    s.overrides = {vv::set_grid(32, 32), vv::set_collision(fluid::CollisionModel::bgk),
                   vv::set("run.steps", static_cast<long>(std::ceil(2.0 * 32 / 0.2)))};
    s.overrides.push_back(vv::set_tau(layer, s.overrides, 0.5001));
    s.overrides.push_back(vv::set_initial_velocity(layer, s.overrides, {0.2, 0.0}));
    out.push_back(s);
  }
  return out;
}
}  // namespace

TEST(DivergenceDiagnosis, EveryDivergedRunStopsWithDiagnosis) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.divergence_diagnosis", "fluid");
  record.set_requirement(
      "Every deliberately unstable run stops with status diverged and a health-monitor diagnosis naming the stop "
      "step, a node inside the grid and the quantity; no observer receives a non-finite field; the runaway-force "
      "run stops exactly at the predicted check.");
  record.set_reference(
      "Health monitor of solver/simulation/observation.cpp (scan before any observer call; describe_divergence); "
      "runaway force: u_s = (s - 1/2) F under Guo forcing (docs/model.md sec. 1), stop at "
      "the first observed step (multiple of the monitor, fields or diagnostics interval) after u_s/c_s exceeds "
      "max_mach.");
  record.set_parameter("monitor_interval_steps", 10.0);
  record.set_parameter("fields_interval_steps", 7.0);
  record.set_parameter("diagnostics_interval_steps", 5.0);

  long complete_count = 0, cases = 0, non_finite = 0;
  double step_error = std::numeric_limits<double>::quiet_NaN();
  for (UnstableSetup& s : unstable_setups()) {
    ++cases;
    FiniteObserver observer;
    vv::CaseRunOptions options;
    options.observers.push_back(&observer);
    const vv::CaseRun run =
        vv::run_case_scene(s.file->scene(s.overrides), "verification.divergence_diagnosis", s.name, options);
    const sim::RunSummary& summary = run.summary;
    const Diagnosis d = parse(summary.diagnosis);
    const bool ok = summary.status == sim::RunStatus::diverged && complete(d, summary.steps, run.setup.grid) &&
                    observer.finished.status == sim::RunStatus::diverged && run.file.status() == "diverged";
    complete_count += ok ? 1 : 0;
    non_finite += observer.non_finite;
    if (s.predicted_step >= 0) step_error = double(summary.steps - s.predicted_step);
    std::cout << s.name << ": " << sim::to_string(summary.status) << " after " << summary.steps << " steps; "
              << summary.diagnosis << "\n";
    record.add_run({{"setup", s.name}, {"path", std::string("scene")},
                    {"model", std::string(fluid::to_string(run.setup.collision.model))},
                    {"tau", run.setup.collision.tau}, {"status", sim::to_string(summary.status)},
                    {"steps", double(summary.steps)},
                    {"predicted_step", s.predicted_step >= 0 ? double(s.predicted_step)
                                                             : std::numeric_limits<double>::quiet_NaN()},
                    {"quantity", d.quantity}, {"node_x", double(d.x)}, {"node_y", double(d.y)},
                    {"diagnosis_complete", ok ? 1.0 : 0.0}, {"fields_observed", double(observer.fields)},
                    {"non_finite_observed", double(observer.non_finite)}, {"diagnosis", summary.diagnosis},
                    {"wall_time_s", run.wall_time_s}},
                   run.file.scene_text());
    EXPECT_TRUE(ok) << s.name << ": " << summary.diagnosis;
  }

  EXPECT_TRUE(record.add_metric({"diagnosed runs", "unstable set-ups that stopped as diverged with step, node and "
                                 "quantity in the diagnosis", "", double(complete_count), double(cases), 0.0,
                                 io::Comparison::at_least,
                                 "every set-up is built to diverge; each one must be diagnosed"}));
  EXPECT_TRUE(record.add_metric({"non-finite observations", "non-finite density/velocity values handed to observers",
                                 "", double(non_finite), 0.0, 0.0, io::Comparison::at_most,
                                 "the monitor scans the state before any observer call"}));
  EXPECT_TRUE(record.add_metric({"runaway stop step error", "stop step minus predicted stop step (runaway force)",
                                 "steps", step_error, 0.0, 0.0, io::Comparison::absolute,
                                 "u_s = (s - 1/2) F holds to round-off at every node, far from the threshold"}));
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
