// Case verification.ib_kernels (issue 4 §2).
//
// Requirement: each IB kernel meets the moment conditions it promises to round-off,
// and the thesis's cosine kernel's one missing condition (first moment) shows as
// its analytic defect, in the 1D sums, in torque conservation and in linear-field
// interpolation; spreading and interpolation are adjoint.
// Reference: Peskin 2002 (Acta Numerica 11:479) §6 moment conditions; thesis eq 24.
// The cosine kernel's sums (4 support nodes, d0 ∈ [1, 2)): Σφ = 1 and Σφ² = 3/8
// exactly, Σ(r − j)φ = d0 − 3/2 + [cos(πd0/2) + sin(πd0/2)]/2, whose extreme is
// ±[√((1 − 8/π²)/2) − (2/π) arccos(2√2/π)] = ±0.0210882.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "common/case_support.hpp"
#include "ib/kernel_moments.hpp"
#include "ib/transfer.hpp"

using namespace erythro;
using namespace erythro::ib;
using geometry::Domain;

namespace {
const double kCosineFirstMax = std::sqrt((1.0 - 8.0 / (std::numbers::pi * std::numbers::pi)) / 2.0) -
                               (2.0 / std::numbers::pi) * std::acos(2.0 * std::sqrt(2.0) / std::numbers::pi);
constexpr int kOffsets = 4000;

struct KernelFigures {
  double zeroth = 0, first = 0, squares_min = 1e9, squares_max = 0, even_odd = 0;
  double linear_interp = 0, torque = 0, adjoint = 0;
};

KernelFigures measure(KernelType t) {
  KernelFigures k;
  for (int i = 0; i < kOffsets; ++i) {
    const auto s = moment_sums(t, i / double(kOffsets));
    k.zeroth = std::max(k.zeroth, std::abs(s.zeroth - 1.0));
    k.first = std::max(k.first, std::abs(s.first));
    k.squares_min = std::min(k.squares_min, s.squares);
    k.squares_max = std::max(k.squares_max, s.squares);
    k.even_odd = std::max(k.even_odd, std::abs(s.even - s.odd));
  }
  // 2D: markers on a sweep of sub-grid offsets inside a walled 24² box (no wall in reach).
  const Domain d{Grid{24, 24}, false, false};
  Transfer tr(t, d);
  std::vector<double> X, Y, Fx, Fy;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> f(-1, 1);
  for (int i = 0; i < 400; ++i) {
    X.push_back(8.0 + i / 400.0);
    Y.push_back(12.0 + 0.37 * i / 400.0);
    Fx.push_back(f(rng));
    Fy.push_back(f(rng));
  }
  // Linear field u = x, v = y: interpolation error per unit gradient.
  std::vector<double> ux(d.grid.size()), uy(d.grid.size());
  for (int j = 0; j < 24; ++j)
    for (int i = 0; i < 24; ++i) {
      ux[d.grid.index(i, j)] = i + 0.5;
      uy[d.grid.index(i, j)] = j + 0.5;
    }
  std::vector<double> Ux(X.size()), Uy(X.size());
  tr.interpolate(X, Y, ux, uy, Ux, Uy);
  for (std::size_t m = 0; m < X.size(); ++m)
    k.linear_interp = std::max({k.linear_interp, std::abs(Ux[m] - X[m]), std::abs(Uy[m] - Y[m])});
  // Torque about (0, 0) and adjointness ⟨S F, u⟩ = ⟨F, J u⟩ with u = (x, y).
  std::vector<double> gx(d.grid.size(), 0.0), gy(d.grid.size(), 0.0);
  tr.spread(X, Y, Fx, Fy, gx, gy);
  double tg = 0, tm = 0, scale = 0, lhs = 0, rhs = 0, ascale = 0;
  for (int j = 0; j < 24; ++j)
    for (int i = 0; i < 24; ++i) {
      const auto n = d.grid.index(i, j);
      tg += (i + 0.5) * gy[n] - (j + 0.5) * gx[n];
      lhs += gx[n] * ux[n] + gy[n] * uy[n];
    }
  for (std::size_t m = 0; m < X.size(); ++m) {
    tm += X[m] * Fy[m] - Y[m] * Fx[m];
    scale += std::abs(Fx[m]) + std::abs(Fy[m]);
    rhs += Fx[m] * Ux[m] + Fy[m] * Uy[m];
    ascale += std::abs(Fx[m] * Ux[m]) + std::abs(Fy[m] * Uy[m]);
  }
  k.torque = std::abs(tg - tm) / scale;  // per unit force: an effective lever-arm error
  k.adjoint = std::abs(lhs - rhs) / ascale;
  return k;
}
}  // namespace

