// Kernel moment conditions (Peskin 2002, Acta Numerica 11:479, §6) for every kernel,
// at many marker offsets r ∈ [0, 1): what each kernel promises holds to round-off;
// what the thesis's cosine kernel (eq 24) does not satisfy is measured against its
// analytic value.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "ib/kernel.hpp"
#include "ib/kernel_moments.hpp"

using namespace erythro::ib;

namespace {
constexpr int kOffsets = 1000;
constexpr double kRoundOff = 1e-14;  // sums of ≤ 9 terms of O(1): a few ulps

// Largest |Σ(r − j)φ(r − j)| of the cosine kernel, derived from Σ over the 4 support
// nodes d0, d0 − 1, d0 − 2, d0 − 3 (d0 ∈ [1, 2)): S1 = d0 − 3/2 + [cos(πd0/2) + sin(πd0/2)]/2,
// extremal where cos(πd0/2 + π/4) = −2√2/π: max |S1| = √((1 − 8/π²)/2) − (2/π) arccos(2√2/π).
double cosine_first_moment_max() {
  const double pi = std::numbers::pi;
  return std::sqrt((1.0 - 8.0 / (pi * pi)) / 2.0) - (2.0 / pi) * std::acos(2.0 * std::sqrt(2.0) / pi);
}
}  // namespace

TEST(Kernel, NamesRoundTrip) {
  for (KernelType t : kAllKernels) {
    KernelType back{};
    ASSERT_TRUE(parse_kernel(to_string(t), back));
    EXPECT_EQ(back, t);
  }
  KernelType k{};
  EXPECT_FALSE(parse_kernel("gaussian", k));
}

TEST(Kernel, SupportAndContinuity) {
  for (KernelType t : kAllKernels) {
    const double half = 0.5 * width(t);
    EXPECT_EQ(phi(t, half), 0.0) << to_string(t);
    EXPECT_EQ(phi(t, -half - 0.1), 0.0) << to_string(t);
    EXPECT_NEAR(phi(t, half - 1e-9), 0.0, 1e-7) << to_string(t);  // continuous at the support edge
    for (double r = -half; r <= half; r += 0.01) EXPECT_GE(phi(t, r), 0.0) << to_string(t) << " r=" << r;
  }
}

TEST(Kernel, PartitionOfUnityAllKernels) {
  // Σφ = 1 holds exactly for all four, the cosine kernel included: its 4-point sum is
  // 1 + ¼[cos a + sin a − cos a − sin a] = 1. Measured defect: round-off.
  for (KernelType t : kAllKernels) {
    double worst = 0.0;
    for (int k = 0; k < kOffsets; ++k) worst = std::max(worst, std::abs(moment_sums(t, k / double(kOffsets)).zeroth - 1.0));
    EXPECT_LE(worst, kRoundOff) << to_string(t);
  }
}

TEST(Kernel, EvenOddConditionOfFourPointKernels) {
  for (KernelType t : {KernelType::cosine4, KernelType::peskin4}) {
    for (int k = 0; k < kOffsets; ++k) {
      const auto s = moment_sums(t, k / double(kOffsets));
      EXPECT_NEAR(s.even, 0.5, kRoundOff) << to_string(t);
      EXPECT_NEAR(s.odd, 0.5, kRoundOff) << to_string(t);
    }
  }
}

TEST(Kernel, FirstMomentVanishesExceptCosine) {
  for (KernelType t : {KernelType::peskin4, KernelType::roma3, KernelType::linear2}) {
    for (int k = 0; k < kOffsets; ++k) EXPECT_NEAR(moment_sums(t, k / double(kOffsets)).first, 0.0, kRoundOff) << to_string(t);
  }
  // Cosine: defect measured on a fine offset grid, compared with the analytic maximum.
  double worst = 0.0;
  for (int k = 0; k <= 100000; ++k) worst = std::max(worst, std::abs(moment_sums(KernelType::cosine4, k / 100000.0).first));
  const double expected = cosine_first_moment_max();
  EXPECT_NEAR(expected, 0.0210882, 1e-7);
  EXPECT_NEAR(worst, expected, 1e-9);  // offset grid 1e-5 resolves the maximum to O(1e-10)
  EXPECT_NEAR(moment_sums(KernelType::cosine4, 0.0).first, 0.0, kRoundOff);  // symmetric offsets
  EXPECT_NEAR(moment_sums(KernelType::cosine4, 0.5).first, 0.0, kRoundOff);
}

TEST(Kernel, SumOfSquares) {
  // Peskin 4-point: 3/8; Roma 3-point: 1/2; the cosine kernel also gives exactly 3/8
  // (1/16 Σ(1 + cos)² = 1/16 (4 + 0 + 2) = 3/8). The hat kernel has no such condition.
  for (int k = 0; k < kOffsets; ++k) {
    const double r = k / double(kOffsets);
    EXPECT_NEAR(moment_sums(KernelType::peskin4, r).squares, 3.0 / 8.0, kRoundOff);
    EXPECT_NEAR(moment_sums(KernelType::cosine4, r).squares, 3.0 / 8.0, kRoundOff);
    EXPECT_NEAR(moment_sums(KernelType::roma3, r).squares, 0.5, kRoundOff);
  }
  EXPECT_GT(std::abs(moment_sums(KernelType::linear2, 0.5).squares - moment_sums(KernelType::linear2, 0.0).squares), 0.4);
}

TEST(Kernel, SupportStartCoversExactlyTheNonzeroNodes) {
  for (KernelType t : kAllKernels) {
    const int w = width(t);
    for (double X : {0.0, 0.3, 0.5, 0.7, 1.0, 5.25, -2.6, 17.999}) {
      const int i0 = support_start(X, w);
      double inside = 0.0;
      for (int b = 0; b < w; ++b) inside += phi(t, X - (i0 + b + 0.5));
      EXPECT_NEAR(inside, 1.0, kRoundOff) << to_string(t) << " X=" << X;
      EXPECT_EQ(phi(t, X - (i0 - 1 + 0.5)), 0.0) << to_string(t) << " X=" << X;
      EXPECT_EQ(phi(t, X - (i0 + w + 0.5)), 0.0) << to_string(t) << " X=" << X;
    }
  }
}

// support_start's floor (a truncation and a correction, so that the weight loops vectorise) is
// std::floor's: at integers and half-integers from both sides, negative coordinates (unwrapped
// markers left of a periodic edge) and random ones.
TEST(Kernel, SupportStartIsTheFloor) {
  std::vector<double> xs;
  for (int i = -40; i <= 40; ++i)
    for (const double base : {double(i), i + 0.5})
      for (const double x : {base, std::nextafter(base, -1e9), std::nextafter(base, 1e9)}) xs.push_back(x);
  std::mt19937_64 g(7);
  std::uniform_real_distribution<double> u(-3000.0, 3000.0);
  for (int k = 0; k < 100000; ++k) xs.push_back(u(g));
  for (const int w : {2, 3, 4})
    for (const double X : xs) {
      ASSERT_EQ(support_start(X, w), static_cast<int>(std::floor(X + 0.5 - 0.5 * w))) << "X=" << X << " w=" << w;
    }
}
