#pragma once
// Exact steady solution of 1D diffusion–reaction through a stack of layers
// (docs/verification-transport.md, cases transport_layered_slab and transport_arteriole_no):
//   planar:       D_j C'' − k_j C + q_j = 0              in layer j (thickness t_j)
//   cylindrical:  D_j (1/r)(r C')' − k_j C + q_j = 0     (a body of revolution, r from the axis)
// zero flux at y = 0 (lumen centre or axis, symmetry) and at the outer end, C and D C'
// continuous at every interface. Planar, in local coordinate s = y − y_j ∈ [0, t_j]:
//   k_j > 0:  C = q_j/k_j + a_j e^{−κ_j s} + b_j e^{−κ_j (t_j − s)},  κ_j = √(k_j/D_j)
//   k_j = 0:  C = −q_j s²/(2 D_j) + a_j + b_j s/t_j
// Cylindrical, in layer j between r_j and r_{j+1}:
//   k_j > 0:  C = q_j/k_j + a_j I0(κ_j r)/I0(κ_j r_{j+1}) + b_j K0(κ_j r)/K0(κ_j r_j)
//   k_j = 0:  C = −q_j r²/(4 D_j) + a_j + b_j ln(r/r_j)
// and in the layer holding the axis (r_0 = 0) only the regular part (b_0 = 0: K0 and ln are
// singular there; this replaces the zero-flux condition at the axis).
// (Decaying exponentials and the scaled Bessel functions keep the 2L×2L system well
// conditioned); the 2L coefficients solve the linear system of the 2 end and 2(L − 1)
// interface conditions.
#include <vector>

namespace erythro::vv {

struct SlabLayer {
  double thickness, D, k, q;  // any consistent units
};

enum class StackGeometry { planar, cylindrical };

class LayeredSlab {
 public:
  explicit LayeredSlab(std::vector<SlabLayer> layers, StackGeometry geometry = StackGeometry::planar);
  double concentration(double y) const;
  double flux(double y) const;  // −D C' (positive towards +y)
  double length() const { return y_.back(); }
  const std::vector<double>& interfaces() const { return y_; }  // y_0 = 0 … y_L = length

 private:
  int layer_of(double y) const;
  // C or C' in layer j at local s, as value + coefficient weights (φa, φb).
  void basis(int j, double s, double& particular, double& pa, double& pb, double& dparticular, double& dpa,
             double& dpb) const;
  void planar_basis(int j, double s, double& particular, double& pa, double& pb, double& dparticular, double& dpa,
                    double& dpb) const;
  void cylindrical_basis(int j, double r, double& particular, double& pa, double& pb, double& dparticular,
                         double& dpa, double& dpb) const;
  std::vector<SlabLayer> layers_;
  StackGeometry geometry_;
  std::vector<double> y_, a_, b_;
};

}  // namespace erythro::vv
