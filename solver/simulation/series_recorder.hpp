#pragma once
// An observer that keeps a run in memory: every diagnostics series by name (the same
// values the run writer stores in /diagnostics), optionally the cells' markers at every
// field output, the scene text and the summary. The V&V cases read their runs through
// it; a library user can too.
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

  // keep_cells: copy the cells' markers at every field output (output.fields_interval_steps).
  explicit SeriesRecorder(bool keep_cells = false) : keep_cells_(keep_cells) {}

  void on_start(const scene::Scene& scene, const scene::LatticeSetup& setup) override;
  void on_series_declared(std::span<const SeriesInfo> series) override;
  void on_sample(long step, std::span<const double> values) override;
  void on_cells(long step, const membrane::ImmersedCells& cells) override;
  void on_finish(const RunSummary& summary) override { summary_ = summary; }

  bool has(const std::string& name) const { return column_.count(name) > 0; }
  // The series `name`, one value per sample; throws std::out_of_range naming it if unknown.
  const std::vector<double>& series(const std::string& name) const;
  std::size_t samples() const { return values_.empty() ? 0 : values_[0].size(); }
  const std::vector<SeriesInfo>& declared() const { return declared_; }
  const std::vector<CellsSnapshot>& cell_snapshots() const { return snapshots_; }
  const RunSummary& summary() const { return summary_; }
  const std::string& scene_text() const { return scene_text_; }
  const scene::LatticeSetup& setup() const { return setup_; }

 private:
  bool keep_cells_ = false;
  std::vector<SeriesInfo> declared_;
  std::map<std::string, std::size_t> column_;
  std::vector<std::vector<double>> values_;  // per series
  std::vector<CellsSnapshot> snapshots_;
  RunSummary summary_;
  std::string scene_text_;
  scene::LatticeSetup setup_;
};

}  // namespace erythro::sim
