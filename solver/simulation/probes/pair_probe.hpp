#pragma once
// The doublet diagnostics (thesis ch. III; docs/model.md §4, §6): built by the simulation
// for a scene with exactly two moving cells and [aggregation]. At every sample, with cell
// 1 taken at its nearest periodic image to cell 0 (area centroids):
//   pair_angle_deg           line of centres (cell 0 → cell 1) from +x, continued across
//                            ±180° from its first value (tumbling of the pair, thesis §III.2)
//   pair_separation_um       distance of the two area centroids
//   pair_gap_um              smallest marker-to-marker distance between the membranes
//   cell_0_contact_area, cell_1_contact_area
//                            relative contact area: the fraction of the cell's markers whose
//                            aggregation force of the last step exceeds 1.2 % of the largest
//                            (thesis §III.2, after Bagchi et al.; aggregation::relative_contact_area);
//                            0 at step 0 (no force computed yet)
//   pair_contact_sigmoid_um  |c3| (S shape) and
//   pair_contact_bow_um      |c2| (bow) of the Legendre fit of cell 0's contact line in the
//                            frame of the line of centres (geometry::contact_shape); 0 at step 0
//   pair_aspect_ratio        a/b of the ellipse with the second area moments of both cells
//                            together (geometry::equivalent_ellipse)
//   pair_dissociated         1 when no marker pair is within the Morse cut-off r_c (no
//                            aggregation force left), else 0
// The angle is continued between samples: a sample interval must be short enough that the
// line of centres turns by less than 180° between two samples.
#include "simulation/probe.hpp"

namespace erythro::sim {

class PairProbe : public Probe {
 public:
  // `cells` (two cells, with aggregation) must outlive the probe.
  explicit PairProbe(const CellPhysics& cells);
  void declare(std::vector<SeriesInfo>& series) const override;
  void sample(const ProbeContext& context, std::span<double> values) override;
  void save_state(StateRecord& record, const std::string& prefix) const override {
    record.put(prefix + "angle", std::vector<double>{first_ ? 1.0 : 0.0, angle_, angle_raw_});
  }
  void restore_state(const StateRecord& record, const std::string& prefix) override {
    const std::vector<double>& v = record.get(prefix + "angle", 3);
    first_ = v[0] != 0.0;
    angle_ = v[1];
    angle_raw_ = v[2];
  }

  // The fraction of the largest aggregation force above which a marker is in contact.
  static constexpr double kContactFraction = 0.012;

 private:
  const CellPhysics& cells_;
  bool first_ = true;
  double angle_ = 0.0, angle_raw_ = 0.0;  // continued and last raw angle (deg)
};

}  // namespace erythro::sim
