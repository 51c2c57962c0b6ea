#pragma once
// In-plane tension laws of the 2D membrane, per unit depth (docs/model.md §3).
// λ = ℓ/L is the stretch of a membrane element (current over rest length).
// Each law gives the tension T(λ), its energy per unit REST length W(λ) with
// W(1) = 0 and dW/dλ = T (so an element of rest length L stores L·W(λ) and pulls
// its ends with T), and the stiffness dT/dλ (used by the stability estimate).
//
//  neo_hookean : thesis eqs 2–6 reduced to 2D (out-of-plane stress zero, λ2 = λ^−½):
//                T = E_s(λ^{3/2} − λ^{−3/2}) = E_s(λ³ − 1)/λ^{3/2},
//                W = E_s[(2/5)(λ^{5/2} − 1) + 2(λ^{−1/2} − 1)].
//  skalak      : Skalak et al. 1973 (Biophys J 13:245), W_S = (E_s/4)[I1² + 2I1 − 2I2 + C I2²],
//                I1 = λ1² + λ2² − 2, I2 = λ1²λ2² − 1, in plane strain (λ2 = 1, a ring
//                section of a long cylinder): W = (E_s/4)(1 + C)(λ² − 1)²,
//                T = E_s(1 + C) λ(λ² − 1).
//  hookean     : linear spring, T = E_s(λ − 1), W = E_s(λ − 1)²/2.
// Small-strain stiffness dT/dλ at λ = 1: 3E_s, 2E_s(1 + C), E_s respectively.
#include <cmath>
#include <string_view>

namespace erythro::membrane {

enum class TensionLawType { neo_hookean, skalak, hookean };

std::string_view to_string(TensionLawType type);
bool parse_tension_law(std::string_view name, TensionLawType& out);

struct TensionLaw {
  TensionLawType type = TensionLawType::neo_hookean;
  double modulus = 0.0;   // E_s (lattice units: force per unit depth)
  double skalak_c = 1.0;  // Skalak's area-dilation parameter C (skalak only)

  double tension(double lambda) const;    // T(λ): tension_of<type>
  double energy(double lambda) const;     // W(λ), energy per unit rest length
  double stiffness(double lambda) const;  // dT/dλ
};

// T(λ) of one law fixed at compile time (the membrane's edge loop takes it per law, so it has no
// branch per edge; TensionLaw::tension dispatches to it).
template <TensionLawType kLaw>
inline double tension_of(const TensionLaw& law, double l) {
  if constexpr (kLaw == TensionLawType::neo_hookean) return law.modulus * (l * std::sqrt(l) - 1.0 / (l * std::sqrt(l)));
  else if constexpr (kLaw == TensionLawType::skalak) return law.modulus * (1.0 + law.skalak_c) * l * (l * l - 1.0);
  else return law.modulus * (l - 1.0);
}

}  // namespace erythro::membrane
