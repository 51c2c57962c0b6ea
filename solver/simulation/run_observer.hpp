#pragma once
// What a running simulation tells the outside world. The I/O layer (HDF5 writer)
// and the command's progress display implement this interface; the simulation
// never includes anything from the layers above it.
#include <span>
#include <string>
#include <vector>

#include "fluid/fluid_lattice.hpp"
#include "membrane/immersed_cells.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"

namespace erythro::sim {

// Diagnostics of one step, lattice units (the writer converts with UnitScales).
struct DiagnosticsSample {
  long step = 0;
  double total_mass = 0.0;      // Σ ρ
  double kinetic_energy = 0.0;  // ½ Σ ρ|u|²
  double max_speed = 0.0;       // max |u|
  double max_mach = 0.0;        // max |u| / c_s
};

// Per-cell shape diagnostics (scenes with [[cells]] only), sent right after each
// DiagnosticsSample: A/A0 − 1 and the Taylor deformation D = (L − B)/(L + B) of the
// ellipse with the same second area moments (simulation.cpp), one entry per cell.
struct CellDiagnostics {
  long step = 0;
  std::vector<double> area_change, taylor_deformation;
};

// Transport diagnostics (scenes with [transport]), sent with each DiagnosticsSample:
// per species the mean concentration (µM) and the last step's relative mass-balance
// residual; per cell the HbO2 saturation (with [hemoglobin]).
struct TransportDiagnostics {
  long step = 0;
  std::vector<double> mean_concentration, residual;
  std::vector<double> saturation;
};

// Concentration fields of the species (µM), by name, for a field output.
struct TransportFields {
  std::vector<std::string> names;
  std::vector<std::span<const double>> concentration;
};

enum class RunStatus { completed, steady_state, diverged };
std::string to_string(RunStatus status);

struct RunSummary {
  RunStatus status = RunStatus::completed;
  long steps = 0;
  double wall_time_s = 0.0;
  double mlups = 0.0;     // million lattice-node updates per second
  // Of wall_time_s: rebuilding the interior index field and its τ (0 without one),
  // measured inside the run, so its share of the step is free of run-to-run host noise.
  double index_field_time_s = 0.0;
  // The part of index_field_time_s the step waited for: all of it on one thread; less
  // when the field is rebuilt beside the force stage (sim::CellPhysics::advance).
  double index_field_exposed_time_s = 0.0;
  std::string diagnosis;  // health monitor's message when diverged
  int threads = 1;
};

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  virtual void on_start(const scene::Scene&, const scene::LatticeSetup&) {}
  virtual void on_diagnostics(const DiagnosticsSample&) {}
  virtual void on_cell_diagnostics(const CellDiagnostics&) {}
  // Fields of a healthy state (lattice units).
  virtual void on_fields(long /*step*/, const fluid::Moments&) {}
  // The cells' markers, right after on_fields (only for scenes with [[cells]]).
  virtual void on_cells(long /*step*/, const membrane::ImmersedCells&) {}
  virtual void on_transport_diagnostics(const TransportDiagnostics&) {}
  // Species concentrations at a field output (after on_fields when there is a fluid).
  virtual void on_transport_fields(long /*step*/, const TransportFields&) {}
  virtual void on_progress(long /*step*/, long /*total_steps*/, double /*mlups*/) {}
  virtual void on_finish(const RunSummary&) {}
};

}  // namespace erythro::sim

namespace erythro::sim {

// Forwards every event to several observers, in order.
class ObserverList : public RunObserver {
 public:
  void add(RunObserver& observer) { observers_.push_back(&observer); }
  void on_start(const scene::Scene& s, const scene::LatticeSetup& l) override {
    for (auto* o : observers_) o->on_start(s, l);
  }
  void on_diagnostics(const DiagnosticsSample& d) override {
    for (auto* o : observers_) o->on_diagnostics(d);
  }
  void on_cell_diagnostics(const CellDiagnostics& d) override {
    for (auto* o : observers_) o->on_cell_diagnostics(d);
  }
  void on_fields(long step, const fluid::Moments& m) override {
    for (auto* o : observers_) o->on_fields(step, m);
  }
  void on_cells(long step, const membrane::ImmersedCells& c) override {
    for (auto* o : observers_) o->on_cells(step, c);
  }
  void on_transport_diagnostics(const TransportDiagnostics& d) override {
    for (auto* o : observers_) o->on_transport_diagnostics(d);
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
