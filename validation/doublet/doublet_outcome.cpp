#include "doublet_outcome.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace erythro::vv {

std::string doublet_outcome(const DoubletShearResult& r) {
  if (r.diverged) return "diverged";
  if (r.dissociated) return "dissociates";
  if (r.t_theta_m90 >= 0) return "rotates as one";
  return "undetermined";
}

namespace {
// Indices of the aggregated samples after γ̇t = 1 (before dissociation).
std::pair<std::size_t, std::size_t> aggregated_range(const DoubletShearResult& r) {
  std::size_t i0 = 0, i1 = 0;
  while (i0 < r.strain_h.size() && r.strain_h[i0] < 1.0) ++i0;
  i1 = i0;
  while (i1 < r.strain_h.size() && (!r.dissociated || r.strain_h[i1] < r.dissociation_strain)) ++i1;
  return {i0, i1};
}
}  // namespace

double max_sigmoid(const DoubletShearResult& r) {
  const auto [i0, i1] = aggregated_range(r);
  double m = 0;
  for (std::size_t i = i0; i < i1; ++i) m = std::max(m, r.sigmoid_h[i]);
  return m;
}

double final_sigmoid(const DoubletShearResult& r) {
  const auto [i0, i1] = aggregated_range(r);
  if (i1 <= i0) return 0;
  const std::size_t from = i1 - std::max<std::size_t>(1, (i1 - i0) / 10);
  double s = 0;
  for (std::size_t i = from; i < i1; ++i) s += r.sigmoid_h[i];
  return s / static_cast<double>(i1 - from);
}

std::string contact_mode(const DoubletShearResult& r, double threshold_um) {
  const auto [i0, i1] = aggregated_range(r);
  if (i1 <= i0) return "none";
  double cmax = 0;
  for (std::size_t i = i0; i < i1; ++i) cmax = std::max(cmax, std::min(r.contact0_h[i], r.contact1_h[i]));
  if (cmax <= 0) return "none";
  const double smax = max_sigmoid(r);
  if (smax < threshold_um) return "flat";
  return final_sigmoid(r) >= 0.5 * smax ? "sigmoid" : "relaxed sigmoid";
}

double mean_contact(const DoubletShearResult& r, double from, double to) {
  double s = 0;
  int n = 0;
  for (std::size_t i = 0; i < r.strain_h.size(); ++i) {
    if (r.strain_h[i] < from || r.strain_h[i] > to) continue;
    if (r.dissociated && r.strain_h[i] >= r.dissociation_strain) break;
    s += std::min(r.contact0_h[i], r.contact1_h[i]);
    ++n;
  }
  return n ? s / n : 0.0;
}

double max_deformation_change(const DoubletShearResult& r, int cell) {
  const std::vector<double>& D = cell == 0 ? r.D0_h : r.D1_h;
  double m = 0;
  for (double d : D) m = std::max(m, std::abs(d - D.front()));
  return m;
}

double jeffery_period(double axis_ratio) { return 2.0 * std::numbers::pi * (axis_ratio + 1.0 / axis_ratio); }

double quadrant_period(const DoubletShearResult& r) {
  if (r.t_theta0 < 0 || r.t_theta_m90 < 0) return -1;
  return 4.0 * (r.t_theta_m90 - r.t_theta0);
}

}  // namespace erythro::vv
