#include "io/run_dispersion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
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
  RunDispersion out;
  out.heights = settled_centroid_heights(file, file_name, after_s);
  out.result = analysis::transverse_dispersion(out.heights.y, out.heights.dt_s, options);
  return out;
}

RunDispersionAcross run_dispersion_across(const RunFile& file, const std::string& file_name, int bins, double lag_s,
                                          const RunDispersion& whole) {
  const CentroidHeights& h = whole.heights;
  RunDispersionAcross out;
  out.lag_from_msd = !(lag_s > 0.0);
  const double lag = out.lag_from_msd ? analysis::profile_lag(whole.result) : lag_s;
  const double k = std::round(lag / h.dt_s);
  const double samples = static_cast<double>(h.y.front().size());
  // A lag typed from the printed table (six digits) is off the interval by round-off: within a
  // hundredth of an interval it is that whole number of intervals.
  if (k < 1.0 || std::abs(k * h.dt_s - lag) > 0.01 * h.dt_s || k >= samples) {
    std::ostringstream why;
    why << file_name << ": --lag-s " << lag << " must be a whole number of sample intervals (" << h.dt_s << " s) from "
        << h.dt_s << " s to below " << samples * h.dt_s << " s (the samples from t = " << h.first_time_s << " s)";
    throw InputError(why.str());
  }
  double y_from = 0.0, y_to = 0.0;
  const std::vector<double>& rows = file.profile_y_um();
  if (rows.size() >= 2) {
    // The profile's rows are centred between the walls, y measured from the bottom one: the top
    // wall lies half a row above the last centre.
    y_to = rows.back() + 0.5 * (rows[1] - rows[0]);
  } else {
    y_from = y_to = h.y.front().front();
    for (const auto& s : h.y)
      for (const double v : s) {
        y_from = std::min(y_from, v);
        y_to = std::max(y_to, v);
      }
    y_to = std::nextafter(y_to, std::numeric_limits<double>::infinity());  // the highest centroid in the top bin
  }
  out.profile = analysis::dispersion_across(h.y, h.dt_s, static_cast<long>(k), y_from, y_to, bins);
  return out;
}

}  // namespace erythro::io
