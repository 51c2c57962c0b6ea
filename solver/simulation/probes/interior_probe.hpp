#pragma once
// The interior viscosity's index field (docs/model.md §5, eqs 26–27), when the scene
// gives the cells an interior viscosity:
//   interior_index_updates         rebuilds of I and τ so far (the first, at the start, included)
//   interior_fill_fraction         Σ(1 − I) h² over the grid / the cells' enclosed area: 1 when
//                                  exactly the enclosed area carries ν_in (eq 26's smoothed
//                                  band included)
//   interior_max_fill_mismatch_um2 max over rebuilds and cells of |Σ(1 − I) h² − A| (the leak
//                                  check of interior::IndexField)
//   interior_max_fallback_cells    max over rebuilds of the cells the flood fill could not
//                                  start in, filled by ray casting instead
#include "simulation/probe.hpp"

namespace erythro::sim {

class InteriorProbe : public Probe {
 public:
  explicit InteriorProbe(const CellPhysics& cells) : cells_(cells) {}
  void declare(std::vector<SeriesInfo>& series) const override;
  void sample(const ProbeContext& context, std::span<double> values) override;

 private:
  const CellPhysics& cells_;
};

}  // namespace erythro::sim
