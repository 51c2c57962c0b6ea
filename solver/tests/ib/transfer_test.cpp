// Spreading and interpolation (docs/model.md §2, thesis eqs 23–25): conservation of force
// and torque, adjointness, reproduction of constant and linear fields, periodic wrap
// and the documented loss of partition of unity at a wall (geometry/domain.hpp).
#include "ib/transfer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "ib/kernel.hpp"
#include "transfer_reference.hpp"

using namespace erythro;
using namespace erythro::ib;
using geometry::Domain;

namespace {
constexpr double kRoundOff = 1e-13;  // relative: sums of O(100) products of O(1) numbers

struct Markers {
  std::vector<double> X, Y, Fx, Fy;
};

// n markers uniformly in [lo, hi)², forces uniform in [−1, 1).
Markers random_markers(int n, double lo, double hi, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(lo, hi), force(-1.0, 1.0);
  Markers m;
  for (int k = 0; k < n; ++k) {
    m.X.push_back(pos(rng));
    m.Y.push_back(pos(rng));
    m.Fx.push_back(force(rng));
    m.Fy.push_back(force(rng));
  }
  return m;
}

struct Field {
  std::vector<double> x, y;
  explicit Field(const Grid& g) : x(g.size(), 0.0), y(g.size(), 0.0) {}
};

double sum(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }
}  // namespace

TEST(Transfer, SpreadingConservesTotalForce) {
  // A 24 × 20 box, and a 3 × 2 box narrower than the 4-point support (it wraps onto itself).
  for (const Grid g : {Grid{24, 20}, Grid{3, 2}}) {
    const Domain d{g, true, true};
    const auto m = random_markers(50, -10.0, 40.0, 1);  // unwrapped, across periodic sides
    for (KernelType t : kAllKernels) {
      Transfer tr(t, d);
      Field f(d.grid);
      tr.spread(m.X, m.Y, m.Fx, m.Fy, f.x, f.y);
      EXPECT_NEAR(sum(f.x), sum(m.Fx), kRoundOff * 50) << to_string(t);
      EXPECT_NEAR(sum(f.y), sum(m.Fy), kRoundOff * 50) << to_string(t);
    }
  }
}

TEST(Transfer, SpreadingConservesTorqueWithFirstMoment) {
  // Markers well inside a 40² box so no support wraps; torque about an arbitrary point P.
  const Domain d{Grid{40, 40}, true, true};
  const auto m = random_markers(60, 5.0, 35.0, 2);
  const double px = 13.37, py = -4.2;
  double torque_markers = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < m.X.size(); ++k) {
    torque_markers += (m.X[k] - px) * m.Fy[k] - (m.Y[k] - py) * m.Fx[k];
    scale += std::abs(m.Fx[k]) + std::abs(m.Fy[k]);
  }
  for (KernelType t : kAllKernels) {
    Transfer tr(t, d);
    Field f(d.grid);
    tr.spread(m.X, m.Y, m.Fx, m.Fy, f.x, f.y);
    double torque_grid = 0.0;
    for (int j = 0; j < d.grid.ny; ++j)
      for (int i = 0; i < d.grid.nx; ++i) {
        const auto n = d.grid.index(i, j);
        torque_grid += (i + 0.5 - px) * f.y[n] - (j + 0.5 - py) * f.x[n];
      }
    const double defect = std::abs(torque_grid - torque_markers);
    if (t == KernelType::cosine4) {
      // No first moment: each marker's force acts off its position by ≤ 0.0211 h per axis.
      EXPECT_LE(defect, 0.0210882 * scale);
      EXPECT_GT(defect, 1e-6 * scale) << "the cosine kernel should show its first-moment defect";
    } else {
      EXPECT_LE(defect, kRoundOff * 50 * scale) << to_string(t);
    }
  }
}

TEST(Transfer, SpreadAndInterpolateAreAdjoint) {
  // ⟨S F, u⟩ = ⟨F, J u⟩ (h = 1): the same weights both ways, only summation order differs.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  for (bool periodic : {true, false}) {
    const Domain d{Grid{30, 22}, periodic, periodic};
    const auto m = random_markers(80, periodic ? -15.0 : 0.2, periodic ? 45.0 : 21.8, 4);
    Field u(d.grid);
    for (auto& v : u.x) v = val(rng);
    for (auto& v : u.y) v = val(rng);
    for (KernelType t : kAllKernels) {
      Transfer tr(t, d);
      Field f(d.grid);
      tr.spread(m.X, m.Y, m.Fx, m.Fy, f.x, f.y);
      std::vector<double> Ux(m.X.size()), Uy(m.X.size());
      tr.interpolate(m.X, m.Y, u.x, u.y, Ux, Uy);
      double grid_side = 0.0, marker_side = 0.0, scale = 0.0;
      for (std::size_t n = 0; n < d.grid.size(); ++n) grid_side += f.x[n] * u.x[n] + f.y[n] * u.y[n];
      for (std::size_t k = 0; k < m.X.size(); ++k) {
        marker_side += m.Fx[k] * Ux[k] + m.Fy[k] * Uy[k];
        scale += std::abs(m.Fx[k] * Ux[k]) + std::abs(m.Fy[k] * Uy[k]);
      }
      EXPECT_NEAR(grid_side, marker_side, kRoundOff * scale) << to_string(t) << " periodic=" << periodic;
    }
  }
}

