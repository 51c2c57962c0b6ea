#include "simulation/probes/interior_probe.hpp"

#include "geometry/polygon.hpp"
#include "simulation/cell_physics.hpp"

namespace erythro::sim {

void InteriorProbe::declare(std::vector<SeriesInfo>& series) const {
  series.push_back({"interior_index_updates", "", "rebuilds of the index field and tau so far"});
  series.push_back({"interior_fill_fraction", "", "sum of (1 - I) over the grid / the cells' enclosed area"});
  series.push_back({"interior_max_fill_mismatch_um2", "um^2",
                    "max over rebuilds and cells of |sum(1 - I) - enclosed area|"});
  series.push_back({"interior_max_fallback_cells", "", "max over rebuilds of cells filled by ray casting"});
}

void InteriorProbe::sample(const ProbeContext& context, std::span<double> values) {
  const interior::IndexField& index = *cells_.index_field();
  const CellPhysics::FillHistory& history = cells_.fill_history();
  double interior = 0.0;  // Σ(1 − I), lattice units²
  for (double I : index.values()) interior += 1.0 - I;
  double enclosed = 0.0;
  const membrane::ImmersedCells& cells = cells_.cells();
  for (int c = 0; c < cells.cell_count(); ++c) enclosed += geometry::signed_area(cells.x(c), cells.y(c));
  const double h_um = context.setup.scales.length_m * 1e6;
  values[0] = static_cast<double>(history.updates);
  values[1] = enclosed > 0.0 ? interior / enclosed : 0.0;
  values[2] = history.max_area_mismatch * h_um * h_um;
  values[3] = static_cast<double>(history.max_fallback_cells);
}

}  // namespace erythro::sim
