#include "simulation/probes/channel_probe.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/polygon.hpp"
#include "simulation/cell_physics.hpp"

namespace erythro::sim {

bool ChannelProbe::applies(const scene::LatticeSetup& s) {
  using fluid::SideType;
  const fluid::BoundaryConfig& b = s.boundaries;
  return s.has_fluid && b.left.type == SideType::periodic && b.bottom.type == SideType::wall &&
         b.top.type == SideType::wall && s.body_force[0] != 0.0 && s.body_force[1] == 0.0 && s.force_frequency == 0.0;
}

void ChannelProbe::declare(std::vector<SeriesInfo>& series) const {
  series.push_back({"channel_mean_velocity_um_s", "um/s", "mean of u_x over the nodes (flow rate per depth / H)"});
  series.push_back({"relative_apparent_viscosity", "",
                    "U0 / mean u_x, U0 = F H^2 / (12 mu) the plasma's mean velocity at the same force"});
  series.push_back({"mean_transverse_plasma_speed_um_s", "um/s",
                    "mean |u_y| over the plasma's nodes (index field > 1/2; every node without an index field)"});
  if (!cells_) return;
  series.push_back({"cell_free_layer_bottom_um", "um",
                    "mean over the x columns a membrane crosses of the distance from the bottom wall to the nearest "
                    "marker"});
  series.push_back({"cell_free_layer_top_um", "um", "the same from the top wall"});
  series.push_back({"cell_free_layer_normalised", "", "mean of the two over H/2"});
  series.push_back({"tube_haematocrit", "", "the cells' share of the channel's area"});
  series.push_back({"discharge_haematocrit", "", "the cells' share of the flow (area x mean marker velocity)"});
}

void ChannelProbe::sample(const ProbeContext& c, std::span<double> values) {
  const fluid::Moments& m = *c.moments;
  const int nx = c.setup.grid.nx, ny = c.setup.grid.ny;
  // One pass: the mean of u_x over every node, and of |u_y| over the plasma's nodes (outside
  // the cells by the index field, when there is one).
  const interior::IndexField* index = cells_ ? cells_->index_field() : nullptr;
  const std::span<const double> inside = index ? index->values() : std::span<const double>{};
  double sum_u = 0.0, sum_uy = 0.0;
  long plasma = 0;
  for (std::size_t n = 0; n < m.ux.size(); ++n) {
    sum_u += m.ux[n];
    if (!inside.empty() && !(inside[n] > 0.5)) continue;
    sum_uy += std::abs(m.uy[n]);
    ++plasma;
  }
  const double mean_u = sum_u / static_cast<double>(m.ux.size());
  // eq 12.1, lattice units (ρ0 = 1): U0 = F H² / (12 ν)
  const double u0 = c.setup.body_force[0] * ny * ny / (12.0 * c.setup.viscosity);
  const double um_s = c.setup.scales.velocity_m_s() * 1e6, um = c.setup.scales.length_m * 1e6;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  values[0] = mean_u * um_s;
  values[1] = mean_u != 0.0 ? u0 / mean_u : nan;  // undefined while the fluid is at rest
  values[2] = plasma ? sum_uy / static_cast<double>(plasma) * um_s : nan;
  if (!cells_) return;

  // eq 12.2: per lattice column, the lowest and highest marker (x wrapped into [0, nx)).
  const membrane::ImmersedCells& cells = cells_->cells();
  constexpr double inf = std::numeric_limits<double>::infinity();
  lowest_.assign(static_cast<std::size_t>(nx), inf);
  highest_.assign(static_cast<std::size_t>(nx), -inf);
  double area = 0.0, area_flux = 0.0;
  for (int k = 0; k < cells.cell_count(); ++k) {
    const std::span<const double> x = cells.x(k), y = cells.y(k), ux = cells.ux(k);
    double u_cell = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double wrapped = x[i] - nx * std::floor(x[i] / nx);
      const auto col = static_cast<std::size_t>(std::clamp(static_cast<int>(wrapped), 0, nx - 1));
      lowest_[col] = std::min(lowest_[col], y[i]);
      highest_[col] = std::max(highest_[col], y[i]);
      u_cell += ux[i];
    }
    const double a = std::abs(geometry::signed_area(x, y));
    area += a;
    area_flux += a * u_cell / static_cast<double>(x.size());  // eq 12.3
  }
  double bottom = 0.0, top = 0.0;
  int columns = 0;
  for (int i = 0; i < nx; ++i) {
    if (!(lowest_[static_cast<std::size_t>(i)] < inf)) continue;
    bottom += lowest_[static_cast<std::size_t>(i)];
    top += ny - highest_[static_cast<std::size_t>(i)];
    ++columns;
  }
  bottom = columns ? bottom / columns : nan;
  top = columns ? top / columns : nan;
  values[3] = bottom * um;
  values[4] = top * um;
  values[5] = 0.5 * (bottom + top) / (0.5 * ny);
  values[6] = area / (static_cast<double>(nx) * ny);                 // eq 12.3
  values[7] = mean_u != 0.0 ? area_flux / (static_cast<double>(nx) * ny * mean_u) : nan;  // eq 12.3
}

}  // namespace erythro::sim
