#pragma once
// What the many-cell channel cases share: the overrides that size and drive the user's channel
// scene, time means of a settled suspension (block means over a window of strain), and the
// dispersion across the channel as a record's series.
#include <map>
#include <string>
#include <vector>

#include "io/result_record.hpp"
#include "io/run_dispersion.hpp"

namespace erythro::vv {

// The studies' checkpoint interval (s of wall time): a kill loses at most ten minutes of a run
// of hours; a checkpoint of a channel run takes milliseconds.
inline constexpr double kStudyCheckpointS = 600.0;

struct ChannelRunSpec {
  const char* scene = "scenes/rbc_channel.toml";  // from the source tree
  double length_um = 0.0, height_um = 0.0, spacing_um = 0.0;
  long markers = 0;  // per cell at this spacing
  long seed = 1;
  double min_gap_um = 0.0;  // the placement's smallest gap between cells; 0: the spacing h
  double wall_shear_rate_per_s = 0.0;  // of plasma alone at the driving force: F = 2 μ γ̇_w / H
  double strain = 0.0;                 // run length, strain units at γ̇_w
  double sample_strain = 0.05;         // diagnostics interval, strain units
  double settled_strain = -1.0;        // >= 0: keep the centroid heights from this strain on (dispersion)
  // > 0: a checkpoint every this many seconds of wall time, and the run picks up after a kill
  // where it was (CaseRunOptions::resume, run_resume.hpp): for the studies of hours.
  double checkpoint_interval_s = 0.0;
};

// The --set overrides of one channel run: domain, spacing, markers, placement gap h and seed,
// the body force, the duration, no field output and the diagnostics every `sample_strain`
// (Δt from the scene's unit conversion and [time_mapping], docs/model.md eq 10.8, after `extra`,
// which is appended first: e.g. time.tau).
std::vector<std::string> channel_overrides(const ChannelRunSpec& spec, const std::vector<std::string>& extra = {});

// One channel run's settled statistics and health, read back from its run.h5 (the series of
// the channel and cell-shape probes; docs/model.md §12).
struct ChannelSeries {
  std::vector<double> strain, eta, cfl, hd;  // γ̇_w t; η_rel, δ*, H_d per diagnostics sample
  double max_area_change = 0.0, max_edge_strain = 0.0;  // over the run (the probes' running extremes)
  double wall_s = 0.0;
  long steps = 0, cells = 0;
  io::CentroidHeights heights;  // with spec.settled_strain >= 0 and a completed run: y_c(t) from then on
  // With spec.settled_strain >= 0 and a completed run: the profiles across the channel (row
  // centres y, µm) averaged from then on: u_x (µm/s) and the haematocrit (docs/model.md §12).
  std::vector<double> profile_y_um, velocity_profile_um_s, haematocrit_profile;
  bool completed = false;  // false: the health monitor stopped it (`diagnosis` says why)
  // A resumable run (spec.checkpoint_interval_s > 0): the step it continued from (−1: none)
  // and whether it was read back finished; wall_s is then of its last part only.
  bool resumable = false, read_back = false;
  long resumed_from_step = -1;
  std::string diagnosis, scene_text;
};

// Runs the channel scene with channel_overrides(spec, extra) through vv::run_case_scene and reads
// its series back. A run the monitor stops is returned with completed = false (its series up to
// the last healthy sample), not thrown.
ChannelSeries run_channel(const ChannelRunSpec& spec, const std::string& case_name, const std::string& label,
                          const std::vector<std::string>& extra = {});

// The means of `y` over `blocks` equal blocks of from <= clock < to (non-finite samples left
// out); NaN for a block without samples.
std::vector<double> block_means(const std::vector<double>& clock, const std::vector<double>& y, double from, double to,
                                int blocks);

struct WindowEstimate {
  double mean = 0.0;  // mean of the block means
  double se = 0.0;    // their standard error: sqrt(Σ (b − mean)² / ((n − 1) n))
};

// block_means over the window, their mean and its standard error (blocks >= 2). Throws
// std::runtime_error when a block is empty.
WindowEstimate block_estimate(const std::vector<double>& clock, const std::vector<double>& y, double from, double to,
                              int blocks);

// Independent estimates of one quantity (one per seed) combined: their plain mean with its 95 %
// confidence half-width (Student's t_0.975 for n − 1 degrees of freedom, given, times the standard
// error over the seeds) and the homogeneity statistic χ² = Σ (m_s − m̄_w)²/se_s² about the
// inverse-variance weighted mean m̄_w (n ≥ 2).
struct SeedEnsemble {
  double mean = 0.0, ci95 = 0.0, chi2 = 0.0, weighted_mean = 0.0;
};
SeedEnsemble combine_seeds(const std::vector<WindowEstimate>& seeds, double t975);

// One-way analysis of variance of k groups (a seed's block means each): the ratio of the
// between-group to the within-group mean square,
//   F = [Σ_s n_s (m_s − m̄)² / (k − 1)] / [Σ_s Σ_j (y_sj − m_s)² / (N − k)],
// m_s the group means, m̄ the mean of all N values. Unlike χ² it does not take each group's
// standard error as exact: the within-group scatter is estimated from all groups together, and F
// with (k − 1, N − k) degrees of freedom allows for that. Needs k ≥ 2 and N > k; throws
// std::invalid_argument otherwise, and when a value is not finite.
struct OneWayAnova {
  double F = 0.0;
  int df_between = 0, df_within = 0;
};
OneWayAnova one_way_anova(const std::vector<std::vector<double>>& groups);

// One channel run as a row of a case's record (with its scene text): the case's own columns
// `keys` (seed, spacing, rate …), then steps, strain reached, the means over the settled window
// [from, to) of η_rel, δ* and H_d (NaN for a run the monitor stopped), the largest edge strain and
// area change, and the wall time; the same in one line on stdout, after `label`.
void add_channel_run(io::ResultRecord& record, const ChannelSeries& r, std::map<std::string, io::Value> keys,
                     double from, double to, int blocks, const std::string& label);

// "strain 200-400": the label of a window of strain units, for records' texts.
std::string strain_window(double from, double to);
// "400 strain units, means over strain 200-400 (four blocks of 50)": a run's length, its settled
// window and the window's blocks, for records' texts.
std::string strain_design(double strain, double from, int blocks);

// The informative metrics of a seed ensemble's means over strain from-to, suffixed `tag`:
// relative_apparent_viscosity_<tag> and cell_free_layer_normalised_<tag>, each with its 95 %
// half-width in the reason.
void add_ensemble_means(io::ResultRecord& record, const std::string& tag, const SeedEnsemble& eta,
                        const SeedEnsemble& cfl, double from, double to);

// D_yy across the channel (eq 12.4b) as a record's series, D_yy,b (µm²/s) against the bin's centre
// (µm): the bins at least kAcrossMinPairs origins started from (a strain unit's samples of ten
// cells at the channel cases' sampling of 0.05 strain units; emptier ones carry too few samples to
// show); the title adds the lag in strain units (the profile's lag times `wall_shear_rate`).
inline constexpr long kAcrossMinPairs = 200;
io::Series dispersion_across_series(const analysis::DispersionProfile& profile, double wall_shear_rate,
                                    const std::string& name, const std::string& title);

}  // namespace erythro::vv
