#pragma once
// Writes one run to OUT/run.h5 (+ OUT/run.xdmf): fields at the output interval,
// diagnostics time series, metadata. The file is written under a temporary name
// (run.h5.partial-<PID>); diagnostics reach the disk at least every kFlushSamples samples
// or kFlushSeconds of wall time, everything at every field output. How it ends:
//   - the run ends, however (completed, steady state, stopped, diverged, interrupted), or
//     fails elsewhere (abort: status "aborted: <reason>"): the file is closed, renamed into
//     place, and only then is run.xdmf written beside it, so the index never points at a
//     missing file, and an earlier run's pair (--force) is replaced as a pair;
//   - a write of its own fails (disk full, quota, a close that cannot flush): the
//     temporary is removed, nothing is put in place (an earlier run's files stay as they
//     were), and OutputError names the file. An unreadable file is never renamed into place.
//
// run.h5 layout:
//   /metadata         attrs scene_text, scene_path, git_revision, compiler, compile_flags,
//                     threads, status, diagnosis, steps, wall_time_s, mlups, and the
//                     lattice parameters (spacing_um, time_step_s, tau, ...)
//   /grid             attrs nx, ny, spacing_um, origin_um (cell-centred nodes)
//   /diagnostics/*    one 1-D dataset per diagnostics series (sim::Probe; attrs units,
//                     description), one entry per sample: step, time_s; with a fluid
//                     total_mass_kg_per_m, kinetic_energy_J_per_m, max_speed_um_s, max_mach,
//                     momentum_x_N_s_per_m, momentum_y_N_s_per_m;
//                     with moving cells, per cell c: cell_<c>_area_change, _taylor_deformation,
//                     _orientation_deg, _inclination_deg, _centroid_x_um, _centroid_y_um, _max_edge_strain,
//                     _marker_phase_deg, _marker0_angle_deg, and cells_max_area_change,
//                     cells_max_edge_strain (simulation/probes/cell_shape_probe.hpp);
//                     with an interior viscosity, interior_index_updates, _fill_fraction,
//                     _max_fill_mismatch_um2, _max_fallback_cells (probes/interior_probe.hpp);
//                     with [transport]: <species>_mean_uM, <species>_mass_balance_residual,
//                     <species>_max_mass_balance_residual, and with [hemoglobin]
//                     cell_<c>_saturation (simulation/probes/transport_probe.hpp)
//   /profiles/*       only for a channel (simulation/probes/channel_profile_probe.hpp):
//                     y_um (ny) the row centres (j + ½) h; per profile a 2-D dataset
//                     (samples, ny) (attrs units, description), row k the sample of
//                     /diagnostics/step[k]: velocity_x_um_s, the row's mean u_x, and
//                     haematocrit, the share of the row's nodes inside a cell (docs/model.md
//                     eq 12.6); time averages: `erythro profiles` (eq 12.7)
//   /timing           attrs <stage>_s, <stage>_calls: wall time of each time-loop stage
//   /fields/<step>/   density [kg/m³] (ny, nx), velocity [µm/s] (ny, nx, 3; z = 0), and one
//                     concentration [µM] (ny, nx) per species, named as the species; attrs
//                     step, time_s; every dataset has a `units` attribute
//   /cells/<step>/    only for scenes with [[cells]], at every field output:
//                     positions [µm] (markers of all cells, 2): (x, y) from the domain's
//                     lower-left corner, unwrapped across periodic sides; cell c owns rows
//                     offsets[c] … offsets[c+1] − 1 of
//                     offsets (cells + 1) [int64 marker index]; edges (markers, 2) [int64]:
//                     the closed polyline of each cell; cell (markers) [int64]: its cell;
//                     attrs step, time_s, cells
//   run.xdmf          the XDMF index of the fields and membranes (xdmf.hpp), written when
//                     run.h5 is in place
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/h5.hpp"
#include "io/xdmf.hpp"
#include "simulation/run_observer.hpp"

namespace erythro::io {

class RunWriter : public sim::RunObserver {
 public:
  // Creates the temporary file in `out_dir` (which must exist and be writable).
  explicit RunWriter(std::string out_dir);
  ~RunWriter() override;

  void on_start(const scene::Scene& scene, const scene::LatticeSetup& setup) override;
  void on_series_declared(std::span<const sim::SeriesInfo> series) override;
  void on_sample(long step, std::span<const double> values) override;
  void on_profiles_declared(std::span<const sim::ProfileInfo> profiles) override;
  void on_profiles(long step, std::span<const double> values) override;
  void on_fields(long step, const fluid::Moments& moments) override;
  void on_cells(long step, const membrane::ImmersedCells& cells) override;
  void on_transport_fields(long step, const sim::TransportFields& fields) override;
  void on_finish(const sim::RunSummary& summary) override;

  // Closes the file with status "aborted: <reason>" and moves it into place; does nothing
  // when the writer has already finished (e.g. its own write failed and removed the file).
  void abort(const std::string& reason);
  // Writes the buffered samples and flushes the file: before a checkpoint, so that a run
  // killed after it has every sample before the checkpoint's step on disk.
  void flush() { flush_samples(); }

  std::string h5_path() const;
  std::string xdmf_path() const;

 private:
  // Runs `write`; if it throws, discards the file and throws OutputError naming it.
  template <class Write>
  void guarded(Write&& write);
  void close_and_commit();
  void close_file();        // every handle, each close checked
  void discard() noexcept;  // closes what it can and removes the temporary file
  void write_xdmf();        // beside the committed run.h5
  void flush_samples();     // writes the buffered samples (and profiles) and flushes the file
  void flush_if_due();      // flush_samples when a block is full or kFlushSeconds have passed
  h5::Handle frame_group(long step);  // /fields/<step>, created (and listed for XDMF) once
  // The XDMF frame of `step` being assembled (fields, cells); a new step commits the last.
  XdmfFrame& xdmf_frame(long step);
  void commit_xdmf_frame();

  std::string out_dir_;
  scene::LatticeSetup setup_;
  h5::Handle file_;
  h5::Handle diagnostics_group_, fields_group_, cells_group_, profiles_group_;
  std::vector<std::unique_ptr<h5::AppendableSeries>> series_;  // one per declared series, in order
  std::vector<std::unique_ptr<h5::AppendableSeries>> profiles_;  // one per declared profile, in order
  static constexpr std::size_t kFlushSamples = 256;
  static constexpr double kFlushSeconds = 2.0;
  std::vector<std::vector<double>> pending_;  // per series, samples not yet written
  std::vector<std::vector<double>> pending_profiles_;  // per profile, rows not yet written
  std::size_t pending_samples_ = 0;
  std::chrono::steady_clock::time_point last_flush_ = std::chrono::steady_clock::now();
  std::optional<XdmfGrid> xdmf_grid_;  // known from on_start
  std::vector<XdmfFrame> xdmf_frames_;
  XdmfFrame frame_;
  bool has_frame_ = false;
  bool write_density_ = true, write_velocity_ = true;
  bool finished_ = false;  // committed, or discarded after a failed write
};

}  // namespace erythro::io
