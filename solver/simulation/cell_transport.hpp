#pragma once
// How a cell enters the transport lattice (docs/transport.md §1 "Curved diffusivity jumps",
// §4.2; scene keys transport.cell_representation, hemoglobin.heme_weights, hemoglobin.coupling,
// hemoglobin.mean_pressure): the nodes it occupies with their weights, and the coupling of its
// cell-averaged Hb–O2 saturation to the lattice over one step.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "common/state_record.hpp"
#include "geometry/domain.hpp"
#include "geometry/polygon.hpp"
#include "transport/hb_kinetics.hpp"
#include "transport/subpixel_diffusivity.hpp"
#include "transport/transport_lattice.hpp"

namespace erythro::sim {

// The nodes of one cell: `mask` (node, φ) sets the interior diffusivity and the initial
// concentration (φ = 1 for ray casting), `heme` weights the release (per unit volume: the
// lattice's source), `sample` the mean P. In an axisymmetric domain a node stands for the ring of
// volume r_n h³ per radian (docs/model.md §7b), so the sample weights carry r_n (mean P over
// the cell's volume) while the release stays per unit volume (the lattice weights its source
// by r, eq 7.7).
struct CellNodes {
  std::vector<transport::AreaFraction> mask, heme, sample;
  double heme_sum = 0.0;     // Σ heme weights, summed in list order
  double sample_norm = 0.0;  // divisor of the mean P: heme_sum (planar), Σ sample weights (axisymmetric)
  double heme_volume = 0.0;  // Σ heme weights × r_n (planar: heme_sum): the cell's heme volume in h² (h³ per radian)
  bool fractional = false;   // area fractions (else ray casting: every weight 1)
};

// representation "ray_cast": nodes whose centre is inside (geometry::ray_cast_inside_nodes),
// weight 1 in all three lists; "area_fraction": φ of each node's square (transport::area_fractions),
// heme and sample weights by `heme_weights` ("area_fraction", "first_moment", "first_moment_sampling";
// transport/heme_weights.hpp). row_radius: the lattice's r per row when axisymmetric (else empty).
CellNodes cell_nodes(const geometry::Polygon& cell, const geometry::Domain& domain, const std::string& representation,
                     const std::string& heme_weights, std::span<const double> row_radius = {});
// One node of a cell as a cell of its own (hemoglobin.kinetics = "local"): the node's heme weight
// φ, sample weight φ r (planar: φ), so its mean P is the node's own.
CellNodes single_node(const transport::AreaFraction& heme, std::span<const double> row_radius, int nx);

// Coupling of S and the lattice's mean P over one step (docs/transport.md §4.2):
enum class HbCoupling {
  explicit_lagged,        // H2 at P^k (stable for λ_eff Δt < 2 only)
  cell_implicit,          // H3: P_end = P^k + r^k (the step's release kept in the cell)
  cell_implicit_outflow,  // H3 with P_end = P^k − o^{k−1} + (1 + κ) r^k, o^{k−1} = P^{k−1} + r^{k−1} − P^k
};
HbCoupling hb_coupling_from(const std::string& name);

// One cell's saturation and the memory of the outflow predictor.
class HbCell {
 public:
  explicit HbCell(double S0 = 0.0) : S_(S0), S0_(S0) {}
  // κ of the source-corrected mean P (eq T7): Σ_sample c_n w_n w'_n / sample_norm (w' the release
  // weights, c_n = lattice.source_offset_factor(n)); 0 without the correction.
  void set_offset_response(const transport::TransportLattice& o2, const CellNodes& nodes);
  // Advances S over dt from the mean P of the lattice's current C; returns the release of the
  // step in concentration units per unit heme weight (µM: C_heme (S − S_new)).
  double advance(const transport::HbParameters& hb, HbCoupling coupling, std::span<const double> C,
                 const CellNodes& nodes, double dt);
  double saturation() const { return S_; }
  double initial_saturation() const { return S0_; }
  // Checkpoint (common/state_record.hpp), under `prefix`: S, S0, κ and the predictor's memory.
  void save_state(StateRecord& record, const std::string& prefix) const;
  void restore_state(const StateRecord& record, const std::string& prefix);

 private:
  double S_ = 0.0, S0_ = 0.0;
  double kappa_ = 0.0;
  double P_prev_ = 0.0, r_prev_ = 0.0;  // P^{k−1}, r^{k−1} (Torr)
  bool first_ = true;
};

}  // namespace erythro::sim
