#pragma once
// Face-flux correction of a D2Q5 TRT (Λ = 1/4) transport lattice towards prescribed face
// fluxes (docs/transport.md §1 "Curved diffusivity jumps", eq T11).
//
// In its steady (and slowly varying) limit the TRT Λ = 1/4 lattice is exactly the 5-point finite-
// volume scheme with face conductance K_ab = 2/(1/D_a + 1/D_b) of its node D's (eq T7). A node D
// cannot give every face the conductance it should have (each node serves four faces). This
// correction adds, for each listed face (a → b, b the +x or +y neighbour of a), the difference
// between a target flux and the lattice's own,
//   ΔF_ab = (K*_ab − K_ab)(Ĉ_a − Ĉ_b) − X*_ab t_ab,     q_a −= ΔF_ab,   q_b += ΔF_ab,        (T11)
// t_ab = ¼ (Ĉ_{a+e} − Ĉ_{a−e} + Ĉ_{b+e} − Ĉ_{b−e}) the transverse difference across the face
// (e ⊥ the face normal), Ĉ the source-offset-corrected concentration (T7), as a source pair:
// mass is conserved exactly, and at steady state the lattice solves the finite-volume scheme
// with the target fluxes F*_ab = K*_ab (Ĉ_a − Ĉ_b) − X*_ab t_ab. The correction is evaluated
// from the last step's Ĉ (explicit, one step lagged: an O(Δt) term in transients).
//
// Axisymmetric lattice (docs/model.md §7b, eq 7.9'): the lattice's own steady face flux is r_f K
// (Ĉ_a − Ĉ_b) per radian, also across jumps of D (r_f: the row's r on an x-face, r_a + ½ on a
// y-face), so a face carries r_f times the planar difference, and the pair enters the source as
// ΔF/r_a and ΔF/r_b (the lattice multiplies its source by r): the r-weighted amount is conserved
// exactly. On the row next to the axis the transverse difference mirrors the row across it.
#include <cstddef>
#include <span>
#include <vector>

#include "lattice/grid.hpp"
#include "transport/transport_lattice.hpp"

namespace erythro::transport {

// Target flux of one face: a = node, b = its +x (x_face) or +y neighbour; K = conductance across
// the face, X = cross coefficient (the D_xy of a diffusivity tensor on the face).
struct FaceTarget {
  std::size_t a = 0;
  bool x_face = true;
  double K = 0.0, X = 0.0;
};

class FaceFluxCorrection {
 public:
  // node_D: the lattice's per-node (scalar) D, lattice units; faces whose target equals the
  // lattice's own flux are dropped. row_radius: the lattice's r per row when axisymmetric (empty:
  // planar). Throws std::invalid_argument if a face with X ≠ 0 lacks a transverse neighbour
  // (touches the grid's edge).
  FaceFluxCorrection(const Grid& grid, std::span<const double> node_D, const std::vector<FaceTarget>& targets,
                     std::span<const double> row_radius = {});

  // Per-node corrections from the lattice's current Ĉ (eq T11); no allocation.
  void evaluate(const TransportLattice& lattice);
  // source[n] += correction[n] for the nodes touched (call after writing the step's own source).
  void add_to(std::span<double> source) const;

  std::size_t faces() const { return faces_.size(); }

  // Gain of the one-step lag (stability, not accuracy): the correction is computed from Ĉ_m =
  // C_m + φ_m q_m (T7, φ = lattice.source_offset_factor), and q holds the last correction, so
  // q_corr(new) = A q_corr(old) + …; returns the row-sum norm max_n Σ_m |A_nm|. Measured on the
  // deoxygenation cell (docs/transport.md, "Stability of the face-flux correction").
  double lagged_gain(const TransportLattice& lattice) const;
  // Throws std::invalid_argument, naming the gain, the limit and what to change, when
  // lagged_gain > kLaggedGainLimit. The gain depends only on the diffusivity contrast and the cut
  // pattern, not on Δt (dK ∝ Δt, φ ∝ 1/Δt); on a curved D_in/D_out jump the limit is a contrast of
  // about 9.5 (950:2800 µm²/s gives 0.17).
  void require_stable(const TransportLattice& lattice) const;
  // Between the largest gain measured stable (0.785) and the smallest measured diverging (0.833)
  // on the deoxygenation cell, 17 runs with contrasts 3–17 (docs/transport.md).
  static constexpr double kLaggedGainLimit = 0.8;

 private:
  struct Face {
    std::size_t a, b, a_plus, a_minus, b_plus, b_minus;
    double dK, X;                         // × r_f when axisymmetric
    double share_a = 1.0, share_b = 1.0;  // 1/r_a, 1/r_b when axisymmetric
  };
  // The nodes whose Ĉ a face reads, each once (evaluate computes Ĉ there once per step), and per
  // face the positions of a, b, a±, b± in that list.
  struct FaceRefs {
    std::size_t a, b, a_plus, a_minus, b_plus, b_minus;
  };
  std::vector<Face> faces_;
  std::vector<FaceRefs> face_refs_;
  std::vector<std::size_t> read_nodes_;
  std::vector<double> read_C_;
  std::vector<std::size_t> nodes_;       // nodes touched by a face (each once)
  std::vector<double> node_correction_;  // per entry of nodes_
  std::vector<std::size_t> slot_;        // node → entry of nodes_ (grid-sized; N = none)
};

}  // namespace erythro::transport
