#include "simulation/probes/shear_probe.hpp"

namespace erythro::sim {

bool ShearProbe::applies(const scene::LatticeSetup& s) {
  // the plasma's μ at both walls: no [[fluid.layers]] band
  return s.has_fluid && s.grid.ny >= 4 && s.viscosity_layers.empty() && scene::wall_shear_rate_per_s(s).has_value();
}

void ShearProbe::declare(std::vector<SeriesInfo>& series) const {
  series.push_back({"wall_shear_stress_bottom_Pa", "Pa", "mu d(mean u_x)/dy at the bottom wall (eq 12.5)"});
  series.push_back({"wall_shear_stress_top_Pa", "Pa", "mu d(mean u_x)/dy at the top wall (eq 12.5)"});
  series.push_back({"shear_relative_viscosity", "",
                    "mean of the two wall stresses / (mu gamma_dot), gamma_dot = (U_top - U_bottom) / H"});
}

namespace {

double row_mean(const fluid::Moments& m, int nx, int y) {
  double s = 0.0;
  for (int x = 0; x < nx; ++x) s += m.ux[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(x)];
  return s / nx;
}

// Eq 12.5: ∂u/∂y at a wall from u(h/2) − U_w = a/2 + b/4 and u(3h/2) − U_w = 3a/2 + 9b/4
// (u − U_w = a y + b y², h = 1): a = (9 (u1 − U_w) − (u2 − U_w)) / 3.
double wall_gradient(double wall, double first, double second) { return (9.0 * (first - wall) - (second - wall)) / 3.0; }

}  // namespace

void ShearProbe::sample(const ProbeContext& c, std::span<double> values) {
  const fluid::Moments& m = *c.moments;
  const int nx = c.setup.grid.nx, ny = c.setup.grid.ny;
  const fluid::BoundaryConfig& b = c.setup.boundaries;
  // lattice units (ρ0 = 1): σ = ν ∂u/∂y; the top wall's gradient with y measured downwards
  const double bottom = c.setup.viscosity * wall_gradient(b.bottom.ux, row_mean(m, nx, 0), row_mean(m, nx, 1));
  const double top = -c.setup.viscosity * wall_gradient(b.top.ux, row_mean(m, nx, ny - 1), row_mean(m, nx, ny - 2));
  const double nominal = c.setup.viscosity * (b.top.ux - b.bottom.ux) / ny;
  const double pa = c.setup.scales.pressure_Pa();
  values[0] = bottom * pa;
  values[1] = top * pa;
  values[2] = 0.5 * (bottom + top) / nominal;
}

}  // namespace erythro::sim
