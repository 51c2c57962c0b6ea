#include "simulation/cell_transport.hpp"

#include <algorithm>
#include <stdexcept>

#include "geometry/grid_polygon.hpp"
#include "transport/heme_weights.hpp"

namespace erythro::sim {

CellNodes cell_nodes(const geometry::Polygon& cell, const geometry::Domain& domain, const std::string& representation,
                     const std::string& heme_weights, std::span<const double> row_radius) {
  CellNodes out;
  if (representation == "ray_cast") {
    std::vector<std::size_t> nodes;
    geometry::ray_cast_inside_nodes(cell, domain, nodes);
    for (std::size_t k : nodes) out.mask.push_back({k, 1.0});
    out.heme = out.mask;
  } else {
    // area fractions (the lattice counterpart of a volume-fraction mask; Σ φ h² = the polygon's
    // area to round-off); a cell crossing a periodic side is clipped, not wrapped
    out.fractional = true;
    const int nx = domain.grid.nx, ny = domain.grid.ny;
    out.mask = transport::area_fractions(cell, nx, ny);
    out.heme = out.mask;
    if (heme_weights != "area_fraction") {
      auto moment = transport::first_moment_weights(cell, nx, ny, out.mask);
      if (heme_weights == "first_moment") out.heme = moment;
      out.sample = std::move(moment);
    }
  }
  if (out.sample.empty()) out.sample = out.heme;
  for (const auto& c : out.heme) out.heme_sum += c.phi;
  out.sample_norm = out.heme_volume = out.heme_sum;
  if (!row_radius.empty()) {  // a ring of volume r h³ per radian per node (docs/model.md §7b)
    const std::size_t nx = static_cast<std::size_t>(domain.grid.nx);
    out.sample_norm = out.heme_volume = 0.0;
    for (auto& c : out.sample) {
      c.phi *= row_radius[c.node / nx];
      out.sample_norm += c.phi;
    }
    for (const auto& c : out.heme) out.heme_volume += c.phi * row_radius[c.node / nx];
  }
  return out;
}

CellNodes single_node(const transport::AreaFraction& heme, std::span<const double> row_radius, int nx) {
  CellNodes out;
  out.fractional = true;
  out.mask = out.heme = out.sample = {heme};
  out.heme_sum = out.sample_norm = out.heme_volume = heme.phi;
  if (!row_radius.empty()) {
    out.sample[0].phi *= row_radius[heme.node / static_cast<std::size_t>(nx)];
    out.sample_norm = out.heme_volume = out.sample[0].phi;
  }
  return out;
}

HbCoupling hb_coupling_from(const std::string& name) {
  if (name == "explicit") return HbCoupling::explicit_lagged;
  if (name == "cell_implicit") return HbCoupling::cell_implicit;
  if (name == "cell_implicit_outflow") return HbCoupling::cell_implicit_outflow;
  throw std::invalid_argument("unknown hemoglobin coupling '" + name + "'");
}

void HbCell::set_offset_response(const transport::TransportLattice& o2, const CellNodes& nodes) {
  // The mean of Ĉ_n = C_n + c_n q_n (eq T7) is P̄ + κ r, r = the step's release in Torr: the
  // offset responds to the step's own release, so it enters the implicit solve.
  std::vector<double> w_release(o2.grid().size(), 0.0);
  for (const auto& c : nodes.heme) w_release[c.node] = c.phi;
  kappa_ = 0.0;
  for (const auto& c : nodes.sample) kappa_ += o2.source_offset_factor(c.node) * c.phi * w_release[c.node];
  kappa_ /= nodes.sample_norm;
}

double HbCell::advance(const transport::HbParameters& hb, HbCoupling coupling, std::span<const double> C,
                       const CellNodes& nodes, double dt) {
  // Heme-weighted mean P = Σ w_n C_n / (α Σ w) (w = 1: transport::mean_partial_pressure)
  double s = 0.0;
  for (const auto& c : nodes.sample) s += c.phi * C[c.node];
  const double P = s / (nodes.sample_norm * hb.alpha);
  // outflow of the last step o^{k−1} = P^{k−1} + r^{k−1} − P^k (what the lattice took out of
  // the cell's mean P besides the release): second order on the slow manifold
  const double outflow = first_ ? 0.0 : P_prev_ + r_prev_ - P;
  double S_new = S_;
  switch (coupling) {
    case HbCoupling::explicit_lagged: S_new = transport::advance_saturation(hb, S_, P, dt).saturation; break;
    case HbCoupling::cell_implicit: S_new = transport::advance_saturation_cell_implicit(hb, S_, P, dt).saturation; break;
    case HbCoupling::cell_implicit_outflow: {
      transport::HbParameters hb_end = hb;
      hb_end.C_heme *= 1.0 + kappa_;  // in the solve only: the release itself is C_heme ΔS
      S_new = transport::advance_saturation_cell_implicit(hb_end, S_, std::max(0.0, P - outflow), dt).saturation;
      break;
    }
  }
  const double released = hb.C_heme * (S_ - S_new);  // −C_heme ΔS, µM
  P_prev_ = P;
  r_prev_ = released / hb.alpha;
  first_ = false;
  S_ = S_new;
  return released;
}

void HbCell::save_state(StateRecord& r, const std::string& prefix) const {
  r.put(prefix + "hb", std::vector<double>{S_, S0_, kappa_, P_prev_, r_prev_, first_ ? 1.0 : 0.0});
}

void HbCell::restore_state(const StateRecord& r, const std::string& prefix) {
  const std::vector<double>& v = r.get(prefix + "hb", 6);
  S_ = v[0];
  S0_ = v[1];
  kappa_ = v[2];
  P_prev_ = v[3];
  r_prev_ = v[4];
  first_ = v[5] != 0.0;
}

}  // namespace erythro::sim
