// FluidLattice::span_moments, the moments of a stretch of one row (what the sparse immersed
// cells compute at their supports), against the whole-grid moments: the same bits at every node
// of the stretch and nothing written outside it; and the whole-grid moments against each node's
// own read (node_moments: slot by slot, the force through collision_force). In both layouts of
// the in-place lattice (after an even and an odd number of steps), on the rows along the walls
// and on stretches that take the edge columns, with a force field of which some rows hold force
// and the others are cleared.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "fluid/fluid_lattice.hpp"
#include "fluid/force_rows.hpp"

using namespace erythro;
using namespace erythro::fluid;

namespace {

const Grid kGrid{40, 24};
constexpr double kUntouched = 12345.0;  // what the arrays hold where span_moments must not write

FluidLattice channel_after(int steps) {
  BoundaryConfig b;
  b.bottom.type = SideType::wall;
  b.top.type = SideType::moving_wall;
  b.top.ux = 0.02;
  FluidLattice lat(kGrid, {CollisionModel::bgk, 0.9, 0.25}, b);
  lat.set_uniform_force(2e-6, -1e-6);
  std::vector<double> rho(kGrid.size()), ux(kGrid.size()), uy(kGrid.size());
  for (int y = 0; y < kGrid.ny; ++y) {
    for (int x = 0; x < kGrid.nx; ++x) {
      const std::size_t n = kGrid.index(x, y);
      rho[n] = 1.0 + 0.01 * std::sin(0.3 * x + 0.2 * y);
      ux[n] = 0.02 * std::cos(0.25 * y) + 0.005 * std::sin(0.4 * x);
      uy[n] = 0.01 * std::sin(0.15 * x + 0.1 * y);
    }
  }
  lat.initialize(rho, ux, uy);
  lat.enable_force_field();
  for (int s = 0; s < steps; ++s) {
    lat.clear_force_field();  // a force in every row, the steps' forces differing
    const FluidLattice::ForceRowsWriter w = lat.force_rows_writer();
    for (int y = 0; y < kGrid.ny; ++y) {
      w.rows[static_cast<std::size_t>(y)] = force_row::kForced;
      for (int x = 0; x < kGrid.nx; ++x) {
        w.fx[kGrid.index(x, y)] = 2e-5 * std::cos(0.2 * x + 0.3 * y + s);
        w.fy[kGrid.index(x, y)] = 1e-5 * std::sin(0.1 * x - 0.2 * y + s);
      }
    }
    lat.step();
  }
  // Force in rows 5 … 9 and row 0 (along the wall); every other row cleared: it still holds the
  // last step's force, which counts as zero.
  lat.clear_force_field();
  const FluidLattice::ForceRowsWriter w = lat.force_rows_writer();
  for (int y : {0, 5, 6, 7, 8, 9}) {
    w.rows[static_cast<std::size_t>(y)] = force_row::kForced;
    for (int x = 0; x < kGrid.nx; ++x) {
      w.fx[kGrid.index(x, y)] = 1e-4 * std::sin(0.5 * x + y);
      w.fy[kGrid.index(x, y)] = -1e-4 * std::cos(0.3 * x - y);
    }
  }
  return lat;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

void expect_spans_match_whole_grid(int steps) {
  const FluidLattice lat = channel_after(steps);
  const Moments whole = lat.moments();
  const int nx = kGrid.nx, ny = kGrid.ny;
  for (int j = 0; j < ny; ++j) {
    for (int x = 0; x < nx; ++x) {
      const std::size_t n = kGrid.index(x, j);
      double r = 0.0, u = 0.0, v = 0.0;
      lat.node_moments(x, j, r, u, v);
      ASSERT_TRUE(same_bits(r, whole.rho[n]) && same_bits(u, whole.ux[n]) && same_bits(v, whole.uy[n]))
          << "steps " << steps << ", node (" << x << ", " << j << ")";
    }
  }
  const int spans[][2] = {{0, nx}, {0, 1}, {nx - 1, nx}, {0, 5}, {3, 17}, {nx - 4, nx}, {7, 7}};
  for (int y : {0, 1, 6, ny / 2, ny - 2, ny - 1}) {
    for (const auto& span : spans) {
      std::vector<double> rho(kGrid.size(), kUntouched), ux(rho), uy(rho);
      lat.span_moments(y, span[0], span[1], rho, ux, uy);
      for (int j = 0; j < ny; ++j) {
        for (int x = 0; x < nx; ++x) {
          const std::size_t n = kGrid.index(x, j);
          const bool inside = j == y && x >= span[0] && x < span[1];
          const double want_rho = inside ? whole.rho[n] : kUntouched;
          const double want_ux = inside ? whole.ux[n] : kUntouched;
          const double want_uy = inside ? whole.uy[n] : kUntouched;
          ASSERT_TRUE(same_bits(rho[n], want_rho) && same_bits(ux[n], want_ux) && same_bits(uy[n], want_uy))
              << "steps " << steps << ", row " << y << ", span [" << span[0] << ", " << span[1] << "), node (" << x
              << ", " << j << ")";
        }
      }
    }
  }
}

}  // namespace

TEST(SpanMoments, EqualTheWholeGridMomentsInTheNaturalLayout) { expect_spans_match_whole_grid(4); }

TEST(SpanMoments, EqualTheWholeGridMomentsInTheStreamedLayout) { expect_spans_match_whole_grid(5); }
