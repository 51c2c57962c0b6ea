// The IB cycle of membrane::ImmersedCells: bitwise reproducible across thread
// counts, advects a cell with a uniform flow and wraps it across periodic sides, and
// its support-node velocity (advance), or the velocity the step wrote for dense cells,
// equals the whole-grid moments bit for bit.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <vector>

#include "geometry/shapes.hpp"
#include "membrane/immersed_cells.hpp"

using namespace erythro;
using namespace erythro::membrane;
using namespace erythro::geometry;

namespace {
std::vector<double> run(int threads, double ux, int steps, double* centre_x = nullptr) {
  omp_set_num_threads(threads);
  fluid::FluidLattice lat(Grid{64, 64}, {fluid::CollisionModel::bgk, 0.8, 3.0 / 16}, fluid::BoundaryConfig{});
  lat.initialize_uniform(1.0, ux, 0.0);
  ImmersedCells cells(ib::KernelType::cosine4, lat);
  const Polygon rest = biconcave(60, 10.0);
  // Deformed start (stretched 10 %) so that forces and flow are non-trivial.
  cells.add_cell(transformed(ellipse(60, 11.0, 5.0), 1.0, 0.2, 58.0, 31.0), RestShape::from_polygon(rest),
                 {{TensionLawType::neo_hookean, 0.01}, 0.05, 0.02});
  for (int s = 0; s < steps; ++s) cells.advance(lat);
  if (centre_x) {
    const Polygon p = cells.polygon(0);
    double cy;
    centroid(p, *centre_x, cy);
  }
  std::vector<double> out(cells.marker_x().begin(), cells.marker_x().end());
  out.insert(out.end(), cells.marker_y().begin(), cells.marker_y().end());
  out.insert(out.end(), lat.populations().begin(), lat.populations().end());
  return out;
}
}  // namespace

TEST(ImmersedCells, BitwiseIdenticalAcrossThreadCounts) {
  const auto a = run(2, 0.0, 40), b = run(2, 0.0, 40), c = run(1, 0.0, 40);
  for (double v : a) ASSERT_TRUE(std::isfinite(v));
  EXPECT_EQ(a, b);
  EXPECT_EQ(a, c);
}

TEST(ImmersedCells, UniformFlowCarriesTheCellAcrossThePeriodicSide) {
  // Marker 0 starts near x = 58 + 11cos(0.2) ≈ 68.8 → wrapped into [0, 64) by the first step;
  // a uniform flow of 0.1 moves the cell by ≈ 0.1 per step.
  double cx = 0.0;
  const auto out = run(1, 0.1, 100, &cx);
  for (std::size_t m = 0; m < 60; ++m) EXPECT_LT(std::abs(out[m] - 32.0), 64.0);  // unwrapped only by the cell size
  EXPECT_GE(out[0], 0.0);
  EXPECT_LT(out[0], 64.0);
  const double travelled = cx + 64.0 - 58.0;  // the centroid crossed x = 64 once
  EXPECT_NEAR(travelled, 0.1 * 100, 0.5);
}

namespace {
// Marker positions and populations after `steps` IB cycles, either by advance() (velocity
// at the kernel-support nodes only, or written by the step when the supports are dense)
// or by the same cycle with the whole-grid moments. `dense`: a grid small enough that
// the cell's supports hold as many nodes as it has (ImmersedCells::dense_supports).
std::vector<double> cycle(bool whole_grid, const fluid::BoundaryConfig& bc, ib::KernelType kernel,
                          bool dense = false) {
  omp_set_num_threads(1);
  fluid::FluidLattice lat(dense ? Grid{64, 14} : Grid{64, 48}, {fluid::CollisionModel::bgk, 0.8, 3.0 / 16}, bc);
  lat.initialize_uniform(1.0, 0.05, 0.0);
  lat.set_uniform_force(1e-6, -2e-6);
  ImmersedCells cells(kernel, lat);
  // Straddles x = 64 (periodic wrap) and reaches within 1 of y = 0 (wall clipping).
  cells.add_cell(transformed(ellipse(60, 11.0, 5.0), 1.0, 0.2, 58.0, 6.5), RestShape::from_polygon(circle(60, 8.0)),
                 {{TensionLawType::skalak, 0.01, 2.0}, 0.05, 0.02});
  EXPECT_EQ(cells.dense_supports(), dense && ib::width(kernel) == 4) << ib::to_string(kernel);
  const std::size_t N = lat.grid().size();
  std::vector<double> rho(N), ux(N), uy(N);
  for (int s = 0; s < 30; ++s) {
    if (!whole_grid) {
      cells.advance(lat);
      continue;
    }
    cells.compute_forces();
    cells.spread_forces(lat);
    lat.step();
    lat.compute_moments(rho, ux, uy);
    cells.move_markers(ux, uy);
    cells.wrap_periodic();
  }
  std::vector<double> out(cells.marker_x().begin(), cells.marker_x().end());
  out.insert(out.end(), cells.marker_y().begin(), cells.marker_y().end());
  out.insert(out.end(), lat.populations().begin(), lat.populations().end());
  return out;
}

// advance() against the cycle with the whole-grid moments, for every kernel, periodic and
// between walls.
void expect_whole_grid_bits(bool dense) {
  fluid::BoundaryConfig walls;
  walls.bottom = {fluid::SideType::wall, 0.0, 0.0};
  walls.top = {fluid::SideType::wall, 0.0, 0.0};
  for (ib::KernelType k : ib::kAllKernels) {
    for (const fluid::BoundaryConfig& bc : {fluid::BoundaryConfig{}, walls}) {
      const auto a = cycle(false, bc, k, dense), b = cycle(true, bc, k, dense);
      for (double v : a) ASSERT_TRUE(std::isfinite(v));
      EXPECT_EQ(a, b) << ib::to_string(k);
    }
  }
}
}  // namespace

TEST(ImmersedCells, SupportVelocityEqualsWholeGridMomentsBitwise) { expect_whole_grid_bits(false); }

// Dense supports: the fluid step writes the velocity (FluidLattice::write_velocity_with_
// next_step, asked for by the spreading) and advance() takes it as it is. The same bits as
// the whole-grid moments after the step.
TEST(ImmersedCells, VelocityWrittenByTheStepEqualsWholeGridMomentsBitwise) { expect_whole_grid_bits(true); }
