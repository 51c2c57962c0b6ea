#include "simulation/probes/channel_profile_probe.hpp"

#include <algorithm>

#include "geometry/grid_polygon.hpp"
#include "simulation/cell_physics.hpp"

namespace erythro::sim {

void ChannelProfileProbe::declare_profiles(std::vector<ProfileInfo>& profiles) const {
  profiles.push_back({"velocity_x_um_s", "um/s", "mean of u_x over the lattice row (docs/model.md eq 12.6)"});
  profiles.push_back({"haematocrit", "",
                      "share of the row's nodes whose centre lies inside a cell's outline (docs/model.md eq 12.6)"});
  profiles.push_back({"cell_flux_um_s", "um/s",
                      "mean over the row of u_x at the nodes inside a cell, 0 elsewhere (docs/model.md eq 12.6)"});
}

void ChannelProfileProbe::sample_profiles(const ProbeContext& c, std::span<double> values) {
  const Grid& g = c.setup.grid;
  const auto nx = static_cast<std::size_t>(g.nx), ny = static_cast<std::size_t>(g.ny);
  const std::span<double> velocity = values.subspan(0, ny), haematocrit = values.subspan(ny, ny),
                          flux = values.subspan(2 * ny, ny);
  const fluid::Moments& m = *c.moments;
  const double um_s = c.setup.scales.velocity_m_s() * 1e6;
  // eq 12.6: ū_j, each row summed in x order (the same sum on any number of threads)
  for (std::size_t j = 0; j < ny; ++j) {
    double sum = 0.0;
    for (std::size_t i = 0; i < nx; ++i) sum += m.ux[j * nx + i];
    velocity[j] = sum / static_cast<double>(nx) * um_s;
  }
  std::fill(haematocrit.begin(), haematocrit.end(), 0.0);
  std::fill(flux.begin(), flux.end(), 0.0);
  if (!cells_) return;
  // eq 12.6: χ, the union of the cells' interiors (a node two outlines claim counts once)
  inside_.assign(g.size(), 0);
  const geometry::Domain domain{g, true, false};
  const membrane::ImmersedCells& cells = cells_->cells();
  for (int k = 0; k < cells.cell_count(); ++k) {
    outline_.x.assign(cells.x(k).begin(), cells.x(k).end());
    outline_.y.assign(cells.y(k).begin(), cells.y(k).end());
    geometry::ray_cast_inside_nodes(outline_, domain, nodes_);
    for (const std::size_t n : nodes_) inside_[n] = 1;
  }
  for (std::size_t j = 0; j < ny; ++j) {
    long count = 0;
    double sum = 0.0;
    for (std::size_t i = 0; i < nx; ++i) {
      if (!inside_[j * nx + i]) continue;
      ++count;
      sum += m.ux[j * nx + i];
    }
    haematocrit[j] = static_cast<double>(count) / static_cast<double>(nx);
    flux[j] = sum / static_cast<double>(nx) * um_s;
  }
}

}  // namespace erythro::sim
