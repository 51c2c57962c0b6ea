#include "manufactured_probe.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace erythro::vv {

double relative_l2_vector(std::span<const double> ax, std::span<const double> ay, std::span<const double> bx,
                          std::span<const double> by) {
  double num = 0.0, den = 0.0;
  for (std::size_t k = 0; k < bx.size(); ++k) {
    num += (ax[k] - bx[k]) * (ax[k] - bx[k]) + (ay[k] - by[k]) * (ay[k] - by[k]);
    den += bx[k] * bx[k] + by[k] * by[k];
  }
  return std::sqrt(num / den);
}

void ManufacturedSteadyProbe::declare(std::vector<sim::SeriesInfo>& series) const {
  series.push_back({"mms_error_u", "", "relative L2 velocity error against the manufactured solution"});
  series.push_back({"mms_transient_over_error", "",
                    "change over one chunk / (e - 1) / velocity error: remaining transient against the error"});
}

void ManufacturedSteadyProbe::sample(const sim::ProbeContext& c, std::span<double> values) {
  values[0] = values[1] = std::numeric_limits<double>::quiet_NaN();
  if (c.step == 0) return;
  const fluid::Moments& m = *c.moments;
  values[0] = relative_l2_vector(m.ux, m.uy, exact_ux_, exact_uy_);
  if (!previous_ux_.empty()) {
    const double change = relative_l2_vector(m.ux, m.uy, previous_ux_, previous_uy_);
    values[1] = change / (std::numbers::e - 1.0) / values[0];
  }
  previous_ux_ = m.ux;
  previous_uy_ = m.uy;
}

}  // namespace erythro::vv
