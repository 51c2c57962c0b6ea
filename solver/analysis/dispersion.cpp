#include "analysis/dispersion.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace erythro::analysis {

namespace {

// Lags k = 1 … k_max, about 10 per decade (every k below 10), ascending and distinct.
std::vector<long> lag_steps(long k_max) {
  std::vector<long> k;
  for (long j = 1; j <= k_max;) {
    k.push_back(j);
    j = std::max(j + 1, static_cast<long>(std::floor(static_cast<double>(j) * 1.2589254117941673)));  // 10^(1/10)
  }
  return k;
}

// eq 12.4: least-squares line MSD = 2 D τ + c over points [from, to].
double fit_diffusivity(const std::vector<MsdPoint>& p, std::size_t from, std::size_t to) {
  double st = 0.0, sm = 0.0, stt = 0.0, stm = 0.0;
  const double n = static_cast<double>(to - from + 1);
  for (std::size_t i = from; i <= to; ++i) {
    st += p[i].lag;
    sm += p[i].msd;
    stt += p[i].lag * p[i].lag;
    stm += p[i].lag * p[i].msd;
  }
  const double slope = (n * stm - st * sm) / (n * stt - st * st);
  return 0.5 * slope;
}

}  // namespace

Dispersion transverse_dispersion(const std::vector<std::vector<double>>& y, double dt,
                                 const DispersionOptions& options) {
  if (y.empty() || y.front().size() < 3) throw std::invalid_argument("dispersion: need cells with >= 3 samples");
  if (!(dt > 0.0)) throw std::invalid_argument("dispersion: the sample interval must be > 0");
  const std::size_t T = y.front().size();
  for (const auto& s : y)
    if (s.size() != T) throw std::invalid_argument("dispersion: every cell needs the same number of samples");

  Dispersion out;
  const long k_max = std::max(1L, static_cast<long>(options.max_lag_fraction * static_cast<double>(T - 1)));
  for (const long k : lag_steps(k_max)) {
    double sum = 0.0;
    long pairs = 0;
    for (const auto& s : y)
      for (std::size_t t = 0; t + static_cast<std::size_t>(k) < T; ++t) {
        const double d = s[t + static_cast<std::size_t>(k)] - s[t];
        sum += d * d;
        ++pairs;
      }
    out.msd.push_back({static_cast<double>(k) * dt, pairs ? sum / static_cast<double>(pairs) : 0.0, 0.0, pairs});
  }
  auto& p = out.msd;
  const std::size_t n = p.size();
  auto log_slope = [&](std::size_t a, std::size_t b) {
    if (!(p[a].msd > 0.0) || !(p[b].msd > 0.0)) return 0.0;
    return std::log(p[b].msd / p[a].msd) / std::log(p[b].lag / p[a].lag);
  };
  for (std::size_t i = 0; i < n; ++i)
    p[i].slope = n < 2 ? 0.0 : log_slope(i == 0 ? 0 : i - 1, i + 1 < n ? i + 1 : n - 1);

  // The longest run of lags with |α − 1| ≤ tolerance.
  std::size_t best_from = 0, best_len = 0;
  for (std::size_t i = 0; i < n;) {
    if (std::abs(p[i].slope - 1.0) > options.slope_tolerance) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < n && std::abs(p[j + 1].slope - 1.0) <= options.slope_tolerance) ++j;
    if (j - i + 1 > best_len) {
      best_from = i;
      best_len = j - i + 1;
    }
    i = j + 1;
  }
  if (best_len >= static_cast<std::size_t>(std::max(2, options.min_points))) {
    out.found = true;
    out.lag_from = p[best_from].lag;
    out.lag_to = p[best_from + best_len - 1].lag;
    out.D = fit_diffusivity(p, best_from, best_from + best_len - 1);
  }
  return out;
}

double dispersion_at_lag(const Dispersion& d, double lag) {
  if (d.msd.empty()) throw std::invalid_argument("dispersion: the MSD holds no lag");
  const MsdPoint* nearest = &d.msd.front();
  for (const MsdPoint& p : d.msd)
    if (std::abs(p.lag - lag) < std::abs(nearest->lag - lag)) nearest = &p;
  return nearest->msd / (2.0 * nearest->lag);
}

}  // namespace erythro::analysis
