#include "simulation/probes/transport_probe.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "simulation/transport_physics.hpp"

namespace erythro::sim {

TransportProbe::TransportProbe(const TransportPhysics& transport)
    : transport_(transport), worst_(transport.species_count(), 0.0), previous_(transport.species_count()) {
  const auto& T = transport.setup();
  const int ny = transport.species_count() ? transport.lattice(0).grid().ny : 0;
  for (std::size_t k = 0; k < T.layers.size(); ++k) {
    const long top = std::lround(T.layers[k].y_hi);  // nearest face (in h)
    if (T.layers[k].full_width && top >= 1 && top < ny)
      fluxes_.push_back({static_cast<std::size_t>(T.layers[k].species), static_cast<std::size_t>(top - 1),
                         static_cast<int>(k)});
  }
}

void TransportProbe::declare(std::vector<SeriesInfo>& series) const {
  // Amounts: per unit depth of a planar section (µM·µm²), per radian of a body of revolution
  // (Σ r C h², µM·µm³; docs/model.md eq 7.8).
  const bool axi = transport_.setup().axisymmetric_inner_radius.has_value();
  const std::string unit = axi ? "uM*um^3" : "uM*um^2", suffix = axi ? "_uM_um3" : "_uM_um2";
  const std::string per = axi ? "per radian" : "per unit depth";
  for (std::size_t i = 0; i < transport_.species_count(); ++i) {
    const std::string& n = transport_.name(i);
    series.push_back({n + "_mean_uM", "uM",
                      "mean concentration of " + n + (axi ? " over the volume (r-weighted)" : " over the nodes")});
    series.push_back({n + "_mass_balance_residual", "",
                      "relative mass-balance residual of the last transport step (docs/transport.md eq T5)"});
    series.push_back({n + "_max_mass_balance_residual", "", "largest |relative residual| of any transport step so far"});
    series.push_back({n + "_amount" + suffix, unit, "stored amount of " + n + " (eq T5's M, " + per + ")"});
    series.push_back(
        {n + "_amount_change" + suffix, unit, "stored amount of " + n + " minus that at the start (" + per + ")"});
    series.push_back({n + "_boundary_inflow" + suffix, unit,
                      "net amount of " + n + " that entered through the sides since the start (" + per + ")"});
    series.push_back({n + "_change_uM", "uM", "max |C - C at the previous sample| over the nodes (NaN at the first)"});
    series.push_back({n + "_steady_balance", "", "|inflow + net source| / |net source| of the last transport step"});
  }
  for (const LayerFlux& f : fluxes_)
    series.push_back({transport_.name(f.species) + "_layer_" + std::to_string(f.layer) + "_top_flux_uM_um_s",
                      "uM*um/s", "flux across the top edge of [[transport.layers]] entry " + std::to_string(f.layer) +
                                     " (+y, mean over x)"});
  for (std::size_t c = 0; c < transport_.saturation().size(); ++c) {
    series.push_back({"cell_" + std::to_string(c) + "_saturation", "",
                      "HbO2 saturation of the cell (local kinetics: the mean over its heme volume)"});
    series.push_back({"cell_" + std::to_string(c) + "_released" + suffix, unit,
                      "O2 released by the cell's haemoglobin since the start (" + per + ")"});
  }
}

void TransportProbe::track_residuals() {
  for (std::size_t i = 0; i < transport_.species_count(); ++i)
    worst_[i] = std::max(worst_[i], std::abs(transport_.lattice(i).mass_balance().relative_residual()));
}

void TransportProbe::save_state(StateRecord& r, const std::string& prefix) const {
  r.put(prefix + "worst", worst_);
  for (std::size_t i = 0; i < previous_.size(); ++i) r.put(prefix + "previous_" + std::to_string(i), previous_[i]);
}

void TransportProbe::restore_state(const StateRecord& r, const std::string& prefix) {
  r.copy_to(prefix + "worst", worst_);
  for (std::size_t i = 0; i < previous_.size(); ++i) previous_[i] = r.get(prefix + "previous_" + std::to_string(i));
}

void TransportProbe::register_stages(TimeLoop& loop) {
  loop.add(Phase::observe, "transport_residuals", [this](long) { track_residuals(); });
}

void TransportProbe::sample(const ProbeContext& context, std::span<double> values) {
  const auto& units = transport_.setup().units;
  // lattice amount (µM per node; axisymmetric: µM·r per node, r in h) → µM·µm² (µM·µm³ per radian)
  const bool axi = transport_.setup().axisymmetric_inner_radius.has_value();
  const double area = units.h_um * units.h_um * (axi ? units.h_um : 1.0);
  std::size_t k = 0;
  for (std::size_t i = 0; i < transport_.species_count(); ++i) {
    const auto& lat = transport_.lattice(i);
    const auto& mb = lat.mass_balance();
    values[k++] = lat.total_amount() / lat.total_weight();
    values[k++] = context.step == 0 ? 0.0 : mb.relative_residual();
    values[k++] = worst_[i];
    const double M = lat.stored_amount();
    values[k++] = M * area;
    values[k++] = (M - transport_.initial_amount(i)) * area;
    values[k++] = transport_.boundary_inflow(i) * area;
    const auto C = lat.concentration();
    double change = std::numeric_limits<double>::quiet_NaN();
    if (previous_[i].size() == C.size()) {
      change = 0.0;
      for (std::size_t n = 0; n < C.size(); ++n) change = std::max(change, std::fabs(C[n] - previous_[i][n]));
    }
    previous_[i].assign(C.begin(), C.end());
    values[k++] = change;
    values[k++] = context.step == 0 ? 0.0
                  : mb.source != 0.0 ? std::fabs(mb.boundary_in + mb.source) / std::fabs(mb.source)
                  : mb.boundary_in == 0.0 ? 0.0
                                          : 1.0;
  }
  if (!fluxes_.empty()) {
    const Grid& g = context.setup.grid;
    east_.resize(g.size());
    north_.resize(g.size());
    std::size_t computed = transport_.species_count();
    for (const LayerFlux& f : fluxes_) {
      if (computed != f.species) {
        transport_.lattice(f.species).face_flux(east_, north_);
        computed = f.species;
      }
      double sum = 0.0;
      for (int x = 0; x < g.nx; ++x) sum += north_[f.row * static_cast<std::size_t>(g.nx) + static_cast<std::size_t>(x)];
      // axisymmetric: the face flux is r-weighted (eq 7.8): per unit area of the face at r_row + ½
      const auto radius = transport_.lattice(f.species).row_radius();
      if (!radius.empty()) sum /= radius[f.row] + 0.5;
      values[k++] = sum / g.nx * units.h_um / units.dt_s;  // amount per step → µM·µm/s
    }
  }
  for (std::size_t c = 0; c < transport_.saturation().size(); ++c) {
    values[k++] = transport_.saturation()[c];
    values[k++] = transport_.released(c) * area;
  }
}

}  // namespace erythro::sim
