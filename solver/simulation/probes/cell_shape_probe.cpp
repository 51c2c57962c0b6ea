#include "simulation/probes/cell_shape_probe.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "geometry/polygon.hpp"
#include "simulation/cell_physics.hpp"

namespace erythro::sim {
namespace {
// An angle difference (degrees) wrapped into (−period/2, period/2].
double wrap(double d, double period) { return d - period * std::round(d / period); }

// Largest |ℓ_e/ℓ0_e − 1| over the edges of cell c.
double max_edge_strain(const membrane::ImmersedCells& cells, int c) {
  const auto x = cells.x(c), y = cells.y(c);
  const auto& rest = cells.rest(c);
  double e_max = 0.0;
  for (std::size_t e = 0; e < x.size(); ++e) {
    const std::size_t f = (e + 1) % x.size();
    const double l = std::hypot(x[f] - x[e], y[f] - y[e]);
    e_max = std::max(e_max, std::abs(l / rest.length[e] - 1.0));
  }
  return e_max;
}

double area_change(const membrane::ImmersedCells& cells, int c) {
  return geometry::signed_area(cells.x(c), cells.y(c)) / cells.rest(c).area - 1.0;
}
}  // namespace

CellShapeProbe::CellShapeProbe(const CellPhysics& cells, long extremes_interval)
    : cells_(cells), extremes_interval_(extremes_interval) {}

void CellShapeProbe::declare(std::vector<SeriesInfo>& series) const {
  for (int c = 0; c < cells_.cells().cell_count(); ++c) {
    const std::string p = "cell_" + std::to_string(c) + "_";
    series.push_back({p + "area_change", "", "A/A0 - 1 of the membrane polygon"});
    series.push_back({p + "taylor_deformation", "", "(L - B)/(L + B) of the ellipse with the same area moments"});
    series.push_back({p + "orientation_deg", "deg", "long axis of that ellipse from +x, in (-90, 90]"});
    series.push_back({p + "inclination_deg", "deg", "the same, continued across +-90 deg from its first value"});
    series.push_back({p + "centroid_x_um", "um", "area centroid x (unwrapped)"});
    series.push_back({p + "centroid_y_um", "um", "area centroid y (unwrapped)"});
    series.push_back({p + "max_edge_strain", "", "max over edges of |l/l0 - 1|"});
    series.push_back({p + "marker_phase_deg", "deg", "mean angle the markers turned about the centroid since the start"});
    series.push_back({p + "marker0_angle_deg", "deg", "angle of marker 0 about the centroid, continued"});
    if (cells_.cells().area_projection())  // docs/model.md eq 3.14
      series.push_back({p + "area_restored", "", "area the projection gave back so far, over the cell's area"});
  }
  series.push_back({"cells_max_area_change", "", "max over cells and tracked steps of |A/A0 - 1|"});
  series.push_back({"cells_max_edge_strain", "", "max over cells, edges and tracked steps of |l/l0 - 1|"});
}

void CellShapeProbe::track_extremes() {
  const membrane::ImmersedCells& cells = cells_.cells();
  for (int c = 0; c < cells.cell_count(); ++c) {
    max_area_change_ = std::max(max_area_change_, std::abs(area_change(cells, c)));
    max_edge_strain_ = std::max(max_edge_strain_, max_edge_strain(cells, c));
  }
}

void CellShapeProbe::save_state(StateRecord& r, const std::string& prefix) const {
  r.put(prefix + "scalars", std::vector<double>{first_ ? 1.0 : 0.0, static_cast<double>(state_.size()),
                                                max_area_change_, max_edge_strain_});
  for (std::size_t c = 0; c < state_.size(); ++c) {
    const CellState& s = state_[c];
    const std::string cell = prefix + std::to_string(c) + ".";
    r.put(cell + "angles", std::vector<double>{s.theta, s.theta_raw, s.marker0_start});
    r.put(cell + "phase", s.phase);
    r.put(cell + "last", s.last);
  }
}

void CellShapeProbe::restore_state(const StateRecord& r, const std::string& prefix) {
  const std::vector<double>& v = r.get(prefix + "scalars", 4);
  first_ = v[0] != 0.0;
  state_.resize(static_cast<std::size_t>(v[1]));
  max_area_change_ = v[2];
  max_edge_strain_ = v[3];
  for (std::size_t c = 0; c < state_.size(); ++c) {
    CellState& s = state_[c];
    const std::string cell = prefix + std::to_string(c) + ".";
    const std::vector<double>& a = r.get(cell + "angles", 3);
    s.theta = a[0];
    s.theta_raw = a[1];
    s.marker0_start = a[2];
    s.phase = r.get(cell + "phase");
    s.last = r.get(cell + "last");
  }
}

void CellShapeProbe::register_stages(TimeLoop& loop) {
  if (extremes_interval_ <= 0) return;
  // Observe phase: the state after the step; every k steps from the first.
  loop.add(Phase::observe, "cell_extremes", [this](long) { track_extremes(); }, extremes_interval_,
           extremes_interval_ - 1);
}

void CellShapeProbe::sample(const ProbeContext& context, std::span<double> values) {
  constexpr double deg = 180.0 / std::numbers::pi;
  const membrane::ImmersedCells& cells = cells_.cells();
  const double um = context.setup.scales.length_m * 1e6;
  state_.resize(static_cast<std::size_t>(cells.cell_count()));
  std::size_t k = 0;
  for (int c = 0; c < cells.cell_count(); ++c) {
    CellState& s = state_[static_cast<std::size_t>(c)];
    const geometry::Polygon p = cells.polygon(c);
    const double dA = geometry::signed_area(p) / cells.rest(c).area - 1.0;
    double D = 0.0, theta = 0.0, cx = 0.0, cy = 0.0;
    geometry::taylor_deformation(p, D, theta);
    geometry::centroid(p, cx, cy);
    if (first_) s.theta = theta;
    else s.theta += wrap(theta - s.theta_raw, 180.0);  // the axis is defined modulo 180°
    s.theta_raw = theta;
    s.phase.resize(p.size(), 0.0);
    s.last.resize(p.size(), 0.0);
    for (std::size_t m = 0; m < p.size(); ++m) {
      const double angle = std::atan2(p.y[m] - cy, p.x[m] - cx) * deg;
      if (!first_) s.phase[m] += wrap(angle - s.last[m], 360.0);
      s.last[m] = angle;
    }
    if (first_) s.marker0_start = s.last[0];
    double mean_phase = 0.0;
    for (double ph : s.phase) mean_phase += ph / static_cast<double>(p.size());
    values[k++] = dA;
    values[k++] = D;
    values[k++] = theta;
    values[k++] = s.theta;
    values[k++] = cx * um;
    values[k++] = cy * um;
    values[k++] = max_edge_strain(cells, c);
    values[k++] = mean_phase;
    values[k++] = s.marker0_start + s.phase[0];
    if (cells.area_projection()) values[k++] = cells.restored_area_fraction(c);
  }
  first_ = false;
  track_extremes();  // the samples count too
  values[k++] = max_area_change_;
  values[k++] = max_edge_strain_;
}

}  // namespace erythro::sim
