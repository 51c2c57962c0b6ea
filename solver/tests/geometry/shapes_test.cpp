// Cell shapes (geometry/shapes.hpp): counter-clockwise, equally spaced in arc length,
// the Evans–Fung section's area and perimeter (docs/parameters.md), transforms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geometry/shapes.hpp"


using namespace erythro::geometry;

namespace {
// Arc length of the ellipse (a cos t, b sin t) between parameters t0 < t1, fine Simpson.
double ellipse_arc(double a, double b, double t0, double t1) {
  const int n = 20000;
  const double h = (t1 - t0) / n;
  auto f = [&](double t) { return std::hypot(a * std::sin(t), b * std::cos(t)); };
  double s = f(t0) + f(t1);
  for (int k = 1; k < n; ++k) s += f(t0 + k * h) * (k % 2 ? 4 : 2);
  return s * h / 3;
}
}  // namespace

TEST(Shapes, CircleIsRegularAndCounterClockwise) {
  const auto p = circle(64, 5.0);
  ASSERT_EQ(p.size(), 64u);
  EXPECT_NEAR(signed_area(p), 0.5 * 64 * 25 * std::sin(2 * std::numbers::pi / 64), 1e-12);
  EXPECT_NEAR(perimeter(p), 2 * 64 * 5 * std::sin(std::numbers::pi / 64), 1e-12);
}

TEST(Shapes, EllipseMarkersAreEquallySpacedInArcLength) {
  const double a = 6.0, b = 2.0;
  const int n = 40;
  const auto p = ellipse(n, a, b);
  EXPECT_GT(signed_area(p), 0.0);
  const double L = ellipse_arc(a, b, 0, 2 * std::numbers::pi);
  // Recover each marker's parameter and check arc(0, t_k) = k L / n.
  for (int k = 0; k < n; ++k) {
    double t = std::atan2(p.y[k] / b, p.x[k] / a);
    if (t < 0) t += 2 * std::numbers::pi;
    if (k == 0) t = 0;
    EXPECT_NEAR(ellipse_arc(a, b, 0, t), L * k / n, 1e-9 * L) << "marker " << k;
  }
  // Equal arcs are NOT equal parameter steps on an elongated ellipse.
  EXPECT_GT(std::abs(std::atan2(p.y[1] / b, p.x[1] / a) - 2 * std::numbers::pi / n), 0.05);
}

TEST(Shapes, EvansFungSectionMatchesTabulatedGeometry) {
  // docs/parameters.md (computed, conf. D): a = 3.91 µm → area 13.627 µm², perimeter
  // 19.271 µm, reduced area 4πA/L² = 0.4611. 2000 markers: polygon error ~1e-6.
  const auto p = biconcave(2000, 3.91);
  const double A = signed_area(p), L = perimeter(p);
  EXPECT_NEAR(A, 13.627, 0.001);
  EXPECT_NEAR(L, 19.271, 0.001);
  EXPECT_NEAR(4 * std::numbers::pi * A / (L * L), 0.4611, 0.0001);
  EXPECT_NEAR(p.x[0], -3.91, 1e-12);  // marker 0 at χ = −π/2
  EXPECT_NEAR(p.y[0], 0.0, 1e-12);
  // Chords of an equal-arc polygon are nearly equal (differences O(Δs³κ²)).
  const auto q = biconcave(100, 3.91);
  double lmin = 1e9, lmax = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    const auto j = (i + 1) % q.size();
    const double l = std::hypot(q.x[j] - q.x[i], q.y[j] - q.y[i]);
    lmin = std::min(lmin, l);
    lmax = std::max(lmax, l);
  }
  EXPECT_LT((lmax - lmin) / lmax, 0.01);
}

TEST(Shapes, TransformScalesRotatesAndPlaces) {
  const auto p = ellipse(30, 3.0, 1.0);
  const auto q = transformed(p, 2.0, std::numbers::pi / 2, 10.0, 20.0);
  EXPECT_NEAR(signed_area(q), 4 * signed_area(p), 1e-10);
  double cx, cy;
  centroid(q, cx, cy);
  EXPECT_NEAR(cx, 10.0, 1e-12);
  EXPECT_NEAR(cy, 20.0, 1e-12);
  EXPECT_NEAR(q.x[0], 10.0, 1e-12);  // (3, 0) → scaled (6, 0) → rotated (0, 6) → placed
  EXPECT_NEAR(q.y[0], 26.0, 1e-12);
}

TEST(Shapes, TaylorDeformationOfEllipseAndCircle) {
  // Ellipse L = 10, B = 5: D = (L − B)/(L + B) = 1/3; the inscribed 400-gon's second moments
  // differ from the ellipse's by O((2π/400)²) ≈ 2.5e-4 relative, so 1e-3 on D. Its symmetry
  // about both axes fixes θ to the rotation (0.3 rad) up to round-off, far from the origin.
  double D, theta;
  taylor_deformation(transformed(ellipse(400, 10.0, 5.0), 1.0, 0.3, 1000.0, 2000.0), D, theta);
  EXPECT_NEAR(D, 1.0 / 3.0, 1e-3);
  EXPECT_NEAR(theta, 0.3 * 180.0 / std::numbers::pi, 1e-6);
  // A regular polygon has an isotropic moment tensor: D = 0 up to round-off.
  taylor_deformation(transformed(circle(64, 8.0), 1.0, 0.0, 500.0, 500.0), D, theta);
  EXPECT_LT(D, 1e-10);
}
