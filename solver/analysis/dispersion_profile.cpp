#include "analysis/dispersion_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace erythro::analysis {

DispersionProfile dispersion_across(const std::vector<std::vector<double>>& y, double dt, long lag_steps, double y_from,
                                    double y_to, int bins) {
  if (y.empty() || y.front().empty()) throw std::invalid_argument("dispersion across: need cells with samples");
  if (!(dt > 0.0)) throw std::invalid_argument("dispersion across: the sample interval must be > 0");
  if (bins < 1 || !(y_to > y_from)) throw std::invalid_argument("dispersion across: need bins >= 1 and y_to > y_from");
  const std::size_t T = y.front().size();
  for (const auto& s : y)
    if (s.size() != T) throw std::invalid_argument("dispersion across: every cell needs the same number of samples");
  if (lag_steps < 1 || static_cast<std::size_t>(lag_steps) >= T)
    throw std::invalid_argument("dispersion across: the lag must be at least one sample and shorter than the series");

  const std::size_t k = static_cast<std::size_t>(lag_steps);
  const double width = (y_to - y_from) / bins;
  std::vector<double> sum(bins, 0.0), sum_sq(bins, 0.0);
  std::vector<long> pairs(bins, 0);
  for (const auto& s : y)
    for (std::size_t t = 0; t + k < T; ++t) {
      const double b_real = std::floor((s[t] - y_from) / width);
      if (!(b_real >= 0.0) || b_real >= bins) continue;  // outside [y_from, y_to), or NaN
      const int b = static_cast<int>(b_real);
      const double d = s[t + k] - s[t];
      sum[b] += d;
      sum_sq[b] += d * d;
      ++pairs[b];
    }

  DispersionProfile out;
  out.lag = static_cast<double>(lag_steps) * dt;
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  for (int b = 0; b < bins; ++b) {
    DispersionBin bin;
    bin.y_from = y_from + b * width;
    bin.y_to = b + 1 == bins ? y_to : y_from + (b + 1) * width;
    bin.pairs = pairs[b];
    const double n = static_cast<double>(pairs[b]);
    const double mean = pairs[b] > 0 ? sum[b] / n : kNaN;
    bin.drift = mean / out.lag;
    // eq 12.4b: the variance about the drift, with Bessel's correction
    bin.D = pairs[b] > 1 ? std::max(0.0, (sum_sq[b] - n * mean * mean) / (n - 1.0)) / (2.0 * out.lag) : kNaN;
    out.bins.push_back(bin);
  }
  return out;
}

double profile_lag(const Dispersion& d, const DispersionOptions& options) {
  if (d.msd.empty()) throw std::invalid_argument("dispersion across: the MSD holds no lag");
  if (d.found) return d.lag_from;
  for (const MsdPoint& p : d.msd)
    if (p.slope <= 1.0 + options.slope_tolerance) return p.lag;
  return d.msd.back().lag;
}

}  // namespace erythro::analysis
