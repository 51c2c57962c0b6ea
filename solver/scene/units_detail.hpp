#pragma once
// Shared by units.cpp and cell_checks.cpp (private to scene/): number formatting
// for messages, the rejection of a set-up, and the cell set-up.
#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"

namespace erythro::scene::detail {

inline std::string num(double v) {
  char buf[48];
  std::snprintf(buf, sizeof(buf), "%.6g", v);
  return buf;
}
inline std::string vec(const std::array<double, 2>& v) {
  std::string out(1, '[');  // built by appending: GCC 12 -Wrestrict misfires on "lit" + string&&
  return out.append(num(v[0])).append(", ").append(num(v[1])).append("]");
}
inline std::string origin(const Scene& s) { return s.source_path.empty() ? "scene" : s.source_path; }

[[noreturn]] inline void reject(const Scene& s, const std::string& what) { throw InputError(origin(s) + ": " + what); }

inline bool is_wall(const SideSpec& side) { return side.type != "periodic"; }
// Axis 0 (x) is bounded by the left/right sides, axis 1 (y) by bottom/top.
inline bool wall_bounded(const Scene& s, int axis) {
  return axis == 0 ? is_wall(s.boundaries.left) : is_wall(s.boundaries.bottom);
}

// TRT relaxes the odd moments with τ− = ½ + Λ/(τ − ½), which tends to ½ (vanishing
// relaxation of the fluxes, unstable) as Λ shrinks or τ grows: τ− must keep the margin τ
// keeps. `tau_source` names what sets τ (the fluid's, a layer's or the cells' interior τ).
inline void check_trt_tau_minus(const Scene& s, const LatticeSetup& L, double tau, const std::string& tau_source) {
  if (L.collision.model != fluid::CollisionModel::trt) return;
  const double magic = L.collision.trt_magic, tau_minus = fluid::trt_tau_minus(tau, magic);
  const double tau_min = 0.5 + s.limits.min_tau_margin;
  if (tau_minus >= tau_min && tau_minus > 0.5) return;
  reject(s, "fluid.collision = \"trt\" with fluid.trt_magic Λ = " + num(magic) + " and τ = " + num(tau) + " (" +
                tau_source + ") gives τ− = ½ + Λ/(τ − ½) = " + num(tau_minus) + ", below " + num(tau_min) +
                " (0.5 + limits.min_tau_margin; τ− → ½ leaves the fluxes unrelaxed, unstable): raise fluid.trt_magic "
                "to >= " + num((tau_min - 0.5) * (tau - 0.5)) + " or lower τ");
}

// [membrane] and [[cells]] → lattice moduli, placed marker polygons and the stability
// estimate. Rules (docs/scenes.md): equivalent radius >= kMinCellRadius h, marker
// spacing in [kMinMarkerSpacing, limits.max_marker_spacing] h, markers >= limits.min_cell_gap h
// from another cell's markers and from a wall, stability numbers below their limits.
// `mechanics` = false (no flow, cells are fixed shapes): placement and geometry checks only.
MembraneSetup derive_membrane(const Scene& s, const LatticeSetup& L, bool mechanics = true);

// [transport], [[species]], [hemoglobin] → TransportSetup (transport_setup.cpp). L has its
// grid, scales (the fluid's, or the transport's own without fluid) and boundaries set.
TransportSetup derive_transport(const Scene& s, const LatticeSetup& L);
// The options of [transport] and [hemoglobin] beyond species and coupling (collision, cell
// representation, interface rule, uniform velocity, [[transport.layers]], the monitor's concentration
// range), checked and converted into T (transport_options.cpp; T.units already set).
void derive_transport_options(const Scene& s, const LatticeSetup& L, TransportSetup& T);
// Rows of `erythro check` for those options (collision, cells, coupling, velocity, layers).
void append_transport_option_rows(const TransportSetup& T, std::vector<std::array<std::string, 3>>& rows);

// [[fluid.layers]] → lattice rectangles and relaxation times (layer_setup.cpp). L has its
// grid and collision set.
std::vector<fluid::ViscosityLayer> derive_layers(const Scene& s, const LatticeSetup& L);

}  // namespace erythro::scene::detail
