#pragma once
// The transverse dispersion of the cells of a finished run (docs/model.md §12, eq 12.4):
// the centroid heights cell_<c>_centroid_y_um of run.h5 from `after_s` on, handed to
// analysis::transverse_dispersion. Used by `erythro dispersion` and by the V&V cases, so
// both judge the same samples.
#include <string>
#include <vector>

#include "analysis/dispersion.hpp"
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
  std::size_t cells = 0, samples = 0;
  double dt_s = 0.0, first_time_s = 0.0;
};

// analysis::transverse_dispersion of settled_centroid_heights(file, file_name, after_s).
RunDispersion run_dispersion(const RunFile& file, const std::string& file_name, double after_s,
                             const analysis::DispersionOptions& options = {});

}  // namespace erythro::io
