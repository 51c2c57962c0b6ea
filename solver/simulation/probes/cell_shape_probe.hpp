#pragma once
// Shape of every moving cell at every sample (docs/model.md §3; lattice geometry in
// physical units). Per cell c:
//   cell_c_area_change        A/A0 − 1 (A0: the rest shape's area)
//   cell_c_taylor_deformation D = (L − B)/(L + B) of the ellipse with the same second
//                             area moments (geometry::taylor_deformation)
//   cell_c_orientation_deg    that ellipse's long axis from +x, in (−90°, 90°]
//   cell_c_inclination_deg    the same, continued across ±90° from its first value (the
//                             axis is defined modulo 180°: for tumbling; its first value is
//                             arbitrary for a circle)
//   cell_c_centroid_x_um, cell_c_centroid_y_um
//                             area centroid (unwrapped across periodic sides as the markers)
//   cell_c_max_edge_strain    max over edges of |ℓ/ℓ0 − 1| (ℓ0: rest edge length)
//   cell_c_marker_phase_deg   mean over markers of the angle each has turned about the
//                             centroid since the first sample (tank-treading; counter-clockwise > 0)
//   cell_c_marker0_angle_deg  marker 0's angle about the centroid, continued (its first value
//                             is its initial angle)
// and, over all cells and every `extremes_interval` steps (not only the samples):
//   cells_max_area_change     max |A/A0 − 1| so far
//   cells_max_edge_strain     max |ℓ/ℓ0 − 1| so far
// Angles are continued between samples, so a sample interval must be short enough that
// no marker turns by 180° (and no axis by 90°) between two samples.
#include <vector>

#include "simulation/probe.hpp"

namespace erythro::sim {

class CellShapeProbe : public Probe {
 public:
  // `cells` must outlive the probe; extremes_interval 0: at the samples only.
  CellShapeProbe(const CellPhysics& cells, long extremes_interval);
  void declare(std::vector<SeriesInfo>& series) const override;
  void sample(const ProbeContext& context, std::span<double> values) override;
  void register_stages(TimeLoop& loop) override;
  void save_state(StateRecord& record, const std::string& prefix) const override;
  void restore_state(const StateRecord& record, const std::string& prefix) override;

 private:
  void track_extremes();

  const CellPhysics& cells_;
  long extremes_interval_;
  bool first_ = true;
  struct CellState {
    double theta = 0.0, theta_raw = 0.0;  // continued and last raw inclination (deg)
    std::vector<double> phase, last;      // per marker: angle turned, last raw angle (deg)
    double marker0_start = 0.0;
  };
  std::vector<CellState> state_;
  double max_area_change_ = 0.0, max_edge_strain_ = 0.0;
};

}  // namespace erythro::sim
