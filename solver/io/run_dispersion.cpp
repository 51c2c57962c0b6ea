#include "io/run_dispersion.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "analysis/profiles.hpp"
#include "common/error.hpp"

namespace erythro::io {

CentroidHeights settled_centroid_heights(const RunFile& file, const std::string& file_name, double after_s) {
  const std::vector<double>& time = file.series("time_s");
  const std::size_t first = analysis::first_sample_after(time, after_s);
  CentroidHeights out;
  for (int c = 0; file.has("cell_" + std::to_string(c) + "_centroid_y_um"); ++c) {
    const std::vector<double>& s = file.series("cell_" + std::to_string(c) + "_centroid_y_um");
    out.y.emplace_back(s.begin() + static_cast<std::ptrdiff_t>(std::min(first, s.size())), s.end());
  }
  if (out.y.empty()) throw InputError(file_name + ": no cell centroid series (cell_<c>_centroid_y_um): a run with cells?");
  if (time.size() < first + 3)
    throw InputError(file_name + ": fewer than 3 samples after " + std::to_string(after_s) + " s");
  const double dt = time[first + 1] - time[first];
  std::size_t end = time.size();  // the run's last step is sampled too, usually off the interval: left out
  if (std::abs(time[end - 1] - time[end - 2] - dt) > 1e-6 * dt) --end;
  for (std::size_t i = first + 1; i < end; ++i)
    if (std::abs(time[i] - time[i - 1] - dt) > 1e-6 * dt)
      throw InputError(file_name + ": the samples are not evenly spaced in time from t = " +
                       std::to_string(time[first]) + " s on: pass --after-s past the uneven ones");
  for (auto& s : out.y) s.resize(std::min(s.size(), end - first));
  out.dt_s = dt;
  out.first_time_s = time[first];
  return out;
}

RunDispersion run_dispersion(const RunFile& file, const std::string& file_name, double after_s,
                             const analysis::DispersionOptions& options) {
  const CentroidHeights h = settled_centroid_heights(file, file_name, after_s);
  RunDispersion out;
  out.result = analysis::transverse_dispersion(h.y, h.dt_s, options);
  out.cells = h.y.size();
  out.samples = h.y.front().size();
  out.dt_s = h.dt_s;
  out.first_time_s = h.first_time_s;
  return out;
}

}  // namespace erythro::io
