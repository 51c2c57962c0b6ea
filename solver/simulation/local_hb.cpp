#include "simulation/local_hb.hpp"

namespace erythro::sim {

LocalHb::LocalHb(const CellNodes& cell, double S0, std::span<const double> row_radius, int nx) {
  nodes_.reserve(cell.heme.size());
  for (const auto& w : cell.heme) {
    nodes_.push_back(single_node(w, row_radius, nx));
    volume_ += nodes_.back().heme_volume;
  }
  hb_.assign(nodes_.size(), HbCell(S0));
}

void LocalHb::set_offset_response(const transport::TransportLattice& o2) {
  for (std::size_t k = 0; k < nodes_.size(); ++k) hb_[k].set_offset_response(o2, nodes_[k]);
}

void LocalHb::advance(const transport::HbParameters& hb, HbCoupling coupling, std::span<const double> C, double dt,
                      std::span<double> source) {
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const transport::AreaFraction& w = nodes_[k].heme[0];
    source[w.node] += w.phi * hb_[k].advance(hb, coupling, C, nodes_[k], dt);  // eq H4
  }
}

double LocalHb::saturation() const {
  double s = 0.0;
  for (std::size_t k = 0; k < nodes_.size(); ++k) s += nodes_[k].heme_volume * hb_[k].saturation();
  return s / volume_;
}

double LocalHb::released(double C_heme) const {
  double s = 0.0;
  for (std::size_t k = 0; k < nodes_.size(); ++k)
    s += nodes_[k].heme_volume * (hb_[k].initial_saturation() - hb_[k].saturation());
  return C_heme * s;
}

void LocalHb::save_state(StateRecord& r, const std::string& prefix) const {
  for (std::size_t k = 0; k < hb_.size(); ++k) hb_[k].save_state(r, prefix + "node_" + std::to_string(k) + ".");
}

void LocalHb::restore_state(const StateRecord& r, const std::string& prefix) {
  for (std::size_t k = 0; k < hb_.size(); ++k) hb_[k].restore_state(r, prefix + "node_" + std::to_string(k) + ".");
}

}  // namespace erythro::sim
