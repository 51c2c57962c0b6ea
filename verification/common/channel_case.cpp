#include "common/channel_case.hpp"

#include <cmath>
#include <stdexcept>

#include "common/scene_case.hpp"
#include "scene/units.hpp"

namespace erythro::vv {

std::vector<std::string> channel_overrides(const ChannelRunSpec& spec, const std::vector<std::string>& extra) {
  const double mu = case_scene(spec.scene).fluid.viscosity_cP * 1e-3;
  const double force = 2.0 * mu * spec.wall_shear_rate_per_s / (spec.height_um * 1e-6);  // N/m³
  std::vector<std::string> o = extra;
  for (const std::string& s : {set("domain.size_um", spec.length_um, spec.height_um),
                               set("domain.spacing_um", spec.spacing_um), set("cell_populations[0].markers", spec.markers),
                               set("cell_populations[0].min_gap_um", spec.spacing_um),
                               set("cell_populations[0].seed", spec.seed), set("body_force.density_N_m3", force, 0.0),
                               set("run.duration_s", spec.strain / spec.wall_shear_rate_per_s),
                               set("output.fields_interval_steps", 0L)})
    o.push_back(s);
  const double dt = scene::derive_lattice(case_scene(spec.scene, o)).scales.time_s;
  o.push_back(set("output.diagnostics_interval_steps",
                  std::max(1L, std::lround(spec.sample_strain / (spec.wall_shear_rate_per_s * dt)))));
  return o;
}

std::vector<double> block_means(const std::vector<double>& clock, const std::vector<double>& y, double from, double to,
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
  for (std::size_t b = 0; b < sum.size(); ++b) sum[b] = count[b] > 0 ? sum[b] / count[b] : std::nan("");
  return sum;
}

WindowEstimate block_estimate(const std::vector<double>& clock, const std::vector<double>& y, double from, double to,
                              int blocks) {
  const std::vector<double> means = block_means(clock, y, from, to, blocks);
  WindowEstimate e;
  for (double m : means) {
    if (std::isnan(m)) throw std::runtime_error("a block of the settled window is empty");
    e.mean += m / blocks;
  }
  double ss = 0.0;
  for (double m : means) ss += (m - e.mean) * (m - e.mean);
  e.se = std::sqrt(ss / (blocks - 1) / blocks);
  return e;
}

}  // namespace erythro::vv