TEST(Transfer, InterpolationReproducesConstantAndLinearFields) {
  // Walled 40² box, markers ≥ 3 nodes from the walls (no support crosses a wall).
  const Domain d{Grid{40, 40}, false, false};
  const auto m = random_markers(200, 3.0, 37.0, 5);
  const double a = 0.3, b = 0.02, c = -0.015;  // u = a + b x + c y, v = −a + c x − b y
  Field u(d.grid);
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 40; ++i) {
      const double x = i + 0.5, y = j + 0.5;
      u.x[d.grid.index(i, j)] = a + b * x + c * y;
      u.y[d.grid.index(i, j)] = -a + c * x - b * y;
    }
  Field one(d.grid);
  std::fill(one.x.begin(), one.x.end(), 1.0);
  std::fill(one.y.begin(), one.y.end(), -2.0);
  for (KernelType t : kAllKernels) {
    Transfer tr(t, d);
    std::vector<double> Ux(m.X.size()), Uy(m.X.size());
    tr.interpolate(m.X, m.Y, one.x, one.y, Ux, Uy);
    for (std::size_t k = 0; k < m.X.size(); ++k) {
      EXPECT_NEAR(Ux[k], 1.0, 1e-14) << to_string(t);
      EXPECT_NEAR(Uy[k], -2.0, 2e-14) << to_string(t);
    }
    tr.interpolate(m.X, m.Y, u.x, u.y, Ux, Uy);
    double worst = 0.0;
    for (std::size_t k = 0; k < m.X.size(); ++k) {
      worst = std::max(worst, std::abs(Ux[k] - (a + b * m.X[k] + c * m.Y[k])));
      worst = std::max(worst, std::abs(Uy[k] - (-a + c * m.X[k] - b * m.Y[k])));
    }
    if (t == KernelType::cosine4) {
      // Error = gradient · first-moment defect: ≤ 0.0211 (|b| + |c|) per component.
      EXPECT_LE(worst, 0.0210882 * (std::abs(b) + std::abs(c)) * (1 + 1e-9));
      EXPECT_GT(worst, 1e-5 * (std::abs(b) + std::abs(c)));
    } else {
      EXPECT_LE(worst, 1e-14) << to_string(t);
    }
  }
}

TEST(Transfer, PeriodicWrapIsExact) {
  const Domain d{Grid{16, 12}, true, true};
  for (KernelType t : kAllKernels) {
    Transfer tr(t, d);
    Field f1(d.grid), f2(d.grid);
    const std::vector<double> X1{0.3}, Y1{11.9}, X2{0.3 + 16 * 3}, Y2{11.9 - 12 * 2}, F{1.0}, G{-0.5};
    tr.spread(X1, Y1, F, G, f1.x, f1.y);
    tr.spread(X2, Y2, F, G, f2.x, f2.y);
    // Equal up to the round-off of the shifted coordinate (48.3 is not 0.3 + 48 in binary).
    for (std::size_t n = 0; n < d.grid.size(); ++n) {
      EXPECT_NEAR(f1.x[n], f2.x[n], 1e-14) << to_string(t);
      EXPECT_NEAR(f1.y[n], f2.y[n], 1e-14) << to_string(t);
    }
    // The support of a marker at x = 0.3 reaches the last column across the side.
    double last_column = 0.0;
    for (int j = 0; j < 12; ++j) last_column += f1.x[d.grid.index(15, j)];
    EXPECT_NEAR(last_column, phi(t, 0.3 - (-0.5)), 1e-15) << to_string(t);
  }
}

TEST(Transfer, WallsDropSupportNodesAndBreakPartitionOfUnity) {
  // Walls at y = 0 and 10. A marker at Y = 0.7 has support rows starting at
  // ⌊0.7 + ½ − w/2⌋; rows below 0 do not exist and their weight is lost.
  const Domain d{Grid{16, 10}, true, false};
  for (KernelType t : kAllKernels) {
    Transfer tr(t, d);
    const int w = width(t);
    double dropped = 0.0;
    for (int j = support_start(0.7, w); j < 0; ++j) dropped += phi(t, 0.7 - (j + 0.5));
    Field f(d.grid);
    const std::vector<double> X{5.2}, Y{0.7}, F{1.0}, G{1.0};
    tr.spread(X, Y, F, G, f.x, f.y);
    EXPECT_NEAR(sum(f.x), 1.0 - dropped, 1e-15) << to_string(t);
    Field one(d.grid);
    std::fill(one.x.begin(), one.x.end(), 1.0);
    std::vector<double> Ux(1), Uy(1);
    tr.interpolate(X, Y, one.x, one.y, Ux, Uy);
    EXPECT_NEAR(Ux[0], 1.0 - dropped, 1e-15) << to_string(t);
    if (t != KernelType::linear2) EXPECT_GT(dropped, 0.01) << to_string(t);  // the hat kernel reaches only 1 node down
    else EXPECT_EQ(dropped, 0.0);
  }
}

