// Tension laws (membrane/tension_law.hpp): T(1) = W(1) = 0, dW/dλ = T and
// dT/dλ = stiffness (central differences), and the closed forms of docs/model.md §3.
#include <gtest/gtest.h>

#include <cmath>

#include "membrane/tension_law.hpp"

using namespace erythro::membrane;


namespace {
constexpr TensionLawType kLaws[] = {TensionLawType::neo_hookean, TensionLawType::skalak, TensionLawType::hookean};
}

TEST(TensionLaw, NamesRoundTrip) {
  for (auto t : kLaws) {
    TensionLawType back{};
    ASSERT_TRUE(parse_tension_law(to_string(t), back));
    EXPECT_EQ(back, t);
  }
  TensionLawType x{};
  EXPECT_FALSE(parse_tension_law("mooney", x));
}

TEST(TensionLaw, RestStateIsStressFreeAndEnergyIsItsIntegral) {
  for (auto t : kLaws) {
    const TensionLaw law{t, 2.5, 3.0};
    EXPECT_EQ(law.tension(1.0), 0.0) << to_string(t);
    EXPECT_NEAR(law.energy(1.0), 0.0, 1e-15) << to_string(t);
    for (double l = 0.6; l <= 1.6; l += 0.05) {
      // Central differences, step 1e-5: truncation ~1e-10·|W'''|, round-off ~1e-16/1e-5.
      const double e = 1e-5;
      EXPECT_NEAR((law.energy(l + e) - law.energy(l - e)) / (2 * e), law.tension(l), 1e-8 * (1 + std::abs(law.tension(l))))
          << to_string(t) << " lambda=" << l;
      EXPECT_NEAR((law.tension(l + e) - law.tension(l - e)) / (2 * e), law.stiffness(l), 1e-8 * (1 + law.stiffness(l)))
          << to_string(t) << " lambda=" << l;
      EXPECT_GT(law.energy(l == 1.0 ? 1.01 : l), 0.0);
    }
  }
}

TEST(TensionLaw, ClosedForms) {
  const double Es = 0.7, l = 1.3;
  const TensionLaw neo{TensionLawType::neo_hookean, Es}, hooke{TensionLawType::hookean, Es},
      skalak{TensionLawType::skalak, Es, 2.0};
  EXPECT_NEAR(neo.tension(l), Es * (l * l * l - 1) / std::pow(l, 1.5), 1e-15);
  EXPECT_NEAR(hooke.tension(l), Es * (l - 1), 1e-15);
  EXPECT_NEAR(skalak.tension(l), Es * 3.0 * l * (l * l - 1), 1e-15);
  // Small-strain stiffness: 3E_s, 2E_s(1 + C), E_s.
  EXPECT_NEAR(neo.stiffness(1.0), 3 * Es, 1e-15);
  EXPECT_NEAR(skalak.stiffness(1.0), 6 * Es, 1e-15);
  EXPECT_NEAR(hooke.stiffness(1.0), Es, 1e-15);
}
