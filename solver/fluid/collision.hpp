#pragma once
// Collision operators (thesis §II.3 eq 14 for BGK; Ginzburg's two-relaxation-time
// operator for TRT; projective regularisation of Latt & Chopard 2006, Math Comput
// Simul 72:165, for `regularized`) with Guo et al. 2002 forcing (docs/model.md eq 1.4; thesis eq 17).
// Why the third model is the regularised one and not MRT: docs/stability.md.
#include <string_view>

namespace erythro::fluid {

enum class CollisionModel { bgk, trt, regularized };

struct CollisionConfig {
  CollisionModel model = CollisionModel::bgk;
  double tau = 1.0;               // relaxation time of the symmetric (viscous) moments
  double trt_magic = 3.0 / 16.0;  // Λ = (τ+ − ½)(τ− − ½); 3/16 puts bounce-back walls exactly halfway
                                  // (TRT only; BGK and regularized ignore it)
};

std::string_view to_string(CollisionModel model);
// Parses "bgk" / "trt" / "regularized"; returns false when the name is unknown.
bool parse_collision_model(std::string_view name, CollisionModel& out);

// τ− of TRT from τ+ and the magic parameter Λ.
inline double trt_tau_minus(double tau_plus, double magic) { return 0.5 + magic / (tau_plus - 0.5); }

}  // namespace erythro::fluid
