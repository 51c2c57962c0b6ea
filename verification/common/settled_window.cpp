#include "common/settled_window.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "scene/units.hpp"

namespace erythro::vv {

WindowEstimate block_estimate(const std::vector<double>& clock, const std::vector<double>& y, double from, double to,
                              int blocks) {
  const double width = (to - from) / blocks;
  std::vector<double> sum(static_cast<std::size_t>(blocks), 0.0);
  std::vector<int> count(static_cast<std::size_t>(blocks), 0);
  for (std::size_t k = 0; k < y.size() && k < clock.size(); ++k) {
    if (clock[k] < from || clock[k] >= to || !std::isfinite(y[k])) continue;
    const auto b = static_cast<std::size_t>(std::min(blocks - 1, static_cast<int>((clock[k] - from) / width)));
    sum[b] += y[k];
    ++count[b];
  }
  WindowEstimate e;
  for (int b = 0; b < blocks; ++b) {
    if (count[static_cast<std::size_t>(b)] == 0) throw std::runtime_error("a block of the settled window is empty");
    sum[static_cast<std::size_t>(b)] /= count[static_cast<std::size_t>(b)];
    e.mean += sum[static_cast<std::size_t>(b)] / blocks;
  }
  if (blocks < 2) return e;  // one block: a mean without an error
  double ss = 0.0;
  for (double v : sum) ss += (v - e.mean) * (v - e.mean);
  e.se = std::sqrt(ss / (blocks - 1) / blocks);
  return e;
}

long steps_per_strain_interval(const scene::Scene& scene, double shear_rate_per_s, double strain_interval) {
  const double dt = scene::derive_lattice(scene).scales.time_s;
  return std::max(1L, std::lround(strain_interval / (shear_rate_per_s * dt)));
}

}  // namespace erythro::vv
