#include "analysis/profiles.hpp"

#include <cstddef>
#include <limits>
#include <stdexcept>

namespace erythro::analysis {

std::size_t first_sample_after(const std::vector<double>& time, double after) {
  std::size_t k = 0;
  while (k < time.size() && time[k] < after) ++k;
  return k;
}

std::vector<double> time_average(const std::vector<double>& time, const std::vector<std::vector<double>>& rows,
                                 double after) {
  if (rows.size() < time.size()) throw std::invalid_argument("profiles: fewer profile rows than sample times");
  const std::size_t first = first_sample_after(time, after);
  if (first == time.size()) throw std::invalid_argument("profiles: no sample at or after the window's start");
  const std::size_t n = rows[first].size();
  for (std::size_t k = first; k < time.size(); ++k) {
    if (rows[k].size() != n) throw std::invalid_argument("profiles: the profile rows differ in length");
    if (k > first && !(time[k] > time[k - 1])) throw std::invalid_argument("profiles: the sample times must increase");
  }
  if (first + 1 == time.size()) return rows[first];  // a window of one sample
  // eq 12.7: trapezoids, summed in sample order
  std::vector<double> mean(n, 0.0);
  for (std::size_t k = first; k + 1 < time.size(); ++k) {
    const double w = 0.5 * (time[k + 1] - time[k]);
    for (std::size_t j = 0; j < n; ++j) mean[j] += w * (rows[k][j] + rows[k + 1][j]);
  }
  const double span = time.back() - time[first];
  for (double& v : mean) v /= span;
  return mean;
}

ChannelHaematocrits channel_haematocrits(const std::vector<double>& haematocrit, const std::vector<double>& cell_flux,
                                         const std::vector<double>& velocity) {
  if (haematocrit.empty() || cell_flux.size() != haematocrit.size() || velocity.size() != haematocrit.size())
    throw std::invalid_argument("profiles: the haematocrit, flux and velocity profiles need the same, non-zero length");
  double phi = 0.0, q = 0.0, u = 0.0;
  for (std::size_t j = 0; j < haematocrit.size(); ++j) {  // eq 12.7
    phi += haematocrit[j];
    q += cell_flux[j];
    u += velocity[j];
  }
  ChannelHaematocrits h;
  h.tube = phi / static_cast<double>(haematocrit.size());
  h.discharge = u != 0.0 ? q / u : std::numeric_limits<double>::quiet_NaN();
  return h;
}

}  // namespace erythro::analysis
