#include "membrane/stability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace erythro::membrane {

namespace {

// Measured divergence thresholds (lattice, h = Δt = ρ0 = 1), inflated circle R = 8,
// λ = 1.05, marker spacing 0.5–0.79 h, τ ∈ {0.6, 1, 2}, 10⁴ steps; the smallest
// value over those set-ups (τ = 0.6 for most). Tension as K_T = dT/dλ.
struct Thresholds {
  double tension, bending, area;
};
Thresholds measured(ib::KernelType k) {
  switch (k) {
    case ib::KernelType::cosine4: return {2.41, 3.57, 0.0906};
    case ib::KernelType::peskin4: return {2.40, 3.68, 0.0920};
    case ib::KernelType::roma3: return {0.144, 0.101, 0.173};
    case ib::KernelType::linear2: return {0.0296, 0.0176, 0.0209};
  }
  return {0.0, 0.0, 0.0};
}
constexpr double kSafety = 2.0;
constexpr double kCalibratedViscosity = 1.0 / 30.0;  // τ = 0.6

}  // namespace

StabilityEstimate estimate_stability(const StabilityInput& in) {
  StabilityEstimate e;
  const double rho = in.density;
  const double lmax = std::max(1.0, in.max_stretch);
  // Stiffness over the expected stretch range (sampled; dT/dλ is monotone for the
  // three laws on λ ≥ 1, the samples only guard the general case).
  double K = 0.0;
  for (int s = 0; s <= 16; ++s) K = std::max(K, in.model.tension.stiffness(1.0 + (lmax - 1.0) * s / 16.0));
  e.tension_number = K / rho;
  e.bending_number = in.model.bending / rho;
  e.area_number = in.model.area_modulus / rho;
  const Thresholds t = measured(in.kernel);
  const double visc = std::min(1.0, in.viscosity / kCalibratedViscosity);
  e.tension_limit = t.tension * visc / kSafety;
  e.bending_limit = t.bending * visc / kSafety;
  e.area_limit = t.area * visc / kSafety;

  e.max_dt_factor = std::numeric_limits<double>::infinity();
  const char* worst = nullptr;
  double worst_value = 0.0, worst_limit = 0.0;
  auto check = [&](const char* name, double value, double limit) {
    if (value <= 0.0) return;
    const double f = std::sqrt(limit / value);
    if (f < e.max_dt_factor) {
      e.max_dt_factor = f;
      worst = name;
      worst_value = value;
      worst_limit = limit;
    }
  };
  check("tension stiffness dT/dlambda", e.tension_number, e.tension_limit);
  check("bending modulus E_B", e.bending_number, e.bending_limit);
  check("area modulus k_A", e.area_number, e.area_limit);
  if (worst != nullptr && e.max_dt_factor < 1.0) {
    std::ostringstream msg;
    msg << "membrane too stiff for the explicit immersed-boundary update with the " << ib::to_string(in.kernel)
        << " kernel: " << worst << " = " << worst_value << " in lattice units exceeds the stable limit " << worst_limit
        << " (explicit-update limit, docs/verification-ib-membrane.md); reduce the time step by a factor "
        << 1.0 / e.max_dt_factor << " or more (finer lattice or larger tau), or soften the membrane";
    e.problem = msg.str();
  }
  const bool narrow = in.kernel == ib::KernelType::roma3 || in.kernel == ib::KernelType::linear2;
  if (narrow && lmax > 1.0 && in.model.tension.modulus > 0.0) {
    e.warning = std::string("the ") + std::string(ib::to_string(in.kernel)) +
                " kernel with a pre-stressed membrane develops a slowly growing grid-scale marker instability "
                "(docs/verification-ib-membrane.md); prefer cosine4 or peskin4";
  }
  return e;
}

}  // namespace erythro::membrane
