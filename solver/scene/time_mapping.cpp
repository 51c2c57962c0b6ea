// [time_mapping] → the run's density (docs/model.md §10, eq 10.8).
#include "scene/time_mapping.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "scene/units_detail.hpp"

namespace erythro::scene {

using detail::num;
using detail::reject;

namespace {

// γ̇ of the drive: walls moving apart (a simple shear), or the plasma's wall shear rate of a
// channel driven by a steady body force along x (plane Poiseuille: γ̇_w = F H/(2μ)).
std::optional<std::pair<double, std::string>> drive_shear_rate(const Scene& s) {
  const BoundarySpec& b = s.boundaries;
  const bool periodic_x = b.left.type == "periodic" && b.right.type == "periodic";
  const bool walls_y = b.bottom.type != "periodic" && b.top.type != "periodic";
  if (!periodic_x || !walls_y) return std::nullopt;
  const double H = s.domain.size_um[1] * 1e-6;
  const double relative_um_s = std::abs(b.top.velocity_um_s[0] - b.bottom.velocity_um_s[0]);
  const bool forced = s.body_force && (s.body_force->density_N_m3[0] != 0.0 || s.body_force->density_N_m3[1] != 0.0);
  if (relative_um_s > 0.0 && !forced)
    return std::pair{relative_um_s * 1e-6 / H, std::string("|U_top − U_bottom| / H of boundaries.*.velocity_um_s")};
  if (forced && relative_um_s == 0.0 && s.body_force->density_N_m3[1] == 0.0 && s.body_force->frequency_Hz == 0.0) {
    const double mu = s.fluid.viscosity_cP * 1e-3;
    return std::pair{std::abs(s.body_force->density_N_m3[0]) * H / (2.0 * mu),
                     std::string("the plasma's wall shear rate F H/(2μ) of body_force.density_N_m3")};
  }
  return std::nullopt;
}

// The largest cell's radius: radius_um (circle, biconcave) or √(ab) (ellipse), times scale.
std::optional<double> largest_cell_radius_um(const Scene& s) {
  std::optional<double> a;
  for (const CellSpec& c : s.cells) {
    const double r = (c.shape == "ellipse" ? std::sqrt(c.semi_axes_um[0] * c.semi_axes_um[1]) : c.radius_um) * c.scale;
    a = std::max(a.value_or(0.0), r);
  }
  return a;
}

}  // namespace

std::optional<TimeMapping> derive_time_mapping(const Scene& s) {
  if (!s.time_mapping) return std::nullopt;
  const TimeMappingSpec& spec = *s.time_mapping;
  if (s.transport && s.transport->coupling == "none")
    reject(s, "[time_mapping] maps the fluid's time, and this scene builds no fluid (transport.coupling = \"none\"): "
              "remove [time_mapping]");
  TimeMapping m;
  m.reynolds = spec.reynolds;
  if (spec.shear_rate_per_s) {
    m.shear_rate_per_s = *spec.shear_rate_per_s;
    m.shear_rate_source = "time_mapping.shear_rate_per_s";
  } else if (const auto drive = drive_shear_rate(s)) {
    std::tie(m.shear_rate_per_s, m.shear_rate_source) = *drive;
  } else {
    reject(s, "[time_mapping] needs the shear rate γ̇ of its Reynolds number γ̇a²ρ/μ: give time_mapping.shear_rate_per_s "
              "(1/s, > 0); it is taken from the drive only in a simple shear (periodic in x, walls at the bottom and "
              "top moving apart, no body force) or a channel (walls at rest, a steady body force along x)");
  }
  if (spec.radius_um) {
    m.radius_m = *spec.radius_um * 1e-6;
    m.radius_source = "time_mapping.radius_um";
  } else if (const auto a = largest_cell_radius_um(s)) {
    m.radius_m = *a * 1e-6;
    m.radius_source = "the largest cell's radius";
  } else {
    reject(s, "[time_mapping] needs the cell radius a of its Reynolds number γ̇a²ρ/μ, and the scene has no cells: give "
              "time_mapping.radius_um (µm, > 0)");
  }
  // Eq 10.8: ρ_run = Re μ / (γ̇ a²); the physical Re with fluid.density_kg_m3.
  const double mu = s.fluid.viscosity_cP * 1e-3, a2 = m.radius_m * m.radius_m;
  m.physical_density_kg_m3 = s.fluid.density_kg_m3;
  m.physical_reynolds = m.shear_rate_per_s * a2 * s.fluid.density_kg_m3 / mu;
  m.run_density_kg_m3 = m.reynolds * mu / (m.shear_rate_per_s * a2);
  if (!(m.run_density_kg_m3 > m.physical_density_kg_m3))
    reject(s, "key 'time_mapping.reynolds' = " + num(m.reynolds) + " is out of range: must be > " +
                  num(m.physical_reynolds) + ", the physical particle Reynolds number γ̇a²ρ/μ (γ̇ = " +
                  num(m.shear_rate_per_s) + " 1/s from " + m.shear_rate_source + ", a = " + num(m.radius_m * 1e6) +
                  " µm from " + m.radius_source + ", ρ = fluid.density_kg_m3 = " + num(s.fluid.density_kg_m3) +
                  " kg/m³): the mapping raises the density, never lowers it; remove [time_mapping] to run at the "
                  "physical Reynolds number");
  return m;
}

}  // namespace erythro::scene
