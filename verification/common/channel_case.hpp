#pragma once
// What the many-cell channel cases share: the overrides that size and drive the user's channel
// scene, and time means of a settled suspension (block means over a window of strain).
#include <string>
#include <vector>

namespace erythro::vv {

struct ChannelRunSpec {
  const char* scene = "scenes/rbc_channel.toml";  // from the source tree
  double length_um = 0.0, height_um = 0.0, spacing_um = 0.0;
  long markers = 0;  // per cell at this spacing
  long seed = 1;
  double wall_shear_rate_per_s = 0.0;  // of plasma alone at the driving force: F = 2 μ γ̇_w / H
  double strain = 0.0;                 // run length, strain units at γ̇_w
  double sample_strain = 0.05;         // diagnostics interval, strain units
};

// The --set overrides of one channel run: domain, spacing, markers, placement gap h and seed,
// the body force, the duration, no field output and the diagnostics every `sample_strain`
// (Δt from the scene's unit conversion and [time_mapping], docs/model.md eq 10.8, after `extra`,
// which is appended first: e.g. time.tau).
std::vector<std::string> channel_overrides(const ChannelRunSpec& spec, const std::vector<std::string>& extra = {});

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

}  // namespace erythro::vv
