// The calibration harness on synthetic problems with known answers (calibration.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "common/calibration.hpp"

using namespace erythro::vv;

namespace {

Curve sample(double t0, double t1, int n, const std::function<double(double)>& y) {
  Curve c;
  for (int k = 0; k < n; ++k) {
    const double t = t0 + (t1 - t0) * k / (n - 1);
    c.t.push_back(t);
    c.y.push_back(y(t));
  }
  return c;
}

}  // namespace

TEST(Calibration, InterpolationAndMisfit) {
  const Curve sim{{0.0, 1.0, 3.0}, {0.0, 2.0, 6.0}};  // y = 2t, piecewise linear
  EXPECT_DOUBLE_EQ(interpolate(sim, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(interpolate(sim, 2.0), 4.0);
  EXPECT_DOUBLE_EQ(interpolate(sim, 3.0), 6.0);
  EXPECT_THROW(interpolate(sim, 3.1), std::invalid_argument);
  const Curve ref{{0.5, 2.0}, {1.5, 4.0}};  // residuals −0.5, 0
  const Misfit m = curve_misfit(sim, ref);
  EXPECT_DOUBLE_EQ(m.max_abs, 0.5);
  EXPECT_DOUBLE_EQ(m.rms, std::sqrt(0.125));
}

TEST(Calibration, BrentFindsParabolaMinimum) {
  int evals = 0;
  bool ok = false;
  const double x = brent_minimize([](double v) { return (v - 0.3) * (v - 0.3) + 1.0; }, -2.0, 5.0, 1e-8, 100, &evals,
                                  &ok);
  EXPECT_NEAR(x, 0.3, 1e-7);
  EXPECT_TRUE(ok);
  EXPECT_LT(evals, 20);  // parabolic steps: exact on a parabola after a few points
}

TEST(Calibration, RecoversDecayTimeExactly) {
  // reference = model at p* = 2.5 on different (finer, offset) times than the model's
  const double p_true = 2.5;
  const Curve ref = sample(0.05, 9.95, 50, [&](double t) { return std::exp(-t / p_true); });
  const CurveModel model = [](const std::vector<double>& p) {
    return sample(0.0, 10.0, 2001, [&](double t) { return std::exp(-t / p[0]); });
  };
  for (MisfitNorm norm : {MisfitNorm::rms, MisfitNorm::max_abs}) {
    CalibrationOptions opt;
    opt.norm = norm;
    opt.x_tolerance = 1e-7;
    const auto r = calibrate_1d(model, ref, {"tau", 0.5, 10.0, 0.0}, opt);
    // the interpolation error of the model curve (Δt = 0.005) bounds the attainable fit
    EXPECT_NEAR(r.params[0], p_true, 1e-4);
    EXPECT_LT(r.misfit.max_abs, 1e-5);
    EXPECT_TRUE(r.converged);
    EXPECT_FALSE(r.at_bound[0]);
    EXPECT_LT(r.evaluations, 60);
    EXPECT_EQ(r.sensitivity_evaluations, 3);
  }
}

TEST(Calibration, MaxAndL2NormsHaveTheirOwnOptima) {
  // constant model y = p against reference {1, 2, 4}: L2 optimum = mean 7/3,
  // max-norm (Chebyshev) optimum = mid-range 5/2 with max residual 3/2.
  const Curve ref{{0.0, 1.0, 2.0}, {1.0, 2.0, 4.0}};
  const CurveModel model = [](const std::vector<double>& p) { return Curve{{0.0, 2.0}, {p[0], p[0]}}; };
  CalibrationOptions opt;
  opt.x_tolerance = 1e-9;
  opt.norm = MisfitNorm::rms;
  const auto l2 = calibrate_1d(model, ref, {"c", 0.0, 10.0, 0.0}, opt);
  EXPECT_NEAR(l2.params[0], 7.0 / 3.0, 1e-7);
  opt.norm = MisfitNorm::max_abs;
  const auto mx = calibrate_1d(model, ref, {"c", 0.0, 10.0, 0.0}, opt);
  EXPECT_NEAR(mx.params[0], 2.5, 1e-7);
  EXPECT_NEAR(mx.objective, 1.5, 1e-7);
}

TEST(Calibration, SensitivityOfALinearModelIsExact) {
  // y = p t at t_k = k (k = 1..4), reference 3t + (0.1, −0.1, 0.1, −0.1):
  // J_k = t_k, sensitivity_rms = √(Σ t²/4) = √7.5, max = 4;
  // least squares p* = 3 + Σ t_k ε_k / Σ t² = 3 − 0.2/30;
  // GN standard error = √(s²/Σt²), s² = SSR/(K − 1).
  const Curve ref{{1.0, 2.0, 3.0, 4.0}, {3.1, 5.9, 9.1, 11.9}};
  const CurveModel model = [](const std::vector<double>& p) { return Curve{{0.0, 5.0}, {0.0, 5.0 * p[0]}}; };
  CalibrationOptions opt;
  opt.x_tolerance = 1e-10;
  const auto r = calibrate_1d(model, ref, {"slope", 0.0, 10.0, 0.0}, opt);
  const double p_star = 3.0 - 0.2 / 30.0;
  EXPECT_NEAR(r.params[0], p_star, 1e-8);
  EXPECT_NEAR(r.sensitivity_rms[0], std::sqrt(7.5), 1e-9);
  EXPECT_NEAR(r.sensitivity_max[0], 4.0, 1e-9);
  double ssr = 0.0;
  for (int k = 1; k <= 4; ++k) ssr += std::pow(p_star * k - ref.y[static_cast<std::size_t>(k - 1)], 2);
  EXPECT_NEAR(r.gn_standard_error[0], std::sqrt(ssr / 3.0 / 30.0), 1e-7);
  EXPECT_NEAR(r.width(0, 0.01), 0.01 / std::sqrt(7.5), 1e-9);
}

TEST(Calibration, OptimumOutsideBracketIsFlaggedAtBound) {
  const Curve ref = sample(0.0, 1.0, 11, [](double t) { return 5.0 * t; });
  const CurveModel model = [](const std::vector<double>& p) { return Curve{{0.0, 1.0}, {0.0, p[0]}}; };
  const auto r = calibrate_1d(model, ref, {"slope", 0.0, 2.0, 0.0});
  EXPECT_NEAR(r.params[0], 2.0, 1e-3);
  EXPECT_TRUE(r.at_bound[0]);
}

TEST(Calibration, NelderMeadRecoversTwoParameters) {
  // y = A exp(−t/τ): (A, τ) = (2, 0.7) from (1, 2).
  const Curve ref = sample(0.0, 3.0, 40, [](double t) { return 2.0 * std::exp(-t / 0.7); });
  const CurveModel model = [](const std::vector<double>& p) {
    return sample(0.0, 3.0, 40, [&](double t) { return p[0] * std::exp(-t / p[1]); });
  };
  CalibrationOptions opt;
  opt.x_tolerance = 1e-8;
  opt.max_evaluations = 2000;
  const auto r = calibrate(model, ref, {{"A", 0.1, 5.0, 1.0}, {"tau", 0.1, 3.0, 2.0}}, opt);
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.params[0], 2.0, 1e-5);
  EXPECT_NEAR(r.params[1], 0.7, 1e-5);
  EXPECT_LT(r.misfit.rms, 1e-6);
  ASSERT_EQ(r.jacobian.size(), 40u);
  // ∂y/∂A at t = 0 is 1, ∂y/∂τ at t = 0 is 0
  EXPECT_NEAR(r.jacobian[0][0], 1.0, 1e-6);
  EXPECT_NEAR(r.jacobian[0][1], 0.0, 1e-9);
}

TEST(Calibration, NelderMeadRespectsBounds) {
  // unconstrained optimum (A, τ) = (2, 0.7), but A ≤ 1.5: the fit sits on the bound.
  const Curve ref = sample(0.0, 3.0, 40, [](double t) { return 2.0 * std::exp(-t / 0.7); });
  const CurveModel model = [](const std::vector<double>& p) {
    return sample(0.0, 3.0, 40, [&](double t) { return p[0] * std::exp(-t / p[1]); });
  };
  CalibrationOptions opt;
  opt.max_evaluations = 2000;
  const auto r = calibrate(model, ref, {{"A", 0.1, 1.5, 1.0}, {"tau", 0.1, 3.0, 1.0}}, opt);
  EXPECT_LE(r.params[0], 1.5);
  EXPECT_TRUE(r.at_bound[0]);
  EXPECT_FALSE(r.at_bound[1]);
}

TEST(Calibration, RejectsBadInput) {
  const Curve ref{{0.0, 1.0}, {0.0, 1.0}};
  const CurveModel model = [](const std::vector<double>& p) { return Curve{{0.0, 0.5}, {0.0, p[0]}}; };
  EXPECT_THROW(calibrate_1d(model, ref, {"x", 1.0, 1.0, 0.0}), std::invalid_argument);
  // the simulated curve does not cover the reference times
  EXPECT_THROW(calibrate_1d(model, ref, {"x", 0.0, 1.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(calibrate(model, ref, {}), std::invalid_argument);
}

// Continuation (refine_1d) from a start near the optimum finds the same optimum as Brent, for
// both norms, in a few model runs; prefetching points changes nothing.
TEST(Calibration, RefineFromAGoodStartMatchesBrent) {
  const Curve ref = sample(0.05, 9.95, 50, [](double t) { return std::exp(-t / 2.5) + 0.01 * std::sin(3.0 * t); });
  int calls = 0;
  const CurveModel model = [&](const std::vector<double>& p) {
    ++calls;
    return sample(0.0, 10.0, 2001, [&](double t) { return std::exp(-t / p[0]); });
  };
  for (MisfitNorm norm : {MisfitNorm::rms, MisfitNorm::max_abs}) {
    CalibrationOptions opt;
    opt.norm = norm;
    opt.x_tolerance = 1e-6;
    opt.fd_relative_step = 1e-3;
    const auto brent = calibrate_1d(model, ref, {"tau", 0.5, 10.0, 0.0}, opt);
    calls = 0;
    std::vector<double> prefetched;
    opt.prefetch = [&](const std::vector<std::vector<double>>& ps) {
      for (const auto& p : ps) prefetched.push_back(p[0]);
    };
    const auto refined = refine_1d(model, ref, {"tau", 0.5, 10.0, 0.0}, brent.params[0] * 1.01, opt);
    EXPECT_NEAR(refined.params[0], brent.params[0], 2e-4 * brent.params[0]) << (norm == MisfitNorm::rms ? "rms" : "max");
    EXPECT_LE(refined.objective, brent.objective * (1.0 + 1e-6));
    EXPECT_TRUE(refined.converged);
    EXPECT_FALSE(refined.at_bound[0]);
    EXPECT_EQ(refined.evaluations, calls);
    // a start 1 % off is further than half the difference step: the pair is taken again there
    EXPECT_LE(calls, 8);
    EXPECT_EQ(prefetched.size(), 4u + static_cast<std::size_t>(refined.evaluations - 4));  // pairs + iterates
    ASSERT_EQ(refined.jacobian.size(), ref.t.size());
    EXPECT_GT(refined.sensitivity_rms[0], 0.0);
  }
}
