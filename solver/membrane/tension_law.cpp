#include "membrane/tension_law.hpp"

#include <cmath>

namespace erythro::membrane {

std::string_view to_string(TensionLawType type) {
  switch (type) {
    case TensionLawType::neo_hookean: return "neo_hookean";
    case TensionLawType::skalak: return "skalak";
    case TensionLawType::hookean: return "hookean";
  }
  return "?";
}

bool parse_tension_law(std::string_view name, TensionLawType& out) {
  for (auto t : {TensionLawType::neo_hookean, TensionLawType::skalak, TensionLawType::hookean}) {
    if (name == to_string(t)) {
      out = t;
      return true;
    }
  }
  return false;
}

double TensionLaw::tension(double l) const {
  switch (type) {
    case TensionLawType::neo_hookean: return tension_of<TensionLawType::neo_hookean>(*this, l);
    case TensionLawType::skalak: return tension_of<TensionLawType::skalak>(*this, l);
    case TensionLawType::hookean: return tension_of<TensionLawType::hookean>(*this, l);
  }
  return 0.0;
}

double TensionLaw::energy(double l) const {
  switch (type) {
    case TensionLawType::neo_hookean: {
      const double s = std::sqrt(l);
      return modulus * (0.4 * (l * l * s - 1.0) + 2.0 * (1.0 / s - 1.0));
    }
    case TensionLawType::skalak: return 0.25 * modulus * (1.0 + skalak_c) * (l * l - 1.0) * (l * l - 1.0);
    case TensionLawType::hookean: return 0.5 * modulus * (l - 1.0) * (l - 1.0);
  }
  return 0.0;
}

double TensionLaw::stiffness(double l) const {
  switch (type) {
    case TensionLawType::neo_hookean: {
      const double s = std::sqrt(l);
      return modulus * 1.5 * (s + 1.0 / (l * l * s));
    }
    case TensionLawType::skalak: return modulus * (1.0 + skalak_c) * (3.0 * l * l - 1.0);
    case TensionLawType::hookean: return modulus;
  }
  return 0.0;
}

}  // namespace erythro::membrane
