#pragma once
// Time-averaged profiles across a channel (docs/model.md §12, eq 12.7) from the profiles a
// run writes at every diagnostics sample (/profiles in run.h5, eq 12.6). Over the samples
// at times t_0 < t_1 < … < t_N of the window (every sample with t ≥ `after`), the average
// of a profile p_k(y_j) is the trapezoidal time mean
//
//   ⟨p⟩_j = Σ_k ½ (p_k,j + p_k+1,j)(t_k+1 − t_k) / (t_N − t_0)
//
// (uneven samples, e.g. the run's dense first steps or its last step, weigh by the time
// they stand for; a window of one sample is that sample). From the averaged profiles:
//   H_t = (1/n) Σ_j ⟨φ⟩_j,   H_d = Σ_j ⟨q⟩_j / Σ_j ⟨ū⟩_j
// the tube and the discharge haematocrit of the nodes (φ the haematocrit, q the cells' flux,
// ū the velocity profile).
#include <vector>

namespace erythro::analysis {

// eq 12.7: the trapezoidal time mean of `rows` (one profile per sample, all of the same
// length) over the samples with time[k] ≥ after. Throws std::invalid_argument when no
// sample is in the window, when `time` does not increase, or the rows are ragged or fewer
// than the times.
std::vector<double> time_average(const std::vector<double>& time, const std::vector<std::vector<double>>& rows,
                                 double after);

// The index of the first sample with time[k] ≥ after (time.size() when none).
std::size_t first_sample_after(const std::vector<double>& time, double after);

struct ChannelHaematocrits {
  double tube = 0.0;       // (1/n) Σ_j φ_j
  double discharge = 0.0;  // Σ_j q_j / Σ_j ū_j; NaN when Σ_j ū_j = 0
};
// eq 12.7 from (averaged) profiles of the same length: haematocrit φ, cells' flux q, velocity ū.
ChannelHaematocrits channel_haematocrits(const std::vector<double>& haematocrit, const std::vector<double>& cell_flux,
                                         const std::vector<double>& velocity);

}  // namespace erythro::analysis
