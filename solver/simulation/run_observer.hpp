#pragma once
// What a running simulation tells the outside world. The I/O layer (HDF5 writer), the
// command's progress display and the V&V cases' SeriesRecorder implement this
// interface; the simulation never includes anything from the layers above it.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fluid/fluid_lattice.hpp"
#include "membrane/immersed_cells.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"
#include "simulation/probe.hpp"
#include "simulation/time_loop.hpp"

namespace erythro::sim {

// Concentration fields of the species (µM), by name, for a field output.
struct TransportFields {
  std::vector<std::string> names;
  std::vector<std::span<const double>> concentration;
};

// completed: ran every step; steady_state: run.steady_state met; stopped: a [[stop_when]]
// rule met; diverged: the health monitor (or a module) stopped an unhealthy run;
// interrupted: a signal asked it to end (interrupt.hpp).
enum class RunStatus { completed, steady_state, stopped, diverged, interrupted };
std::string to_string(RunStatus status);
// The status that to_string wrote, or nothing (e.g. "running", "aborted: …").
std::optional<RunStatus> run_status_from(const std::string& text);

struct RunSummary {
  RunStatus status = RunStatus::completed;
  long steps = 0;
  double wall_time_s = 0.0;
  double mlups = 0.0;     // million lattice-node updates per second
  // Of wall_time_s: rebuilding the interior index field and its τ (0 without one),
  // measured inside the run, so its share of the step is free of run-to-run host noise.
  double index_field_time_s = 0.0;
  // The part of index_field_time_s the step waited for: all of it on one thread; less
  // when the field is rebuilt beside the force stage (sim::CellPhysics).
  double index_field_exposed_time_s = 0.0;
  // The index field's rebuilds during the run, and how many of them ran beside the force stage
  // (on two or more threads, where each arrangement is measured and the faster kept).
  long index_field_rebuilds = 0, index_field_rebuilds_beside_forces = 0;
  std::string diagnosis;  // why the run ended early (health monitor, stop rule, steady state)
  int threads = 1;
  std::vector<StageTiming> stages;  // wall time of every stage of the time loop
};

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  virtual void on_start(const scene::Scene&, const scene::LatticeSetup&) {}
  // The diagnostics series, once before the first sample: "step" and "time_s" first, then
  // every probe's series (probe.hpp).
  virtual void on_series_declared(std::span<const SeriesInfo>) {}
  // One value per declared series, at every diagnostics sample of a healthy state.
  virtual void on_sample(long /*step*/, std::span<const double> /*values*/) {}
  // The probes' profiles (probe.hpp), once after on_series_declared; not called when no
  // probe has one. Then, right after each on_sample, their values at that sample: the
  // profiles one after the other, grid.ny values each, in declared order.
  virtual void on_profiles_declared(std::span<const ProfileInfo>) {}
  virtual void on_profiles(long /*step*/, std::span<const double> /*values*/) {}
  // Fields of a healthy state (lattice units).
  virtual void on_fields(long /*step*/, const fluid::Moments&) {}
  // The cells' markers, right after on_fields (only for scenes with [[cells]] and a fluid).
  virtual void on_cells(long /*step*/, const membrane::ImmersedCells&) {}
  // Species concentrations at a field output (after on_fields when there is a fluid).
  virtual void on_transport_fields(long /*step*/, const TransportFields&) {}
  virtual void on_progress(long /*step*/, long /*total_steps*/, double /*mlups*/) {}
  virtual void on_finish(const RunSummary&) {}
};

// Forwards every event to several observers, in order.
class ObserverList : public RunObserver {
 public:
  void add(RunObserver& observer) { observers_.push_back(&observer); }
  void on_start(const scene::Scene& s, const scene::LatticeSetup& l) override {
    for (auto* o : observers_) o->on_start(s, l);
  }
  void on_series_declared(std::span<const SeriesInfo> series) override {
    for (auto* o : observers_) o->on_series_declared(series);
  }
  void on_sample(long step, std::span<const double> values) override {
    for (auto* o : observers_) o->on_sample(step, values);
  }
  void on_profiles_declared(std::span<const ProfileInfo> profiles) override {
    for (auto* o : observers_) o->on_profiles_declared(profiles);
  }
  void on_profiles(long step, std::span<const double> values) override {
    for (auto* o : observers_) o->on_profiles(step, values);
  }
  void on_fields(long step, const fluid::Moments& m) override {
    for (auto* o : observers_) o->on_fields(step, m);
  }
  void on_cells(long step, const membrane::ImmersedCells& c) override {
    for (auto* o : observers_) o->on_cells(step, c);
  }
  void on_transport_fields(long step, const TransportFields& f) override {
    for (auto* o : observers_) o->on_transport_fields(step, f);
  }
  void on_progress(long step, long total, double mlups) override {
    for (auto* o : observers_) o->on_progress(step, total, mlups);
  }
  void on_finish(const RunSummary& s) override {
    for (auto* o : observers_) o->on_finish(s);
  }

 private:
  std::vector<RunObserver*> observers_;
};

}  // namespace erythro::sim
