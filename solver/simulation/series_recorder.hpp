#pragma once
// An observer that keeps a run in memory: every diagnostics series by name (the same
// values the run writer stores in /diagnostics), every profile by name (/profiles),
// optionally the cells' markers at every field output, the scene text and the summary.
// The V&V cases read their runs through it; a library user can too.
#include <map>
#include <string>
#include <vector>

#include "geometry/polygon.hpp"
#include "simulation/run_observer.hpp"

namespace erythro::sim {

class SeriesRecorder : public RunObserver {
 public:
  struct CellsSnapshot {
    long step = 0;
    std::vector<geometry::Polygon> cells;  // lattice units
  };

  // keep_cells: copy the cells' markers at every field output (output.fields_interval_steps);
  // keep_transport: copy the species' fields of the latest field output (µM, the values run.h5 gets).
  explicit SeriesRecorder(bool keep_cells = false, bool keep_transport = false)
      : keep_cells_(keep_cells), keep_transport_(keep_transport) {}

  void on_start(const scene::Scene& scene, const scene::LatticeSetup& setup) override;
  void on_series_declared(std::span<const SeriesInfo> series) override;
  void on_sample(long step, std::span<const double> values) override;
  void on_profiles_declared(std::span<const ProfileInfo> profiles) override;
  void on_profiles(long step, std::span<const double> values) override;
  void on_cells(long step, const membrane::ImmersedCells& cells) override;
  void on_transport_fields(long step, const TransportFields& fields) override;
  void on_finish(const RunSummary& summary) override { summary_ = summary; }

  bool has(const std::string& name) const { return column_.count(name) > 0; }
  // The series `name`, one value per sample; throws std::out_of_range naming it if unknown.
  const std::vector<double>& series(const std::string& name) const;
  std::size_t samples() const { return values_.empty() ? 0 : values_[0].size(); }
  const std::vector<SeriesInfo>& declared() const { return declared_; }
  bool has_profile(const std::string& name) const { return profile_column_.count(name) > 0; }
  // The profile `name` at every sample (one row of grid.ny values per sample, row j at
  // y = (j + ½) h); throws std::out_of_range naming it if unknown.
  const std::vector<std::vector<double>>& profile(const std::string& name) const;
  const std::vector<CellsSnapshot>& cell_snapshots() const { return snapshots_; }
  // The species field `name` at the latest field output (keep_transport); throws std::out_of_range.
  const std::vector<double>& transport_field(const std::string& name) const;
  long transport_field_step() const { return transport_step_; }
  const RunSummary& summary() const { return summary_; }
  const std::string& scene_text() const { return scene_text_; }
  const scene::LatticeSetup& setup() const { return setup_; }

 private:
  bool keep_cells_ = false, keep_transport_ = false;
  std::map<std::string, std::vector<double>> transport_;
  long transport_step_ = -1;
  std::vector<SeriesInfo> declared_;
  std::map<std::string, std::size_t> column_;
  std::vector<std::vector<double>> values_;  // per series
  std::map<std::string, std::size_t> profile_column_;
  std::vector<std::vector<std::vector<double>>> profiles_;  // per profile, per sample
  std::vector<CellsSnapshot> snapshots_;
  RunSummary summary_;
  std::string scene_text_;
  scene::LatticeSetup setup_;
};

}  // namespace erythro::sim
