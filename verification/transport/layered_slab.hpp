#pragma once
// Exact steady solution of 1D diffusion–reaction through a stack of layers
// (docs/verification-transport.md, case transport_layered_slab):
//   D_j C'' − k_j C + q_j = 0 in layer j (thickness t_j),
// zero flux at y = 0 (lumen centre, symmetry) and at the outer end, C and D C'
// continuous at every interface. In local coordinate s = y − y_j ∈ [0, t_j]:
//   k_j > 0:  C = q_j/k_j + a_j e^{−κ_j s} + b_j e^{−κ_j (t_j − s)},  κ_j = √(k_j/D_j)
//   k_j = 0:  C = −q_j s²/(2 D_j) + a_j + b_j s/t_j
// (decaying exponentials keep the 2L×2L system well conditioned); the 2L
// coefficients solve the linear system of the 2 end and 2(L − 1) interface conditions.
#include <vector>

namespace erythro::vv {

struct SlabLayer {
  double thickness, D, k, q;  // any consistent units
};

class LayeredSlab {
 public:
  explicit LayeredSlab(std::vector<SlabLayer> layers);
  double concentration(double y) const;
  double flux(double y) const;  // −D C' (positive towards +y)
  double length() const { return y_.back(); }
  const std::vector<double>& interfaces() const { return y_; }  // y_0 = 0 … y_L = length

 private:
  int layer_of(double y) const;
  // C or C' in layer j at local s, as value + coefficient weights (φa, φb).
  void basis(int j, double s, double& particular, double& pa, double& pb, double& dparticular, double& dpa,
             double& dpb) const;
  std::vector<SlabLayer> layers_;
  std::vector<double> y_, a_, b_;
};

}  // namespace erythro::vv
