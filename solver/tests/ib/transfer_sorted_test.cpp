// Spreading and interpolation through the markers laid out by rows (ib/transfer.hpp): on a grid
// that stays in the cache and on one beyond it (where both ask for the cache lines ahead), with
// markers inside, next to the walls, across the periodic sides and wholly beyond a wall, the
// results are the ordered sums of docs/model.md eqs 2.2–2.3 (transfer_reference.hpp) bit for
// bit, after a spread (its weights serve again) and without one.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "ib/kernel.hpp"
#include "ib/transfer.hpp"
#include "transfer_reference.hpp"

using namespace erythro;
using namespace erythro::ib;
using geometry::Domain;

namespace {

struct Scene {
  Domain domain;
  std::vector<double> X, Y, Fx, Fy;  // the markers
  std::vector<double> ux, uy;        // a velocity field
  std::vector<double> fx, fy;        // a force field the spreading adds to
};

// n random markers over the grid, and markers on the rows next to the walls (or across the
// periodic bottom and top), across the periodic sides and (with walls) wholly beyond one.
Scene scene(Grid g, bool periodic_y, int n) {
  Scene s{Domain{g, true, periodic_y}, {}, {}, {}, {}, {}, {}, {}, {}};
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> x(0.0, g.nx), y(0.0, g.ny), unit(-1.0, 1.0);
  auto add = [&](double X, double Y) {
    s.X.push_back(X);
    s.Y.push_back(Y);
    s.Fx.push_back(unit(rng));
    s.Fy.push_back(unit(rng));
  };
  for (int k = 0; k < n; ++k) add(x(rng), y(rng));
  for (double Y : {0.05, 0.6, 1.3, g.ny - 1.3, g.ny - 0.6, g.ny - 0.05})
    for (double X : {0.2, 0.5 * g.nx + 0.3, g.nx - 0.2}) add(X, Y);
  if (!periodic_y)
    for (double Y : {-3.0, g.ny + 3.0}) add(0.5 * g.nx, Y);  // no row of the support on the grid
  for (auto* f : {&s.ux, &s.uy, &s.fx, &s.fy}) {
    f->resize(g.size());
    for (double& v : *f) v = unit(rng);
  }
  return s;
}

// A grid that stays in the cache, and one beyond 2^17 nodes (transfer.cpp's kPrefetchNodes).
const Grid kGrids[] = {Grid{20, 14}, Grid{520, 260}};

}  // namespace

TEST(TransferSorted, SpreadingIsTheOrderedSumBitForBit) {
  for (const Grid g : kGrids) {
    for (const bool periodic_y : {false, true}) {
      const Scene s = scene(g, periodic_y, g.size() > 1000 ? 3000 : 300);
      for (KernelType t : kAllKernels) {
        std::vector<double> fx = s.fx, fy = s.fy, rx = s.fx, ry = s.fy;
        Transfer tr(t, s.domain);
        tr.spread(s.X, s.Y, s.Fx, s.Fy, fx, fy);
        reference::spread_in_order(s.domain, t, s.X, s.Y, s.Fx, s.Fy, rx, ry);
        std::size_t differ = 0;
        for (std::size_t n = 0; n < g.size(); ++n) differ += fx[n] != rx[n] || fy[n] != ry[n];
        EXPECT_EQ(differ, 0u) << to_string(t) << " " << g.nx << "x" << g.ny << " periodic_y " << periodic_y;
      }
    }
  }
}

TEST(TransferSorted, InterpolationIsTheOrderedSumBitForBitAfterASpreadAndWithout) {
  for (const Grid g : kGrids) {
    for (const bool periodic_y : {false, true}) {
      const Scene s = scene(g, periodic_y, g.size() > 1000 ? 3000 : 300);
      for (KernelType t : kAllKernels) {
        for (const bool after_spread : {true, false}) {
          Transfer tr(t, s.domain);
          if (after_spread) {
            std::vector<double> fx = s.fx, fy = s.fy;
            tr.spread(s.X, s.Y, s.Fx, s.Fy, fx, fy);
          }
          const double unset = std::numeric_limits<double>::quiet_NaN();  // a marker left out shows
          std::vector<double> Ux(s.X.size(), unset), Uy(s.X.size(), unset);
          tr.interpolate(s.X, s.Y, s.ux, s.uy, Ux, Uy);
          std::size_t differ = 0;
          for (std::size_t k = 0; k < s.X.size(); ++k) {
            double ex, ey;
            reference::interpolate_one(s.domain, t, s.ux, s.uy, s.X[k], s.Y[k], ex, ey);
            differ += Ux[k] != ex || Uy[k] != ey;
          }
          EXPECT_EQ(differ, 0u) << to_string(t) << " " << g.nx << "x" << g.ny << " periodic_y " << periodic_y
                                << " after a spread " << after_spread;
          if (!periodic_y) {  // the last two markers have no row on the grid: no velocity, +0
            for (std::size_t k = s.X.size() - 2; k < s.X.size(); ++k) {
              EXPECT_EQ(Ux[k], 0.0) << to_string(t) << " marker " << k;
              EXPECT_EQ(Uy[k], 0.0) << to_string(t) << " marker " << k;
              EXPECT_FALSE(std::signbit(Ux[k]) || std::signbit(Uy[k])) << to_string(t) << " marker " << k;
            }
          }
        }
      }
    }
  }
}
