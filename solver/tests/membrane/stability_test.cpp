// The explicit-update stability estimate (membrane/stability.hpp): numbers, limits,
// Δt factor, and the messages the scene layer shows.
#include <gtest/gtest.h>

#include <cmath>

#include "membrane/stability.hpp"

using namespace erythro;
using namespace erythro::membrane;
using namespace erythro::geometry;

TEST(Stability, SoftMembraneIsAccepted) {
  StabilityInput in;
  in.kernel = ib::KernelType::cosine4;
  in.model.tension = {TensionLawType::neo_hookean, 1.7e-5};  // thesis doublet, lattice
  in.model.bending = 4.6e-5;
  in.viscosity = 1.0 / 6.0;
  const auto e = estimate_stability(in);
  EXPECT_TRUE(e.acceptable()) << e.problem;
  EXPECT_NEAR(e.tension_number, 3 * 1.7e-5, 1e-15);  // dT/dλ(1) = 3E_s
  EXPECT_NEAR(e.max_dt_factor,
              std::min(std::sqrt(e.bending_limit / e.bending_number), std::sqrt(e.tension_limit / e.tension_number)),
              1e-12);
  EXPECT_GT(e.max_dt_factor, 100.0);  // the thesis membrane is far from the explicit limit
  EXPECT_TRUE(e.warning.empty());
}

TEST(Stability, StiffMembraneIsRejectedWithAFactor) {
  StabilityInput in;
  in.kernel = ib::KernelType::peskin4;
  in.model.tension = {TensionLawType::hookean, 3.0};
  in.viscosity = 1.0 / 6.0;
  const auto e = estimate_stability(in);
  ASSERT_FALSE(e.acceptable());
  EXPECT_NEAR(e.tension_limit, 2.40 / 2, 1e-12);
  EXPECT_NEAR(e.max_dt_factor, std::sqrt(1.2 / 3.0), 1e-12);
  EXPECT_NE(e.problem.find("peskin4"), std::string::npos);
  EXPECT_NE(e.problem.find("tension stiffness"), std::string::npos);
}

TEST(Stability, LowViscosityLowersTheLimitsAndPreStressWidensTheStiffnessRange) {
  StabilityInput in;
  in.model.tension = {TensionLawType::skalak, 0.1, 1.0};  // Skalak stiffens with stretch
  in.viscosity = 1.0 / 60.0;  // half the calibrated viscosity
  in.max_stretch = 1.5;
  const auto e = estimate_stability(in);
  EXPECT_NEAR(e.tension_limit, 2.41 / 2 / 2, 1e-12);
  EXPECT_NEAR(e.tension_number, in.model.tension.stiffness(1.5), 1e-12);
  in.model.tension = {TensionLawType::neo_hookean, 0.1};  // softens beyond λ = 1: stiffest at rest
  EXPECT_NEAR(estimate_stability(in).tension_number, 0.3, 1e-12);
}

TEST(Stability, NarrowKernelWithPreStressWarns) {
  StabilityInput in;
  in.kernel = ib::KernelType::roma3;
  in.model.tension = {TensionLawType::neo_hookean, 1e-3};
  in.max_stretch = 1.05;
  EXPECT_FALSE(estimate_stability(in).warning.empty());
  in.max_stretch = 1.0;
  EXPECT_TRUE(estimate_stability(in).warning.empty());
}
