#include "transport/face_flux_correction.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace erythro::transport {

FaceFluxCorrection::FaceFluxCorrection(const Grid& grid, std::span<const double> node_D,
                                       const std::vector<FaceTarget>& targets, std::span<const double> row_radius) {
  const std::size_t N = grid.size(), nx = static_cast<std::size_t>(grid.nx);
  if (node_D.size() != N) throw std::invalid_argument("FaceFluxCorrection: node_D does not match the grid");
  slot_.assign(N, N);
  auto slot_of = [&](std::size_t n) {
    if (slot_[n] == N) {
      slot_[n] = nodes_.size();
      nodes_.push_back(n);
    }
  };
  const bool axisymmetric = !row_radius.empty();
  for (const auto& t : targets) {
    const int x = static_cast<int>(t.a % nx), y = static_cast<int>(t.a / nx);
    if ((t.x_face && x + 1 >= grid.nx) || (!t.x_face && y + 1 >= grid.ny)) {
      throw std::invalid_argument("FaceFluxCorrection: face beyond the grid");
    }
    const std::size_t b = t.x_face ? t.a + 1 : t.a + nx;
    const double K_lattice = 2.0 / (1.0 / node_D[t.a] + 1.0 / node_D[b]);  // eq T7: harmonic face D
    const double dK = t.K - K_lattice;
    if (dK == 0.0 && t.X == 0.0) continue;
    Face f{t.a, b, t.a, t.a, b, b, dK, t.X};
    if (t.X != 0.0) {
      const std::size_t e = t.x_face ? nx : 1;  // transverse step
      // the row next to the axis mirrors itself across it (C even in r)
      const bool axis_row = t.x_face && y == 0 && axisymmetric && row_radius[0] == 0.5;
      const bool has_room = t.x_face ? ((y >= 1 || axis_row) && y + 1 < grid.ny) : (x >= 1 && x + 1 < grid.nx);
      if (!has_room) throw std::invalid_argument("FaceFluxCorrection: cross term on the grid's edge");
      f = {t.a, b, t.a + e, axis_row ? t.a : t.a - e, b + e, axis_row ? b : b - e, dK, t.X};
    }
    if (axisymmetric) {  // eq 7.9': per radian, through a face of radius r_f
      const double r_a = row_radius[static_cast<std::size_t>(y)];
      const double r_b = t.x_face ? r_a : row_radius[static_cast<std::size_t>(y + 1)];
      const double r_f = t.x_face ? r_a : r_a + 0.5;
      f.dK *= r_f;
      f.X *= r_f;
      f.share_a = 1.0 / r_a;
      f.share_b = 1.0 / r_b;
    }
    slot_of(f.a);
    slot_of(f.b);
    faces_.push_back(f);
  }
  node_correction_.assign(nodes_.size(), 0.0);
  std::vector<std::size_t> read_slot(N, N);
  auto read = [&](std::size_t n) {
    if (read_slot[n] == N) {
      read_slot[n] = read_nodes_.size();
      read_nodes_.push_back(n);
    }
    return read_slot[n];
  };
  for (const auto& f : faces_)
    face_refs_.push_back({read(f.a), read(f.b), read(f.a_plus), read(f.a_minus), read(f.b_plus), read(f.b_minus)});
  read_C_.assign(read_nodes_.size(), 0.0);
}

void FaceFluxCorrection::evaluate(const TransportLattice& lattice) {
  std::fill(node_correction_.begin(), node_correction_.end(), 0.0);
  for (std::size_t k = 0; k < read_nodes_.size(); ++k)
    read_C_[k] = lattice.source_corrected_concentration(read_nodes_[k]);  // Ĉ (T7), once per node
  for (std::size_t i = 0; i < faces_.size(); ++i) {
    const Face& f = faces_[i];
    const FaceRefs& r = face_refs_[i];
    double dF = f.dK * (read_C_[r.a] - read_C_[r.b]);
    if (f.X != 0.0)
      dF -= f.X * 0.25 * (read_C_[r.a_plus] - read_C_[r.a_minus] + read_C_[r.b_plus] - read_C_[r.b_minus]);  // eq T11
    node_correction_[slot_[f.a]] -= dF * f.share_a;
    node_correction_[slot_[f.b]] += dF * f.share_b;
  }
}

double FaceFluxCorrection::lagged_gain(const TransportLattice& lattice) const {
  // A_nm = Σ_f s_nf ∂ΔF_f/∂Ĉ_m φ_m, s_nf = −1 at a, +1 at b; rows accumulated per touched node
  // as Σ |…| over (face, m) pairs (an upper bound of Σ_m |A_nm|, equal when no m repeats).
  std::vector<double> row(nodes_.size(), 0.0);
  const auto phi = [&](std::size_t m) { return lattice.source_offset_factor(m); };
  for (const auto& f : faces_) {
    // (axisymmetric: Ĉ_m = C_m + φ_m q_m with q the per-volume source, q_m = ΔF share_m)
    double dependence = std::abs(f.dK) * (phi(f.a) + phi(f.b));
    if (f.X != 0.0) dependence += std::abs(f.X) * 0.25 * (phi(f.a_plus) + phi(f.a_minus) + phi(f.b_plus) + phi(f.b_minus));
    row[slot_[f.a]] += dependence * f.share_a;
    row[slot_[f.b]] += dependence * f.share_b;
  }
  return row.empty() ? 0.0 : *std::max_element(row.begin(), row.end());
}

void FaceFluxCorrection::require_stable(const TransportLattice& lattice) const {
  const double gain = lagged_gain(lattice);
  if (gain > kLaggedGainLimit) {
    throw std::invalid_argument(
        "FaceFluxCorrection: lagged gain " + std::to_string(gain) + " exceeds the stability limit " +
        std::to_string(kLaggedGainLimit) +
        " (a diffusivity contrast above about 9.5 across the membrane); reduce the contrast or use the series or "
        "node-tensor interface rule (docs/transport.md, \"Stability of the face-flux correction\")");
  }
}

void FaceFluxCorrection::add_to(std::span<double> source) const {
  for (std::size_t k = 0; k < nodes_.size(); ++k) source[nodes_[k]] += node_correction_[k];
}

}  // namespace erythro::transport
