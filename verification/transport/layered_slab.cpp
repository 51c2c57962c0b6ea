#include "layered_slab.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace erythro::vv {

LayeredSlab::LayeredSlab(std::vector<SlabLayer> layers, StackGeometry geometry)
    : layers_(std::move(layers)), geometry_(geometry) {
  const int L = static_cast<int>(layers_.size());
  if (L < 1) throw std::invalid_argument("LayeredSlab: no layers");
  y_.assign(1, 0.0);
  for (const auto& l : layers_) y_.push_back(y_.back() + l.thickness);
  const int M = 2 * L;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(M, M);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(M);
  auto row_value = [&](int r, int j, double s, double sign, bool derivative) {
    double p, pa, pb, dp, dpa, dpb;
    basis(j, s, p, pa, pb, dp, dpa, dpb);
    const double scale = derivative ? layers_[j].D : 1.0;  // flux continuity: D C'
    A(r, 2 * j) += sign * scale * (derivative ? dpa : pa);
    A(r, 2 * j + 1) += sign * scale * (derivative ? dpb : pb);
    rhs(r) -= sign * scale * (derivative ? dp : p);
  };
  int r = 0;
  if (geometry_ == StackGeometry::planar) {
    row_value(r++, 0, 0.0, 1.0, true);  // C'(0) = 0
  } else {
    A(r++, 1) = 1.0;  // b_0 = 0: regular at the axis (then C'(0) = 0)
  }
  for (int j = 0; j + 1 < L; ++j) {
    row_value(r, j, layers_[j].thickness, 1.0, false);  // C_j(t_j) − C_{j+1}(0) = 0
    row_value(r++, j + 1, 0.0, -1.0, false);
    row_value(r, j, layers_[j].thickness, 1.0, true);  // D_j C_j' − D_{j+1} C_{j+1}' = 0
    row_value(r++, j + 1, 0.0, -1.0, true);
  }
  row_value(r++, L - 1, layers_[L - 1].thickness, 1.0, true);  // C'(end) = 0
  const Eigen::VectorXd x = A.partialPivLu().solve(rhs);
  for (int j = 0; j < L; ++j) {
    a_.push_back(x[2 * j]);
    b_.push_back(x[2 * j + 1]);
  }
}

void LayeredSlab::basis(int j, double s, double& p, double& pa, double& pb, double& dp, double& dpa,
                        double& dpb) const {
  if (geometry_ == StackGeometry::planar) return planar_basis(j, s, p, pa, pb, dp, dpa, dpb);
  return cylindrical_basis(j, y_[j] + s, p, pa, pb, dp, dpa, dpb);
}

void LayeredSlab::cylindrical_basis(int j, double r, double& p, double& pa, double& pb, double& dp, double& dpa,
                                    double& dpb) const {
  const SlabLayer& l = layers_[j];
  const double r_in = y_[j], r_out = y_[j + 1];
  const bool axis = r_in == 0.0;  // the axis layer: the singular part is left out (b_0 = 0)
  if (l.k > 0.0) {
    const double kappa = std::sqrt(l.k / l.D);
    p = l.q / l.k;
    dp = 0.0;
    const double i_scale = std::cyl_bessel_i(0.0, kappa * r_out);
    pa = std::cyl_bessel_i(0.0, kappa * r) / i_scale;
    dpa = kappa * std::cyl_bessel_i(1.0, kappa * r) / i_scale;  // I0' = I1
    if (axis) {
      pb = dpb = 0.0;
    } else {
      const double k_scale = std::cyl_bessel_k(0.0, kappa * r_in);
      pb = std::cyl_bessel_k(0.0, kappa * r) / k_scale;
      dpb = -kappa * std::cyl_bessel_k(1.0, kappa * r) / k_scale;  // K0' = −K1
    }
  } else {
    p = -l.q * r * r / (4.0 * l.D);
    dp = -l.q * r / (2.0 * l.D);
    pa = 1.0;
    dpa = 0.0;
    pb = axis ? 0.0 : std::log(r / r_in);
    dpb = axis ? 0.0 : 1.0 / r;
  }
}

void LayeredSlab::planar_basis(int j, double s, double& p, double& pa, double& pb, double& dp, double& dpa,
                               double& dpb) const {
  const SlabLayer& l = layers_[j];
  if (l.k > 0.0) {
    const double kappa = std::sqrt(l.k / l.D);
    p = l.q / l.k;
    dp = 0.0;
    pa = std::exp(-kappa * s);
    pb = std::exp(-kappa * (l.thickness - s));
    dpa = -kappa * pa;
    dpb = kappa * pb;
  } else {
    p = -l.q * s * s / (2.0 * l.D);
    dp = -l.q * s / l.D;
    pa = 1.0;
    pb = s / l.thickness;
    dpa = 0.0;
    dpb = 1.0 / l.thickness;
  }
}

int LayeredSlab::layer_of(double y) const {
  for (int j = 0; j + 1 < static_cast<int>(layers_.size()); ++j)
    if (y < y_[j + 1]) return j;
  return static_cast<int>(layers_.size()) - 1;
}

double LayeredSlab::concentration(double y) const {
  const int j = layer_of(y);
  double p, pa, pb, dp, dpa, dpb;
  basis(j, y - y_[j], p, pa, pb, dp, dpa, dpb);
  return p + a_[j] * pa + b_[j] * pb;
}

double LayeredSlab::flux(double y) const {
  const int j = layer_of(y);
  double p, pa, pb, dp, dpa, dpb;
  basis(j, y - y_[j], p, pa, pb, dp, dpa, dpb);
  return -layers_[j].D * (dp + a_[j] * dpa + b_[j] * dpb);
}

}  // namespace erythro::vv