TEST(Transfer, RejectsBadInput) {
  const Domain d{Grid{8, 8}, true, true};
  Transfer tr(KernelType::peskin4, d);
  Field f(d.grid);
  const std::vector<double> X{1.0, std::nan("")}, Y{1.0, 2.0}, F{0.0, 0.0};
  EXPECT_THROW(tr.spread(X, Y, F, F, f.x, f.y), std::domain_error);
  std::vector<double> small(10);
  EXPECT_THROW(tr.spread(Y, Y, F, F, small, small), std::invalid_argument);
}

// Many markers (the threads' path): the first non-finite marker is named, by spreading and by
// interpolation, both after a spread (its positions compared) and with no spread before.
TEST(Transfer, NamesTheFirstNonFiniteMarkerOfMany) {
  const Domain d{Grid{64, 64}, true, true};
  Field f(d.grid);
  const std::size_t M = 2000;
  std::vector<double> X(M), Y(M), F(M, 1.0), Ux(M), Uy(M);
  for (std::size_t m = 0; m < M; ++m) {
    X[m] = 0.031 * static_cast<double>(m);
    Y[m] = 0.017 * static_cast<double>(m);
  }
  auto message = [](auto&& call) -> std::string {
    try {
      call();
    } catch (const std::domain_error& e) {
      return e.what();
    }
    return "no error";
  };
  Transfer tr(KernelType::cosine4, d);
  tr.spread(X, Y, F, F, f.x, f.y);
  tr.interpolate(X, Y, f.x, f.y, Ux, Uy);  // the positions of the spread: its weights serve
  Y[1500] = std::numeric_limits<double>::infinity();
  X[1700] = std::nan("");
  EXPECT_NE(message([&] { tr.interpolate(X, Y, f.x, f.y, Ux, Uy); }).find("marker 1500 "), std::string::npos);
  EXPECT_NE(message([&] { tr.spread(X, Y, F, F, f.x, f.y); }).find("marker 1500 "), std::string::npos);
  Transfer fresh(KernelType::cosine4, d);  // no spread before: no positions to compare with
  EXPECT_NE(message([&] { fresh.interpolate(X, Y, f.x, f.y, Ux, Uy); }).find("marker 1500 "), std::string::npos);
  Y[1500] = 1.0;
  EXPECT_NE(message([&] { tr.interpolate(X, Y, f.x, f.y, Ux, Uy); }).find("marker 1700 "), std::string::npos);
}

// Interpolation as model.md eq 2.3 writes it, one marker at a time in the code's order (each
// row's sum over b from +0, then the rows from +0, a row beyond a wall left out): the kernel's
// path, whichever it takes (the four-wide supports inside their rows go through vector lanes,
// one row per lane), gives these bits exactly, near walls, across periodic sides and inside.
TEST(Transfer, InterpolationIsTheOrderedSumBitForBit) {
  for (const bool periodic_y : {false, true}) {
    const Domain d{Grid{20, 14}, true, periodic_y};
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    Field u(d.grid);
    for (std::size_t n = 0; n < d.grid.size(); ++n) {
      u.x[n] = value(rng);
      u.y[n] = value(rng);
    }
    // Inside, next to both walls (or across the periodic bottom and top) and across the sides.
    Markers m = random_markers(400, 0.0, 14.0, 11);
    for (double y : {0.05, 0.6, 1.3, 12.7, 13.4, 13.95}) {
      for (double x : {0.2, 7.3, 19.8}) {
        m.X.push_back(x);
        m.Y.push_back(y);
      }
    }
    for (KernelType t : kAllKernels) {
      Transfer tr(t, d);
      std::vector<double> Ux(m.X.size()), Uy(m.X.size());
      tr.interpolate(m.X, m.Y, u.x, u.y, Ux, Uy);
      for (std::size_t k = 0; k < m.X.size(); ++k) {
        double sx, sy;
        reference::interpolate_one(d, t, u.x, u.y, m.X[k], m.Y[k], sx, sy);
        EXPECT_EQ(Ux[k], sx) << to_string(t) << " marker " << k << " periodic_y " << periodic_y;
        EXPECT_EQ(Uy[k], sy) << to_string(t) << " marker " << k << " periodic_y " << periodic_y;
      }
    }
  }
}
