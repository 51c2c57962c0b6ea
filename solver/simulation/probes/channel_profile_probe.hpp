#pragma once
// Profiles across a channel (docs/model.md §12, eq 12.6) for the channel of ChannelProbe
// (walls at y = 0 and H, periodic in x, a steady body force along x): per lattice row j,
// at y_j = (j + ½) h,
//   velocity_x_um_s   ū_j = (1/n_x) Σ_i u_x(i, j), the row's mean velocity along x
//   haematocrit       φ_j = (1/n_x) Σ_i χ(i, j), the share of the row's nodes inside a cell,
//                     χ = 1 when the node's centre lies inside a cell's outline (the polygon
//                     of its markers, even–odd ray casting with the periodic images in x:
//                     geometry::ray_cast_inside_nodes), whether or not the cells have an
//                     interior viscosity; 0 everywhere without cells
//   cell_flux_um_s    q_j = (1/n_x) Σ_i χ(i, j) u_x(i, j), the row's flow inside the cells;
//                     Σ_j q_j / Σ_j ū_j is the discharge haematocrit of the nodes (eq 12.7)
// Only the current state is read; the time average over a window is `erythro profiles`
// (analysis/profiles.hpp, eq 12.7).
#include <cstdint>
#include <vector>

#include "geometry/polygon.hpp"
#include "simulation/probe.hpp"

namespace erythro::sim {

class ChannelProfileProbe : public Probe {
 public:
  // `cells` may be nullptr (no cells: the haematocrit is 0); it must outlive the probe.
  explicit ChannelProfileProbe(const CellPhysics* cells) : cells_(cells) {}
  void declare(std::vector<SeriesInfo>& /*series*/) const override {}
  void sample(const ProbeContext& /*context*/, std::span<double> /*values*/) override {}
  void declare_profiles(std::vector<ProfileInfo>& profiles) const override;
  void sample_profiles(const ProbeContext& context, std::span<double> values) override;

 private:
  const CellPhysics* cells_;
  // scratch, reused from sample to sample
  geometry::Polygon outline_;
  std::vector<std::size_t> nodes_;
  std::vector<std::uint8_t> inside_;
};

}  // namespace erythro::sim
