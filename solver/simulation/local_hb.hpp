#pragma once
// Local Hb–O2 kinetics (hemoglobin.kinetics = "local"; docs/transport.md §4.2, eq H4): every heme
// node n of a still cell carries its own saturation S_n, advanced by the law and coupling of the
// cell-mean model (eqs H1–H3) from the node's own P_n, as an HbCell of that one node; the release
// C_heme (S_n − S_n,new) goes to node n alone (weight φ_n). The cell's saturation is the mean over
// its heme volume, Σ V_n S_n / Σ V_n with V_n = φ_n (planar) or φ_n r_n (axisymmetric): what the
// resolved reference solvers report.
#include <span>
#include <string>
#include <vector>

#include "common/state_record.hpp"
#include "simulation/cell_transport.hpp"
#include "transport/hb_kinetics.hpp"
#include "transport/transport_lattice.hpp"

namespace erythro::sim {

class LocalHb {
 public:
  // Every heme node of `cell` at saturation S0; row_radius as for cell_nodes (empty: planar).
  LocalHb(const CellNodes& cell, double S0, std::span<const double> row_radius, int nx);
  // The T7 offset response of each node's own mean P (HbCell::set_offset_response).
  void set_offset_response(const transport::TransportLattice& o2);
  // Advances every node's S over dt from C and adds its release to `source` (per unit volume).
  void advance(const transport::HbParameters& hb, HbCoupling coupling, std::span<const double> C, double dt,
               std::span<double> source);
  double saturation() const;                 // Σ V_n S_n / Σ V_n
  double released(double C_heme) const;      // C_heme Σ V_n (S0 − S_n): O2 released since the start
  void save_state(StateRecord& record, const std::string& prefix) const;
  void restore_state(const StateRecord& record, const std::string& prefix);

 private:
  std::vector<CellNodes> nodes_;  // one node each
  std::vector<HbCell> hb_;
  double volume_ = 0.0;           // Σ V_n
};

}  // namespace erythro::sim
