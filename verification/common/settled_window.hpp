#pragma once
// Time means of a settled suspension, shared by the many-cell cases: a series' mean over a
// window of its clock (strain units) from block means, and the sampling interval in steps.
#include <vector>

#include "scene/scene.hpp"

namespace erythro::vv {

struct WindowEstimate {
  double mean = 0.0;  // mean of the block means
  double se = 0.0;    // their standard error: sqrt(Σ (b − mean)² / ((n − 1) n))
};

// `y` over from <= clock < to, cut into `blocks` equal blocks (non-finite samples left out);
// with one block, se = 0. Throws std::runtime_error when a block is empty.
WindowEstimate block_estimate(const std::vector<double>& clock, const std::vector<double>& y, double from, double to,
                              int blocks);

// The steps between samples every `strain_interval` strain units at shear rate `shear_rate_per_s`,
// with Δt from the scene's unit conversion (its [time_mapping], docs/model.md eq 10.8).
long steps_per_strain_interval(const scene::Scene& scene, double shear_rate_per_s, double strain_interval);

}  // namespace erythro::vv
