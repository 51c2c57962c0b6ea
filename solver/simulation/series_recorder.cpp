#include "simulation/series_recorder.hpp"

#include <stdexcept>

namespace erythro::sim {

void SeriesRecorder::on_start(const scene::Scene& scene, const scene::LatticeSetup& setup) {
  scene_text_ = scene.source_text;
  setup_ = setup;
}

void SeriesRecorder::on_series_declared(std::span<const SeriesInfo> series) {
  declared_.assign(series.begin(), series.end());
  values_.assign(series.size(), {});
  for (std::size_t k = 0; k < series.size(); ++k) column_[series[k].name] = k;
}

void SeriesRecorder::on_sample(long /*step*/, std::span<const double> values) {
  for (std::size_t k = 0; k < values.size() && k < values_.size(); ++k) values_[k].push_back(values[k]);
}

void SeriesRecorder::on_profiles_declared(std::span<const ProfileInfo> profiles) {
  profiles_.assign(profiles.size(), {});
  for (std::size_t k = 0; k < profiles.size(); ++k) profile_column_[profiles[k].name] = k;
}

void SeriesRecorder::on_profiles(long /*step*/, std::span<const double> values) {
  if (profiles_.empty()) return;
  const std::size_t rows = values.size() / profiles_.size();
  for (std::size_t k = 0; k < profiles_.size(); ++k)
    profiles_[k].emplace_back(values.begin() + static_cast<std::ptrdiff_t>(k * rows),
                              values.begin() + static_cast<std::ptrdiff_t>((k + 1) * rows));
}

const std::vector<std::vector<double>>& SeriesRecorder::profile(const std::string& name) const {
  const auto it = profile_column_.find(name);
  if (it == profile_column_.end()) throw std::out_of_range("SeriesRecorder: no profile '" + name + "'");
  return profiles_[it->second];
}

void SeriesRecorder::on_cells(long step, const membrane::ImmersedCells& cells) {
  if (!keep_cells_) return;
  CellsSnapshot s;
  s.step = step;
  for (int c = 0; c < cells.cell_count(); ++c) s.cells.push_back(cells.polygon(c));
  snapshots_.push_back(std::move(s));
}

void SeriesRecorder::on_transport_fields(long step, const TransportFields& fields) {
  if (!keep_transport_) return;
  transport_step_ = step;
  for (std::size_t i = 0; i < fields.names.size(); ++i)
    transport_[fields.names[i]].assign(fields.concentration[i].begin(), fields.concentration[i].end());
}

const std::vector<double>& SeriesRecorder::transport_field(const std::string& name) const {
  const auto it = transport_.find(name);
  if (it == transport_.end()) throw std::out_of_range("SeriesRecorder: no transport field '" + name + "' kept");
  return it->second;
}

const std::vector<double>& SeriesRecorder::series(const std::string& name) const {
  const auto it = column_.find(name);
  if (it == column_.end()) throw std::out_of_range("SeriesRecorder: no diagnostics series '" + name + "'");
  return values_[it->second];
}

}  // namespace erythro::sim
