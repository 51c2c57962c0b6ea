// The force field cleared without being touched (fluid/force_rows.hpp): a cleared row is zeroed
// by the spreading right before it adds to the row, or at the start of the next step. Checked
// against a lattice whose field is zeroed at every clear, in the same cycles of the coupled
// step (clear, spread, step): the populations after each step, the field after it, and, between
// the clear and the step, everything the lattice reads from the field (moments, one node's
// moments, the checkpoint record) are the same bits, on one and on two threads.
#include "fluid/force_rows.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "common/state_record.hpp"
#include "fluid/fluid_lattice.hpp"
#include "geometry/domain.hpp"
#include "ib/transfer.hpp"

using namespace erythro;
using namespace erythro::fluid;

namespace {

const Grid kGrid{96, 80};  // large enough that the kernel and the zeroing fork threads

FluidLattice channel() {
  BoundaryConfig b;
  b.bottom.type = SideType::wall;
  b.top.type = SideType::moving_wall;
  b.top.ux = 0.03;
  FluidLattice lat(kGrid, {CollisionModel::bgk, 0.8, 0.25}, b);
  lat.set_uniform_force(1e-6, 0.0);
  return lat;
}

// Markers along a line through rows [y0, y1) with forces that vary per cycle.
struct Markers {
  std::vector<double> X, Y, Fx, Fy;
};
Markers markers_in_rows(double y0, double y1, int cycle) {
  Markers m;
  for (int k = 0; k < 60; ++k) {
    const double s = k / 60.0;
    m.X.push_back(5.0 + 85.0 * s);
    m.Y.push_back(y0 + (y1 - y0) * s);
    m.Fx.push_back(1e-4 * std::sin(3.0 * s + cycle));
    m.Fy.push_back(-1e-4 * std::cos(2.0 * s + cycle));
  }
  return m;
}

// Rows of the three cycles: a band, most of the channel (a later clear leaves more than 64
// rows to the step's zeroing, which then forks), a few rows.
const double kRows[][2] = {{10.0, 30.0}, {4.0, 76.0}, {40.0, 44.0}};

struct Outcome {
  std::vector<double> populations;
  std::vector<double> window;  // what was read between each clear and its step
  std::vector<double> field;   // the force field after the last step
};

// Three cycles of clear, spread, step. `zero_at_clear`: the reference, whose every cleared row
// is zeroed (and marked free of force) before the spreading, as an eager clear would.
Outcome run(bool zero_at_clear, int threads) {
  omp_set_num_threads(threads);
  FluidLattice lat = channel();
  ib::Transfer transfer(ib::KernelType::peskin4, geometry::Domain{kGrid, true, false});
  Outcome out;
  for (int cycle = 0; cycle < 3; ++cycle) {
    lat.clear_force_field();
    const FluidLattice::ForceRowsWriter w = lat.force_rows_writer();
    if (zero_at_clear) {
      for (int y = 0; y < kGrid.ny; ++y) {
        if (w.rows[static_cast<std::size_t>(y)] != force_row::kCleared) continue;
        for (int x = 0; x < kGrid.nx; ++x) w.fx[kGrid.index(x, y)] = w.fy[kGrid.index(x, y)] = 0.0;
        w.rows[static_cast<std::size_t>(y)] = force_row::kZero;
      }
    }
    const Markers m = markers_in_rows(kRows[cycle][0], kRows[cycle][1], cycle);
    transfer.spread(m.X, m.Y, m.Fx, m.Fy, w.fx, w.fy, w.rows);
    // Read between the clear and the step: rows the last cycle forced and this one did not.
    const Moments mo = lat.moments();
    out.window.insert(out.window.end(), mo.ux.begin(), mo.ux.end());
    out.window.insert(out.window.end(), mo.uy.begin(), mo.uy.end());
    double rho, ux, uy;
    lat.node_moments(50, 60, rho, ux, uy);  // forced in cycle 1, not in cycle 2
    out.window.insert(out.window.end(), {rho, ux, uy});
    StateRecord r;
    lat.save_state(r, "f.");
    for (const char* name : {"f.force_x", "f.force_y"}) {
      const std::vector<double>& f = r.get(name);
      out.window.insert(out.window.end(), f.begin(), f.end());
    }
    for (int s = 0; s < 3; ++s) lat.step();
  }
  out.populations.assign(lat.populations().begin(), lat.populations().end());
  const FluidLattice& read = lat;
  out.field.assign(read.force_x().begin(), read.force_x().end());
  out.field.insert(out.field.end(), read.force_y().begin(), read.force_y().end());
  return out;
}

std::size_t differing(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  std::size_t n = 0;
  for (std::size_t k = 0; k < a.size(); ++k) n += std::memcmp(&a[k], &b[k], sizeof(double)) != 0;
  return n;
}

}  // namespace

TEST(ForceRows, AClearedFieldReadsAndStepsAsAZeroedOneBitForBit) {
  const int before = omp_get_max_threads();
  const Outcome reference = run(true, 1);
  for (int threads : {1, 2}) {
    const Outcome lazy = run(false, threads);
    EXPECT_EQ(differing(lazy.populations, reference.populations), 0u) << threads << " threads";
    EXPECT_EQ(differing(lazy.window, reference.window), 0u) << threads << " threads";
    EXPECT_EQ(differing(lazy.field, reference.field), 0u) << threads << " threads";
  }
  omp_set_num_threads(before);
}

TEST(ForceRows, ClearingMarksRowsAndTheStepLeavesNoneCleared) {
  FluidLattice lat = channel();
  ib::Transfer transfer(ib::KernelType::peskin4, geometry::Domain{kGrid, true, false});
  for (int cycle = 0; cycle < 2; ++cycle) {
    lat.clear_force_field();
    const FluidLattice::ForceRowsWriter w = lat.force_rows_writer();
    const Markers m = markers_in_rows(kRows[cycle][0], kRows[cycle][1], cycle);
    transfer.spread(m.X, m.Y, m.Fx, m.Fy, w.fx, w.fy, w.rows);
    if (cycle == 1) {
      EXPECT_EQ(lat.force_row_state(0), force_row::kZero);     // never forced
      EXPECT_EQ(lat.force_row_state(20), force_row::kForced);  // forced again
      EXPECT_EQ(lat.force_row_state(60), force_row::kForced);  // newly forced
    }
    lat.step();
  }
  lat.clear_force_field();
  const FluidLattice::ForceRowsWriter w = lat.force_rows_writer();
  const Markers m = markers_in_rows(kRows[2][0], kRows[2][1], 2);
  transfer.spread(m.X, m.Y, m.Fx, m.Fy, w.fx, w.fy, w.rows);
  EXPECT_EQ(lat.force_row_state(42), force_row::kForced);
  EXPECT_EQ(lat.force_row_state(60), force_row::kCleared);  // forced last cycle, not written this one
  lat.step();
  for (int y = 0; y < kGrid.ny; ++y) EXPECT_NE(lat.force_row_state(y), force_row::kCleared) << "row " << y;
  const FluidLattice& read = lat;
  for (int x = 0; x < kGrid.nx; ++x) EXPECT_EQ(read.force_x()[kGrid.index(x, 60)], 0.0);
}
