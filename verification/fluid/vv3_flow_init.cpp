#include "vv3_flow_init.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "lattice/d2q9.hpp"

namespace erythro::vv {

FlowField::FlowField(std::size_t n) { resize(n, false); }

void FlowField::resize(std::size_t n, bool with_gradients) {
  rho.assign(n, 1.0);
  ux.assign(n, 0.0);
  uy.assign(n, 0.0);
  const std::size_t m = with_gradients ? n : 0;
  dux_dx.assign(m, 0.0);
  dux_dy.assign(m, 0.0);
  duy_dx.assign(m, 0.0);
  duy_dy.assign(m, 0.0);
}

void FlowField::drop_gradients() {
  dux_dx.clear();
  dux_dy.clear();
  duy_dx.clear();
  duy_dy.clear();
}

void initialize_post_collision(fluid::FluidLattice& lattice, const FlowField& field, std::span<const double> fx,
                               std::span<const double> fy) {
  using namespace d2q9;
  const std::size_t N = lattice.grid().size();
  if (field.rho.size() != N || field.ux.size() != N || field.uy.size() != N) {
    throw std::invalid_argument("initialize_post_collision: field size does not match the grid");
  }
  const bool gradients = !field.dux_dx.empty();
  const bool force = !fx.empty();
  const double tau = lattice.collision().tau;
  std::vector<double> f(Q * N);
  for (std::size_t n = 0; n < N; ++n) {
    const double rho = field.rho[n];
    for (int i = 0; i < Q; ++i) {
      double value = equilibrium_deviation(i, rho, field.ux[n], field.uy[n]);
      if (gradients) {
        // Q_i:∇u = Σ_ab (c_a c_b − c_s² δ_ab) ∂_a u_b
        const double q_grad = cx[i] * cx[i] * field.dux_dx[n] + cx[i] * cy[i] * (field.dux_dy[n] + field.duy_dx[n]) +
                              cy[i] * cy[i] * field.duy_dy[n] - cs2 * (field.dux_dx[n] + field.duy_dy[n]);
        value -= (tau - 1.0) * inv_cs2 * w[i] * rho * q_grad;
      }
      if (force) value += 0.5 * inv_cs2 * w[i] * (cx[i] * fx[n] + cy[i] * fy[n]);
      f[i * N + n] = value;
    }
  }
  lattice.set_populations(f);
}

double relative_l2_vector(std::span<const double> ax, std::span<const double> ay, std::span<const double> bx,
                          std::span<const double> by) {
  double num = 0.0, den = 0.0;
  for (std::size_t k = 0; k < bx.size(); ++k) {
    num += (ax[k] - bx[k]) * (ax[k] - bx[k]) + (ay[k] - by[k]) * (ay[k] - by[k]);
    den += bx[k] * bx[k] + by[k] * by[k];
  }
  return std::sqrt(num / den);
}

}  // namespace erythro::vv
