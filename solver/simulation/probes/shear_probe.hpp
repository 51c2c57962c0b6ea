#pragma once
// Simple-shear diagnostics (docs/model.md §12, eq 12.5) for a wall-driven simple shear: walls at the
// bottom and top moving at U_b and U_t ≠ U_b, periodic in x, no body force
// (scene::wall_shear_rate_per_s), no [[fluid.layers]]:
//   wall_shear_stress_bottom_Pa  σ_xy = μ ∂ū_x/∂y at the bottom wall
//   wall_shear_stress_top_Pa     σ_xy = μ ∂ū_x/∂y at the top wall
//   shear_relative_viscosity     their mean over μ γ̇, γ̇ = (U_t − U_b)/H: the suspension's
//                                viscosity relative to the plasma's (1 without cells)
// ū_x is the mean of u_x over a row; the wall gradient is one-sided through the wall's speed
// and the first two rows (y = h/2, 3h/2), exact for a quadratic profile (eq 12.5), so exact in
// simple shear and in Poiseuille flow. μ is the plasma's: the rows must be plasma (cells kept
// off the walls by the short-range repulsion). At steady state the x-averaged shear stress is
// the same at every y, so either wall gives the suspension's stress; their mean halves the
// noise. Only the current state is read; time averages are the user's.
#include "simulation/probe.hpp"

namespace erythro::sim {

class ShearProbe : public Probe {
 public:
  // Whether `setup` is such a simple shear with a fluid.
  static bool applies(const scene::LatticeSetup& setup);
  void declare(std::vector<SeriesInfo>& series) const override;
  void sample(const ProbeContext& context, std::span<double> values) override;
};

}  // namespace erythro::sim
