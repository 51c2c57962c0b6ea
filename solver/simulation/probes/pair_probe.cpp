#include "simulation/probes/pair_probe.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "geometry/pair_geometry.hpp"
#include "simulation/cell_physics.hpp"

namespace erythro::sim {
namespace {
// An angle difference (degrees) wrapped into (−period/2, period/2].
double wrap(double d, double period) { return d - period * std::round(d / period); }
}  // namespace

PairProbe::PairProbe(const CellPhysics& cells) : cells_(cells) {
  if (cells.cells().cell_count() != 2 || !cells.aggregates())
    throw std::logic_error("PairProbe: needs exactly two cells and aggregation");
}

void PairProbe::declare(std::vector<SeriesInfo>& series) const {
  series.push_back({"pair_angle_deg", "deg", "line of centres (cell 0 to cell 1) from +x, continued"});
  series.push_back({"pair_separation_um", "um", "distance of the two cells' area centroids"});
  series.push_back({"pair_gap_um", "um", "smallest marker-to-marker distance between the two membranes"});
  series.push_back({"cell_0_contact_area", "", "fraction of cell 0's markers with an aggregation force > 1.2 % of the largest"});
  series.push_back({"cell_1_contact_area", "", "fraction of cell 1's markers with an aggregation force > 1.2 % of the largest"});
  series.push_back({"pair_contact_sigmoid_um", "um", "|c3| (S shape) of the Legendre fit of cell 0's contact line"});
  series.push_back({"pair_contact_bow_um", "um", "|c2| (bow) of the Legendre fit of cell 0's contact line"});
  series.push_back({"pair_aspect_ratio", "", "a/b of the equivalent ellipse of the two cells together"});
  series.push_back({"pair_dissociated", "", "1 when no marker pair is within the Morse cut-off, else 0"});
}

void PairProbe::sample(const ProbeContext& context, std::span<double> values) {
  const membrane::ImmersedCells& cells = cells_.cells();
  const aggregation::CellContacts& agg = *cells_.contacts();
  const geometry::Domain& domain = agg.domain();
  const double um = context.setup.scales.length_m * 1e6;
  std::array<geometry::Polygon, 2> p{cells.polygon(0), cells.polygon(1)};
  double cx[2], cy[2];
  for (int k = 0; k < 2; ++k) geometry::centroid(p[k], cx[k], cy[k]);
  // Cell 1 at its nearest periodic image to cell 0 (a rigid shift of its markers).
  if (domain.periodic_x) {
    const double shift = domain.grid.nx * std::round((cx[1] - cx[0]) / domain.grid.nx);
    for (double& x : p[1].x) x -= shift;
    cx[1] -= shift;
  }
  if (domain.periodic_y) {
    const double shift = domain.grid.ny * std::round((cy[1] - cy[0]) / domain.grid.ny);
    for (double& y : p[1].y) y -= shift;
    cy[1] -= shift;
  }
  const double dx = cx[1] - cx[0], dy = cy[1] - cy[0];
  const double angle = std::atan2(dy, dx) * 180.0 / std::numbers::pi;
  const double separation = std::hypot(dx, dy);
  const double gap = geometry::min_marker_gap(p[0], p[1]);
  // Contact from the aggregation forces of the last step (none before the first).
  double contact[2] = {0.0, 0.0}, sigmoid = 0.0, bow = 0.0;
  const std::span<const double> magnitude = agg.force_magnitude();
  if (context.step > 0 && !magnitude.empty()) {
    const std::vector<std::size_t> offsets = aggregation::cell_offsets(cells);
    for (int k = 0; k < 2; ++k) contact[k] = aggregation::relative_contact_area(magnitude, offsets, k, kContactFraction);
    const double fmax = *std::max_element(magnitude.begin(), magnitude.end());
    std::vector<char> in_contact(p[0].size(), 0);
    for (std::size_t m = 0; m < p[0].size(); ++m)
      in_contact[m] = fmax > 0 && magnitude[offsets[0] + m] > kContactFraction * fmax;
    const geometry::ContactShape cs =
        geometry::contact_shape(p[0], in_contact, cx[0], cy[0], dx / separation, dy / separation);
    sigmoid = cs.sigmoid * um;
    bow = cs.bow * um;
  }
  if (first_) angle_ = angle;
  else angle_ += wrap(angle - angle_raw_, 360.0);
  angle_raw_ = angle;
  first_ = false;
  values[0] = angle_;
  values[1] = separation * um;
  values[2] = gap * um;
  values[3] = contact[0];
  values[4] = contact[1];
  values[5] = sigmoid;
  values[6] = bow;
  values[7] = geometry::equivalent_ellipse(p).axis_ratio;
  values[8] = gap > agg.cutoff() ? 1.0 : 0.0;
}

}  // namespace erythro::sim
