#include "doublet_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "aggregation/morse_units.hpp"
#include "common/scene_case.hpp"
#include "geometry/shapes.hpp"
#include "membrane/membrane_units.hpp"

namespace erythro::vv {

const char* theta_series(const DoubletShearConfig& c) {
  return c.cells == 2 ? "pair_angle_deg" : "cell_0_inclination_deg";
}

namespace {
double scene_Es0_N_m(const DoubletShearConfig& c) {
  const double Es0_dyn_cm = c.Es0_N_m * 1e3;  // membrane.shear_modulus_dyn_cm below (1 dyn/cm = 1e-3 N/m)
  return Es0_dyn_cm * membrane::kDynPerCm;
}
}  // namespace

double surface_energy_J_m2(const DoubletShearConfig& c) {
  if (c.de_star >= 0) return aggregation::surface_energy_for_de_star(c.de_star);  // docs/model.md eq 4.7
  return c.old_reading_de_star * scene_Es0_N_m(c);
}

double old_reading_level(const DoubletShearConfig& c) {
  return c.de_star >= 0 ? surface_energy_J_m2(c) / scene_Es0_N_m(c) : c.old_reading_de_star;
}

DoubletScene doublet_scene(const DoubletShearConfig& c) {
  if (c.cells == 2 && c.shape != CellShape::biconcave)
    throw std::invalid_argument("doublet run: the doublet scene has biconcave cells");
  if (c.cells == 1 && c.shape != CellShape::ellipse)
    throw std::invalid_argument("doublet run: the single-cell scene has an elliptical cell");
  if (c.cells != 1 && c.cells != 2) throw std::invalid_argument("doublet run: cells must be 1 or 2");
  DoubletScene d;
  d.path = c.cells == 2 ? "validation/doublet/doublet.toml" : "validation/doublet/single_cell.toml";
  // Physical set-up (docs/model.md §10, eq 10.7): the thesis's values, and the density that
  // gives the particle Reynolds number ργ̇a²/μ = c.reynolds at this shear rate.
  const double h_um = c.h_m * 1e6, a_um = c.a_m * 1e6, box_um = c.box_m * 1e6;
  const long n = std::lround(c.box_m / c.h_m);
  const double U = 0.5 * c.shear_rate * static_cast<double>(n) * h_um;  // µm/s, γ̇ = 2U/H
  const double mu_cP = c.mu_Pa_s * 1e3;
  std::vector<std::string>& o = d.overrides;
  o = {set("domain.spacing_um", h_um),
       set("domain.size_um", box_um, box_um),
       set("time.tau", c.tau),
       set("fluid.viscosity_cP", mu_cP),
       set("fluid.density_kg_m3", c.reynolds * c.mu_Pa_s / (c.shear_rate * c.a_m * c.a_m)),
       set("boundaries.bottom.velocity_um_s", -U, 0.0),
       set("boundaries.top.velocity_um_s", U, 0.0),
       set("monitor.max_mach", c.max_mach),
       set("membrane.kernel", "\"" + std::string(ib::to_string(c.kernel)) + "\""),
       set("membrane.shear_modulus_dyn_cm", c.Es0_N_m * 1e3),  // 1 dyn/cm = 1e-3 N/m
       set("membrane.bending_modulus_dyn_cm", c.Eb_J * 1e7),   // 1 dyn·cm = 1e-7 J
       set("membrane.area_modulus_Pa", c.area_modulus * c.Es0_N_m / c.a_m),
       set("membrane.interior_viscosity_cP", c.viscosity_ratio * mu_cP),
       set("membrane.interior_method", "\"" + std::string(interior::to_string(c.indicator)) + "\""),
       set("membrane.index_update_interval", static_cast<long>(c.index_update_interval))};
  for (int k = 0; k < c.cells; ++k) o.push_back(set("cells[" + std::to_string(k) + "].markers", static_cast<long>(c.markers)));
  if (c.cells == 2) {
    o.push_back(set("cells[0].radius_um", a_um));
    o.push_back(set("cells[1].radius_um", a_um));
    o.push_back(set("cells[1].shear_modulus_dyn_cm", c.Es1_N_m * 1e3));
    o.push_back(set("aggregation.surface_energy_J_m2", surface_energy_J_m2(c)));
    o.push_back(set("aggregation.zero_force_distance_um", c.r0_m * 1e6));
    o.push_back(set("aggregation.decay_per_um", c.beta_per_m * 1e-6));
    o.push_back(set("aggregation.cutoff_um", (c.r0_m + c.cutoff_k / c.beta_per_m) * 1e6));
  } else {
    o.push_back(set("cells[0].semi_axes_um", a_um, a_um / c.ellipse_axis_ratio));
  }
  // The lattice this gives: shear rate per step and the flat-contact gap d* (h).
  const scene::LatticeSetup setup = scene::derive_lattice(case_scene(d.path, o));
  d.gamma = setup.scales.time_s * c.shear_rate;

  // Placement (lattice units, then µm): centre off the lattice symmetry by 0.123 h in x.
  // Doublet: long axes normal to the line of centres at θ0 (face to face), the rims the
  // flat-contact gap d* (or initial_gap) apart; single cell: long axis at θ0.
  const double xc = 0.5 * static_cast<double>(n) + 0.123, yc = 0.5 * static_cast<double>(n);
  if (c.cells == 2) {
    const geometry::Polygon base = geometry::biconcave(c.markers, a_um / h_um);  // as the scene builds it
    double half = 0;
    for (double y : base.y) half = std::max(half, std::abs(y));
    const double gap = c.initial_gap_m < 0 ? setup.membrane->aggregation_flat_gap : c.initial_gap_m / c.h_m;
    const double dist = half + 0.5 * gap;
    const double th0 = c.theta0_deg * std::numbers::pi / 180.0;
    const double ex = std::cos(th0), ey = std::sin(th0);
    o.push_back(set("cells[0].center_um", (xc - dist * ex) * h_um, (yc - dist * ey) * h_um));
    o.push_back(set("cells[1].center_um", (xc + dist * ex) * h_um, (yc + dist * ey) * h_um));
    o.push_back(set("cells[0].angle_deg", c.theta0_deg - 90.0));
    o.push_back(set("cells[1].angle_deg", c.theta0_deg - 90.0));
  } else {
    o.push_back(set("cells[0].center_um", xc * h_um, yc * h_um));
    o.push_back(set("cells[0].angle_deg", c.theta0_deg));
  }
  // Run control in steps: the strain cap, a sample (and health check) every sample_strain,
  // the stop rules of the TOML (θ below a level; a strain span after dissociation).
  d.sample_every = std::max(1L, std::lround(c.sample_strain / d.gamma));
  o.push_back(set("run.steps", std::lround(c.strain / d.gamma)));
  o.push_back(set("output.diagnostics_interval_steps", d.sample_every));
  o.push_back(set("monitor.interval_steps", d.sample_every));
  o.push_back(set("stop_when[0].below", c.stop_theta_deg));
  if (c.cells == 2)
    o.push_back(set("stop_when[1].after_steps", static_cast<long>(std::ceil(c.stop_after_dissociation / d.gamma))));
  d.scene = case_scene(d.path, o);
  return d;
}

}  // namespace erythro::vv
