#pragma once
// The transverse dispersion of the cells of a finished run (docs/model.md §12, eqs 12.4, 12.4b):
// the centroid heights cell_<c>_centroid_y_um of run.h5 from `after_s` on, handed to
// analysis::transverse_dispersion. Used by `erythro dispersion` and by the V&V cases, so
// both judge the same samples.
#include <string>
#include <vector>

#include "analysis/dispersion.hpp"
#include "analysis/dispersion_profile.hpp"
#include "io/run_file.hpp"

namespace erythro::io {

// The cells' centroid heights y_c(t) (µm) at the evenly spaced samples from `after_s` on: one
// series per cell, all of one length, sampled every dt_s from first_time_s.
struct CentroidHeights {
  std::vector<std::vector<double>> y;
  double dt_s = 0.0, first_time_s = 0.0;
};

// The run's last sample, usually off the interval, is left out. Throws InputError naming
// `file_name` when there are no centroid series, fewer than three samples or unevenly spaced ones.
CentroidHeights settled_centroid_heights(const RunFile& file, const std::string& file_name, double after_s);

struct RunDispersion {
  analysis::Dispersion result;  // lags in s, MSD in µm², D_yy in µm²/s
  CentroidHeights heights;      // the samples judged: cells, samples per cell, Δt, first time
};

// analysis::transverse_dispersion of settled_centroid_heights(file, file_name, after_s).
RunDispersion run_dispersion(const RunFile& file, const std::string& file_name, double after_s,
                             const analysis::DispersionOptions& options = {});

// The dispersion across the channel (eq 12.4b) of the samples `whole` judged, in `bins` equal
// bins between the walls (y = 0 and the channel height of the run's /profiles; a run without
// profiles: the span of the centroids), at the lag `lag_s` (0: analysis::profile_lag of `whole`).
struct RunDispersionAcross {
  analysis::DispersionProfile profile;  // lag in s, heights in µm, drift in µm/s, D_b in µm²/s
  bool lag_from_msd = false;            // the lag was picked from the whole channel's MSD
};
// Throws InputError naming `file_name` when lag_s is not a whole number of sample intervals (within 1 % of one)
// shorter than the samples; std::invalid_argument when bins < 1.
RunDispersionAcross run_dispersion_across(const RunFile& file, const std::string& file_name, int bins, double lag_s,
                                          const RunDispersion& whole);

}  // namespace erythro::io
