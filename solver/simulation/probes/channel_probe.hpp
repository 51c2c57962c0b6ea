#pragma once
// Channel diagnostics (thesis ch. IV; docs/model.md §12) for a channel: walls at the bottom
// and top (y = 0 and H), periodic in x, driven by a steady body force F along x:
//   channel_mean_velocity_um_s   Ū, the mean of u_x over the nodes (the flow rate per depth / H)
//   relative_apparent_viscosity  U0/Ū, U0 = F H²/(12 μ) the mean velocity of the plasma alone
//                                at the same F (eq 12.1); NaN while the fluid is at rest
//   mean_transverse_plasma_speed_um_s  the mean of |u_y| over the plasma's nodes (index field
//                                I > ½ with an interior viscosity; every node without one)
// and, with cells (eqs 12.2, 12.3):
//   cell_free_layer_bottom_um    mean over the x columns a membrane crosses of the distance
//   cell_free_layer_top_um       from the wall to the nearest marker in that column
//   cell_free_layer_normalised   their mean over H/2
//   tube_haematocrit             Σ A_c / (L H): the cells' share of the channel's area
//   discharge_haematocrit        Σ A_c U_c / (L H Ū): their share of the flow (U_c: cell c's
//                                mean marker velocity along x; NaN while Ū = 0)
// Only the current state is read; time averages are the user's (the series are written
// at every diagnostics sample). Profiles across the same channel: channel_profile_probe.hpp.
#include "simulation/probe.hpp"

namespace erythro::sim {

class ChannelProbe : public Probe {
 public:
  // Whether `setup` is such a channel (walls at the bottom and top, at rest; periodic in x;
  // a steady body force along x and none along y).
  static bool applies(const scene::LatticeSetup& setup);
  // `cells` may be nullptr (no cells: the flow series only); it must outlive the probe.
  explicit ChannelProbe(const CellPhysics* cells) : cells_(cells) {}
  void declare(std::vector<SeriesInfo>& series) const override;
  void sample(const ProbeContext& context, std::span<double> values) override;

 private:
  const CellPhysics* cells_;
  std::vector<double> lowest_, highest_;  // per x column, scratch
};

}  // namespace erythro::sim