TEST(IbKernels, MomentsConservationAdjointness) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.ib_kernels", "ib");
  record.set_requirement(
      "Every kernel sums to one (defect <= 1e-14); peskin4, roma3 and linear2 have zero first moment and "
      "reproduce linear fields and conserve torque to round-off; the cosine kernel's first-moment defect, "
      "linear-interpolation error and torque lever-arm error equal the analytic 0.0210882 h; sums of squares "
      "are 3/8 (cosine4, peskin4) and 1/2 (roma3); spreading and interpolation are adjoint to 1e-14.");
  record.set_reference(
      "Peskin 2002, Acta Numerica 11:479, sec. 6 (moment conditions); thesis eq 24 (cosine kernel); analytic "
      "cosine first-moment extreme sqrt((1 - 8/pi^2)/2) - (2/pi) arccos(2 sqrt 2/pi).");
  record.set_parameter("offsets_1d", double(kOffsets));
  record.set_parameter("markers_2d", 400.0);
  const std::string roundoff = "sums of <= 16 products of O(1) numbers: a few ulps";
  for (KernelType t : kAllKernels) {
    const std::string name(to_string(t));
    const vv::Stopwatch run_clock;
    const KernelFigures k = measure(t);
    const double run_seconds = run_clock.seconds();
    record.add_run({{"kernel", name}, {"zeroth_defect", k.zeroth}, {"first_moment_max", k.first},
                    {"sum_squares_min", k.squares_min}, {"sum_squares_max", k.squares_max},
                    {"even_odd_defect", k.even_odd}, {"linear_interp_error", k.linear_interp},
                    {"torque_lever_error", k.torque}, {"adjoint_defect", k.adjoint}, {"wall_time_s", run_seconds}});
    EXPECT_TRUE(record.add_metric({"zeroth " + name, "max |sum phi - 1| over offsets", "", k.zeroth, 1e-14, 0.0,
                                   io::Comparison::at_most, roundoff}));
    EXPECT_TRUE(record.add_metric({"adjoint " + name, "|<SF,u> - <F,Ju>| / sum|F U|", "", k.adjoint, 1e-14, 0.0,
                                   io::Comparison::at_most, roundoff}));
    if (t == KernelType::cosine4) {
      const std::string why = "analytic extreme of the cosine kernel's first moment; the 2D sweep samples offsets "
                              "every 1/400 (1D every 1/4000), so the sampled maximum lies within 2e-5 (2D) or "
                              "2e-7 (1D) of it";
      EXPECT_TRUE(record.add_metric({"first_moment cosine4", "max |sum (r-j) phi| (1D)", "h", k.first,
                                     kCosineFirstMax, 2e-7, io::Comparison::absolute, why}));
      EXPECT_TRUE(record.add_metric({"linear_interp cosine4", "max interpolation error of u = x per unit gradient",
                                     "h", k.linear_interp, kCosineFirstMax, 2e-5, io::Comparison::absolute, why}));
      EXPECT_TRUE(record.add_metric({"torque cosine4", "|torque(grid) - torque(markers)| / sum|F| (lever-arm error)",
                                     "h", k.torque, kCosineFirstMax, kCosineFirstMax, io::Comparison::at_most,
                                     "each marker's torque is off by at most its force times the first-moment "
                                     "defect; random forces partly cancel, so only the bound is asserted"}));
    } else {
      EXPECT_TRUE(record.add_metric({"first_moment " + name, "max |sum (r-j) phi|", "h", k.first, 1e-14, 0.0,
                                     io::Comparison::at_most, roundoff}));
      EXPECT_TRUE(record.add_metric({"linear_interp " + name, "max interpolation error of u = x", "h",
                                     k.linear_interp, 1e-13, 0.0, io::Comparison::at_most,
                                     "round-off on coordinates of size 10"}));
      EXPECT_TRUE(record.add_metric({"torque " + name, "|torque(grid) - torque(markers)| / sum|F|", "h", k.torque,
                                     1e-13, 0.0, io::Comparison::at_most, "round-off on lever arms of size 10"}));
    }
    const double target = t == KernelType::roma3 ? 0.5 : 0.375;
    if (t != KernelType::linear2) {
      EXPECT_TRUE(record.add_metric({"sum_squares " + name, "max |sum phi^2 - C| over offsets", "",
                                     std::max(std::abs(k.squares_max - target), std::abs(k.squares_min - target)),
                                     1e-14, 0.0, io::Comparison::at_most, roundoff}));
    }
  }
  // Plot: first moment against offset for each kernel.
  for (KernelType t : kAllKernels) {
    io::Series s{"first_moment_" + std::string(to_string(t)), "First moment sum (r-j) phi(r-j)", "offset r / h",
                 "first moment / h", {}, {}, {}};
    for (int i = 0; i <= 100; ++i) {
      s.x.push_back(i / 100.0);
      s.y.push_back(moment_sums(t, i / 100.0).first);
    }
    record.add_series(s);
  }
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
