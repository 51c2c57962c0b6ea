// Randomised check of the band pass and the fill against a brute-force reference: random
// star-shaped cells (radius 1.5–20 h, 8–200 markers, up to 6 Fourier modes, anywhere on a
// periodic grid, so many cross a side) take both band-pass paths (wedges, capsules) and
// the small-cell fallback. Every node: I = H(d) in the band, 0 inside, 1 outside, with d
// the brute-force signed distance over the nearest periodic image.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>

#include "geometry/grid_polygon.hpp"
#include "interior/index_field.hpp"

using namespace erythro;
using namespace erythro::interior;
using namespace erythro::geometry;

namespace {
struct Lcg {
  std::uint64_t s;
  double operator()() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(s >> 11) * 0x1.0p-53;
  }
};

geometry::Polygon star(Lcg& u, double cx, double cy) {
  const double s = u(), R = 1.5 + 18.5 * s * s, amp = 0.6 * u();
  const int markers = 8 + static_cast<int>(192 * u()), modes = 1 + static_cast<int>(6 * u());
  double a[6], ph[6], sum = 0;
  for (int k = 0; k < modes; ++k) {
    a[k] = u();
    ph[k] = 2 * std::numbers::pi * u();
    sum += a[k];
  }
  geometry::Polygon p;
  for (int m = 0; m < markers; ++m) {
    const double th = 2 * std::numbers::pi * m / markers;
    double r = 1.0;
    for (int k = 0; k < modes; ++k) r += amp * a[k] / sum * std::cos((k + 2) * th + ph[k]);
    p.x.push_back(cx + R * r * std::cos(th));
    p.y.push_back(cy + R * r * std::sin(th));
  }
  return p;
}
}  // namespace

TEST(Randomized, BandAndInteriorMatchBruteForce) {
  const int n = 64;
  Lcg u{12345};
  int wedge = 0, capsule = 0, fallback = 0;
  for (int trial = 0; trial < 80; ++trial) {
    const auto p = star(u, n * u(), n * u());
    IndexField f(geometry::Domain{Grid{n, n}, true, true}, {Method::flood_fill, 2.0});
    const FillReport& r = f.update(std::vector<geometry::Polygon>{p});
    wedge += r.wedge_cells;
    capsule += 1 - r.wedge_cells;
    fallback += r.fallback_cells;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        double best = 1e300;
        for (int ky = -1; ky <= 1; ++ky)
          for (int kx = -1; kx <= 1; ++kx) {
            const double d = signed_distance(p, i + 0.5 + kx * n, j + 0.5 + ky * n);
            if (std::abs(d) < std::abs(best)) best = d;
          }
        const double expect = std::abs(best) < 2.0 ? smoothed_heaviside(best) : (best < 0 ? 0.0 : 1.0);
        ASSERT_NEAR(f.values()[j * n + i], expect, 1e-12) << "trial " << trial << " node " << i << " " << j;
      }
  }
  EXPECT_GT(wedge, 5);
  EXPECT_GT(capsule, 5);
  EXPECT_GT(fallback, 0);
}
